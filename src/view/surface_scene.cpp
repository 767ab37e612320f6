#include "pcsketch/view/surface_scene.h"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <string>

#include "pcsketch/core/assert.h"
#include "pcsketch/core/error.h"

namespace pcsketch::view {

struct SurfaceScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  /// Embree works in float; the scene is recentred on the box centre so that far-from-origin clouds keep precision.
  Vec3f centre = Vec3f::Zero();
  /// The geometry's buffers (x, y, z, radius per point; unit normal per point), owned by Embree, alive with `scene`.
  const float* vertices = nullptr;
  const float* normals = nullptr;
  std::size_t size = 0;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  RTCRay make_ray(const Vec3f& origin, const Vec3f& direction, float t_near, float t_far) const {
    RTCRay ray{};
    const Vec3f o = origin - centre;
    ray.org_x = o.x();
    ray.org_y = o.y();
    ray.org_z = o.z();
    ray.dir_x = direction.x();
    ray.dir_y = direction.y();
    ray.dir_z = direction.z();
    ray.tnear = std::max(t_near, 0.f);
    ray.tfar = t_far;
    ray.mask = std::numeric_limits<unsigned>::max();
    ray.time = 0.f;
    ray.flags = 0;
    return ray;
  }
};

namespace {

void check_device(RTCDevice device, const char* step) {
  const RTCError code = rtcGetDeviceError(device);
  if (code != RTC_ERROR_NONE)
    throw Error(std::string("surface scene: Embree failed in ") + step + " (error " + std::to_string(code) + ")");
}

/// Embree's build monitor, which several build threads may call at once: it passes on a report each time the build
/// has gone a twentieth further, one call at a time, and remembers a request to stop (Embree then abandons the
/// build) or an exception (which must not cross Embree's C frames).
class BuildMonitor {
 public:
  explicit BuildMonitor(const ProgressFn& progress) : progress_(progress) {}

  static bool call(void* self, double fraction) { return static_cast<BuildMonitor*>(self)->report(fraction); }

  /// After the build: throws what the callback threw, or Cancelled if it asked to stop.
  void rethrow() const {
    if (error_) std::rethrow_exception(error_);
    if (stopped_) throw Cancelled();
  }

 private:
  bool report(double fraction) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stopped_ || fraction < next_) return !stopped_;
    next_ = fraction + 0.05;
    try {
      stopped_ = !progress_(kStage, fraction);
    } catch (...) {
      error_ = std::current_exception();
      stopped_ = true;
    }
    return !stopped_;
  }

  static constexpr std::string_view kStage = "scene";
  const ProgressFn& progress_;
  std::mutex mutex_;
  double next_ = 0.05;
  bool stopped_ = false;
  std::exception_ptr error_;
};

}  // namespace

std::vector<float> local_spacing(const neighbourhood::Neighbourhoods& neighbourhoods, std::size_t kth) {
  PCS_ASSERT(kth >= 1, "local_spacing: kth counts from 1");
  const std::size_t n = neighbourhoods.size();
  std::vector<float> spacing(n, 0.f);
  if (neighbourhoods.k == 0) return spacing;
  const std::size_t j = std::min(kth, neighbourhoods.k) - 1;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) spacing[i] = neighbourhoods.distances_of(i)[j];
  });
  return spacing;
}

