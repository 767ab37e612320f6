// Drawing quality of whole drawings: every visible edge of a cube and of a notched box drawn once (the contour and
// the ridge along it fused, the JSON marking the copy), and shading that stays inside the object's silhouette.

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "pcsketch/io/read_cloud.h"
#include "pcsketch/io/sample_mesh.h"
#include "pcsketch/pipeline.h"
#include "pcsketch/render/json.h"
#include "support/analytic_shapes.h"
#include "support/mesh_ground_truth.h"

namespace pcsketch {
namespace {

bool drawn_line(const Stroke& s) { return s.visible && !s.fused_into && s.kind != LineKind::Hatch; }

/// Fraction of the drawn line samples (every px) that another drawn line stroke runs alongside: within `distance`
/// px of one of its segments and turned less than 30° from it.
double doubled_fraction(const Drawing& d, float distance) {
  std::size_t samples = 0, doubled = 0;
  for (std::size_t a = 0; a < d.strokes.size(); ++a) {
    if (!drawn_line(d.strokes[a])) continue;
    const std::vector<Vec2f>& pa = d.strokes[a].image_points;
    for (std::size_t i = 0; i + 1 < pa.size(); ++i) {
      const Vec2f dir = (pa[i + 1] - pa[i]).normalized();
      for (const Vec2f& p : test::sample_polyline({pa[i], pa[i + 1]}, false, 1.f)) {
        ++samples;
        bool alongside = false;
        for (std::size_t b = 0; b < d.strokes.size() && !alongside; ++b) {
          if (b == a || !drawn_line(d.strokes[b])) continue;
          const std::vector<Vec2f>& q = d.strokes[b].image_points;
          for (std::size_t k = 0; k + 1 < q.size() && !alongside; ++k) {
            const Vec2f e = q[k + 1] - q[k];
            const float t = std::clamp((p - q[k]).dot(e) / std::max(e.squaredNorm(), 1e-12f), 0.f, 1.f);
            alongside = (q[k] + t * e - p).norm() < distance && std::abs(e.normalized().dot(dir)) > std::cos(0.5236f);
          }
        }
        doubled += alongside;
      }
    }
  }
  return samples == 0 ? 1.0 : static_cast<double>(doubled) / static_cast<double>(samples);
}

/// Strokes the JSON marks fused, and whether every one of them points at a drawn stroke.
std::size_t fused_in_json(const Drawing& d, bool& targets_drawn) {
  const nlohmann::json j = render::to_json(d);
  std::size_t fused = 0;
  targets_drawn = true;
  for (const auto& p : j["polylines"]) {
    if (!p.contains("fused_into")) continue;
    ++fused;
    const auto& target = j["polylines"][p["fused_into"].get<std::size_t>()];
    targets_drawn = targets_drawn && !target.contains("fused_into") && target["visible"].get<bool>();
  }
  return fused;
}

void expect_each_edge_drawn_once(const Prepared& prepared, const view::CameraOptions& camera) {
  DrawOptions o;
  o.camera = camera;
  const float distance = o.fusion.distance_widths * o.thickness.rho_max;  // 6 px
  DrawOptions unfused = o;
  unfused.fusion.enabled = false;
  const Drawing before = draw_view(prepared, camera, unfused).drawing;
  const Drawing after = draw_view(prepared, camera, o).drawing;
  // Without fusion the rims are drawn twice (outline and ridge); with it, only where lines meet at corners.
  EXPECT_GT(doubled_fraction(before, distance), 0.2);
  EXPECT_LT(doubled_fraction(after, distance), 0.03);
  EXPECT_EQ(after.parameters["fusion"]["distance_widths"], o.fusion.distance_widths);  // recorded for reproduction
  EXPECT_EQ(after.parameters["finish"]["min_length_px"], o.finish.min_length_px);
  bool targets_drawn = false;
  EXPECT_GE(fused_in_json(after, targets_drawn), 3u);
  EXPECT_TRUE(targets_drawn);
  for (const Stroke& s : after.strokes) {
    if (s.fused_into) {
      EXPECT_EQ(after.strokes[*s.fused_into].kind, LineKind::Contour) << "a ridge wins over no contour";
    }
  }
}

TEST(Fusion, EachVisibleEdgeOfACubeIsDrawnOnce) {
  const Prepared p = prepare(test::cube(1.f, {.n = 20000}));
  expect_each_edge_drawn_once(p, {.direction = Vec3d(-1, -0.8, -0.6), .width = 512, .height = 512});
}

TEST(Fusion, EachVisibleEdgeOfANotchedBoxIsDrawnOnce) {
  const Prepared p = prepare(io::sample_mesh(test::notched_box(), {.n = 30000, .seed = 9}));
  expect_each_edge_drawn_once(p, {.direction = Vec3d(-0.4, 0.6, -1), .width = 512, .height = 512});
}

/// Shading pixels outside `mask` (#W·#H flags): region pixel centres (even-odd rule, as the renderers fill) and
/// hatch stroke samples every 0.25 px.
std::size_t shading_pixels_outside(const Drawing& d, const std::vector<std::uint8_t>& mask) {
  const int w = d.width, h = d.height;
  auto outside = [&](const Vec2f& p) {
    const int x = static_cast<int>(std::floor(p.x())), y = static_cast<int>(std::floor(p.y()));
    return x < 0 || y < 0 || x >= w || y >= h || !mask[static_cast<std::size_t>(y) * w + x];
  };
  std::size_t count = 0;
  for (const ShadeRegion& r : d.regions) {
    float x0 = 1e9f, x1 = -1e9f, y0 = 1e9f, y1 = -1e9f;
    for (const Vec2f& p : r.polygon) x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x()), y0 = std::min(y0, p.y()),
                                     y1 = std::max(y1, p.y());
    for (int y = static_cast<int>(y0); y <= static_cast<int>(y1); ++y)
      for (int x = static_cast<int>(x0); x <= static_cast<int>(x1); ++x) {
        const Vec2f c(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
        bool in = false;
        for (std::size_t k = 0, n = r.polygon.size(); k < n; ++k) {
          const Vec2f &a = r.polygon[k], &b = r.polygon[(k + 1) % n];
          if ((a.y() > c.y()) != (b.y() > c.y()) && c.x() < a.x() + (c.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
            in = !in;
        }
        count += in && outside(c);
      }
  }
  for (const Stroke& s : d.strokes)
    if (s.kind == LineKind::Hatch)
      for (const Vec2f& p : test::sample_polyline(s.image_points, s.closed, 0.25f)) count += outside(p);
  return count;
}

/// Shading pixels farther than `slack` px from every point's disc of half its scene radius (the surface the points
/// cover, without the discs' overhang past the outline).
std::size_t shading_outside_silhouette(const Prepared& prepared, const Drawing& d, const DrawOptions& o,
                                       const view::Camera& cam, float slack) {
  const int w = d.width, h = d.height;
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(w) * h, 0);
  for (std::size_t i = 0; i < prepared.cloud.size(); ++i) {
    const Vec3f uvd = cam.project(prepared.cloud.positions[i]);
    const float disc_px = o.shadow.splat_radius_factor * prepared.local_spacing[i] / cam.units_per_pixel(uvd.z());
    const float r = 0.5f * disc_px + slack;
    for (int y = std::max(0, static_cast<int>(uvd.y() - r)); y <= std::min(h - 1, static_cast<int>(uvd.y() + r)); ++y)
      for (int x = std::max(0, static_cast<int>(uvd.x() - r)); x <= std::min(w - 1, static_cast<int>(uvd.x() + r)); ++x)
        if (Vec2f(static_cast<float>(x) + 0.5f - uvd.x(), static_cast<float>(y) + 0.5f - uvd.y()).norm() <= r)
          mask[static_cast<std::size_t>(y) * w + x] = 1;
  }
  return shading_pixels_outside(d, mask);
}

/// Shading pixels (as above) farther than `slack` px from the mesh's filled silhouette.
std::size_t shading_outside_mesh(const Mesh& mesh, const Drawing& d, const view::Camera& cam, float slack) {
  const std::vector<std::uint8_t> covered = test::mesh_silhouette(mesh, cam);
  const int w = d.width, h = d.height, reach = static_cast<int>(std::ceil(slack));
  std::vector<std::uint8_t> mask(covered.size(), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!covered[static_cast<std::size_t>(y) * w + x]) continue;
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dx = -reach; dx <= reach; ++dx)
          if (static_cast<float>(dx * dx + dy * dy) <= slack * slack && x + dx >= 0 && y + dy >= 0 && x + dx < w &&
              y + dy < h)
            mask[static_cast<std::size_t>(y + dy) * w + x + dx] = 1;
    }
  return shading_pixels_outside(d, mask);
}

TEST(Fusion, FandiskShadingStaysInsideTheMeshSilhouette) {
  // The fandisk's own vertices as the cloud (sparse: 15–20 px apart), shading compared with its mesh's silhouette.
  const Mesh mesh = io::read_mesh(PCSKETCH_FIXTURES "/fandisk.off");
  PointCloud cloud;
  cloud.positions = mesh.vertices;
  const Prepared prepared = prepare(std::move(cloud));
  for (const Vec3d& direction : {Vec3d(1, 1, 1), Vec3d(-1, 0.3, -0.5)}) {
    const view::CameraOptions camera{.direction = direction};
    const Drawing d = draw_view(prepared, camera, {}).drawing;
    const view::Camera cam = view::make_camera(prepared.cloud.positions, prepared.cloud.origin, camera);
    // Within one pen width (ρ_max, 3 px) of the mesh. Before the silhouette clip: 209 and 799 pixels beyond that.
    EXPECT_EQ(shading_outside_mesh(mesh, d, cam, 3.f), 0u) << d.camera.dump();
  }
}

TEST(Fusion, BunnyShadingStaysInsideItsSilhouette) {
  io::ReadResult read = io::read_point_cloud(PCSKETCH_DATA "/bunny.ply");
  const DrawOptions o;
  const Prepared prepared = prepare(std::move(read.cloud), o);
  // The gallery's three-quarter view and two others. (This holds before the silhouette clip too: on the dense bunny
  // the discs barely overhang; the sparse fandisk above is where shading left the object.)
  const view::CameraOptions views[] = {{.azimuth_deg = -35.0, .elevation_deg = 15.0},
                                       {.direction = Vec3d(1, 1, 1)},
                                       {.azimuth_deg = 45.0, .elevation_deg = -20.0}};
  for (const view::CameraOptions& camera : views) {
    const Drawing d = draw_view(prepared, camera, o).drawing;
    const view::Camera cam = view::make_camera(prepared.cloud.positions, prepared.cloud.origin, camera);
    // Slack: the mask's 2 px cells reach 1.4 px past a disc, and a hatch stroke is 0.7 px wide.
    EXPECT_EQ(shading_outside_silhouette(prepared, d, o, cam, 2.f), 0u) << d.camera.dump();
  }
}

}  // namespace
}  // namespace pcsketch
