#include "pcsketch/io/sample_mesh.h"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pcsketch/core/error.h"

namespace pcsketch::io {
namespace {

/// SplitMix64: a small, fast generator whose stream is fully defined here (std distributions are not portable).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Standard normal (Box-Muller; one value per call keeps the stream simple).
  double gaussian() {
    const double u1 = 1.0 - uniform();  // (0, 1]: log is finite
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  std::uint64_t state_;
};

// Fixed chunk size: each chunk's generator depends only on (seed, chunk), so any thread count gives the same cloud.
constexpr std::size_t kChunk = 16384;

/// Appends options.outlier_fraction · n stray points (see SampleOptions), from a generator of their own.
void add_outliers(PointCloud& cloud, const Mesh& mesh, const SampleOptions& options) {
  const auto count = static_cast<std::size_t>(std::llround(options.outlier_fraction * static_cast<double>(options.n)));
  if (count == 0) return;
  const Box3f box = bounding_box(mesh.vertices);
  const double diagonal = box.diagonal();
  const Vec3d low = box.min.cast<double>() - Vec3d::Constant(0.1 * diagonal);
  const Vec3d extent = box.size().cast<double>() + Vec3d::Constant(0.2 * diagonal);
  Rng rng(options.seed ^ 0x6f75746c69657273ull);  // "outliers"
  Vec3d centre = Vec3d::Zero();
  for (std::size_t j = 0; j < count; ++j) {
    if (j % options.outlier_clump == 0)
      centre = low + Vec3d(rng.uniform(), rng.uniform(), rng.uniform()).cwiseProduct(extent);
    Vec3d p = centre;
    if (options.outlier_clump > 1) p += 0.002 * diagonal * Vec3d(rng.gaussian(), rng.gaussian(), rng.gaussian());
    cloud.positions.push_back(p.cast<float>());
    cloud.source_index.push_back(kOutlier);
    if (options.keep_normals) cloud.normals.push_back(Vec3f::UnitZ());
  }
}

}  // namespace

PointCloud sample_mesh(const Mesh& mesh, const SampleOptions& options) {
  if (options.n == 0) throw Error("sample_mesh: n must be at least 1");
  if (options.n > 0xffffffffull) throw Error("sample_mesh: n must be below 2^32");
  if (!(options.noise_sigma_factor >= 0.0)) throw Error("sample_mesh: noise sigma must be non-negative");
  if (!(options.outlier_fraction >= 0.0 && options.outlier_fraction <= 1.0))
    throw Error("sample_mesh: the outlier fraction must be in [0, 1]");
  if (options.outlier_clump == 0) throw Error("sample_mesh: outlier clumps need at least 1 point");
  const std::size_t nv = mesh.vertices.size();
  std::vector<double> cumulative(mesh.faces.size());
  double total = 0.0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (const std::uint32_t v : mesh.faces[f])
      if (v >= nv)
        throw Error("sample_mesh: face " + std::to_string(f) + " uses vertex " + std::to_string(v) + " of " +
                    std::to_string(nv));
    const auto& [a, b, c] = mesh.faces[f];
    const Vec3d ab = (mesh.vertices[b] - mesh.vertices[a]).cast<double>();
    const Vec3d ac = (mesh.vertices[c] - mesh.vertices[a]).cast<double>();
    total += 0.5 * ab.cross(ac).norm();
    cumulative[f] = total;
  }
  if (!(total > 0.0) || !std::isfinite(total)) throw Error("sample_mesh: the mesh has no face of positive area");
  const double sigma = options.noise_sigma_factor * static_cast<double>(bounding_box(mesh.vertices).diagonal());

  PointCloud cloud;
  cloud.origin = mesh.origin;
  cloud.positions.resize(options.n);
  cloud.source_index.resize(options.n);
  if (options.keep_normals) cloud.normals.resize(options.n);
  const std::size_t chunks = (options.n + kChunk - 1) / kChunk;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t chunk = range.begin(); chunk != range.end(); ++chunk) {
      Rng rng(options.seed * 0x2545f4914f6cdd1dull + chunk);
      rng.next();  // decorrelate neighbouring seeds
      const std::size_t end = std::min(options.n, (chunk + 1) * kChunk);
      for (std::size_t i = chunk * kChunk; i < end; ++i) {
        const double target = rng.uniform() * total;
        const std::size_t f = std::min<std::size_t>(
            std::upper_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin(), cumulative.size() - 1);
        const auto& [a, b, c] = mesh.faces[f];
        // Uniform barycentrics: u = 1 - sqrt(r1), v = r2 sqrt(r1) (Osada et al. 2002).
        const double s = std::sqrt(rng.uniform());
        const double r2 = rng.uniform();
        const Vec3d pa = mesh.vertices[a].cast<double>(), pb = mesh.vertices[b].cast<double>(),
                    pc = mesh.vertices[c].cast<double>();
        Vec3d p = (1.0 - s) * pa + s * (1.0 - r2) * pb + s * r2 * pc;
        if (sigma > 0.0) p += sigma * Vec3d(rng.gaussian(), rng.gaussian(), rng.gaussian());
        cloud.positions[i] = p.cast<float>();
        cloud.source_index[i] = static_cast<std::uint32_t>(f);
        if (options.keep_normals) cloud.normals[i] = (pb - pa).cross(pc - pa).normalized().cast<float>();
      }
    }
  });
  add_outliers(cloud, mesh, options);
  return cloud;
}

}  // namespace pcsketch::io