SurfaceScene::SurfaceScene(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                           const std::vector<float>& spacing, const SurfaceSceneOptions& options)
    : impl_(std::make_unique<Impl>()) {
  const std::size_t n = positions.size();
  if (normals.size() != n || spacing.size() != n)
    throw Error("surface scene: positions, normals and local spacing must have one entry per point");
  if (n > std::numeric_limits<unsigned>::max()) throw Error("surface scene: too many points for Embree");

  const ProgressReporter report(options.progress, "scene");
  report(0.0);
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw Error("surface scene: Embree device creation failed");
  impl_->scene = rtcNewScene(impl_->device);
  check_device(impl_->device, "scene creation");
  if (n == 0) {
    rtcCommitScene(impl_->scene);
    return;
  }

  impl_->centre = bounding_box(positions).center();
  RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_ORIENTED_DISC_POINT);
  auto* vertices = static_cast<float*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), n));
  auto* disc_normals = static_cast<float*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_NORMAL, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), n));
  check_device(impl_->device, "buffer allocation");
  // In parallel: the first writes to Embree's fresh buffers fault their pages in, which is most of this loop's time.
  const Vec3f centre = impl_->centre;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Vec3f p = positions[i] - centre;
      const Vec3f& nrm = normals[i];
      const float len = nrm.norm();
      // A point without a usable normal gets a zero radius: it keeps its index (primID = point) but is never hit.
      const bool usable = std::isfinite(len) && len > 1e-12f && std::isfinite(spacing[i]);
      const Vec3f unit = usable ? Vec3f(nrm / len) : Vec3f::UnitZ();
      vertices[4 * i + 0] = p.x();
      vertices[4 * i + 1] = p.y();
      vertices[4 * i + 2] = p.z();
      vertices[4 * i + 3] = usable ? options.disc_radius_factor * spacing[i] : 0.f;
      disc_normals[3 * i + 0] = unit.x();
      disc_normals[3 * i + 1] = unit.y();
      disc_normals[3 * i + 2] = unit.z();
    }
  });
  impl_->vertices = vertices;
  impl_->normals = disc_normals;
  impl_->size = n;
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(impl_->scene, geometry);
  rtcReleaseGeometry(geometry);
  BuildMonitor monitor(options.progress);
  if (options.progress) rtcSetSceneProgressMonitorFunction(impl_->scene, &BuildMonitor::call, &monitor);
  rtcCommitScene(impl_->scene);
  rtcSetSceneProgressMonitorFunction(impl_->scene, nullptr, nullptr);  // `monitor` goes out of scope
  monitor.rethrow();
  check_device(impl_->device, "scene build");
  report(1.0);
}

SurfaceScene::~SurfaceScene() = default;
SurfaceScene::SurfaceScene(SurfaceScene&&) noexcept = default;
SurfaceScene& SurfaceScene::operator=(SurfaceScene&&) noexcept = default;

std::optional<SurfaceHit> SurfaceScene::intersect(const Vec3f& origin, const Vec3f& direction, float t_near,
                                                  float t_far) const {
  if (!(t_far > t_near)) return std::nullopt;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rayhit{};
  rayhit.ray = impl_->make_ray(origin, direction, t_near, t_far);
  rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &rayhit);
  if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  const Vec3f normal(rayhit.hit.Ng_x, rayhit.hit.Ng_y, rayhit.hit.Ng_z);
  const float len = normal.norm();
  return SurfaceHit{rayhit.ray.tfar, rayhit.hit.primID, len > 0 ? Vec3f(normal / len) : Vec3f::UnitZ()};
}

bool SurfaceScene::occluded(const Vec3f& origin, const Vec3f& direction, float t_near, float t_far) const {
  if (!(t_far > t_near)) return false;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray = impl_->make_ray(origin, direction, t_near, t_far);
  rtcOccluded1(impl_->scene, &context, &ray);
  // Embree marks an occluded ray by setting tfar to -inf.
  return ray.tfar < 0.f;
}

std::size_t SurfaceScene::size() const { return impl_->size; }

SurfaceDisc SurfaceScene::disc(std::uint32_t point) const {
  PCS_ASSERT(point < impl_->size, "surface scene: disc index out of range");
  const float* v = impl_->vertices + 4 * static_cast<std::size_t>(point);
  const float* nrm = impl_->normals + 3 * static_cast<std::size_t>(point);
  return {Vec3f(v[0], v[1], v[2]) + impl_->centre, Vec3f(nrm[0], nrm[1], nrm[2]), v[3]};
}

}  // namespace pcsketch::view
