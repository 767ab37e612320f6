// What scanners deliver, through the whole pipeline: noisy spheres drawn as their circle without speckle, and stray
// points that neither move the frame nor get drawn.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "pcsketch/pipeline.h"
#include "support/analytic_shapes.h"
#include "support/scan_lines.h"

namespace pcsketch {
namespace {

/// Image position and radius (pixels) of the unit sphere's outline in the default orthographic view.
struct Circle {
  Vec2f centre;
  float radius;
  float distance(const Vec2f& p) const { return std::abs((p - centre).norm() - radius); }
};

Circle projected_unit_sphere(const Prepared& prepared, const view::CameraOptions& options) {
  const view::Camera camera = view::make_camera(prepared.cloud.positions, prepared.cloud.origin, options);
  return {camera.project(Vec3f::Zero()).head<2>(), camera.scale};
}

float length_px(const Stroke& s) {
  float total = 0;
  for (std::size_t i = 1; i < s.image_points.size(); ++i) total += (s.image_points[i] - s.image_points[i - 1]).norm();
  return total;
}

PointCloud unit_sphere(float noise_fraction, std::uint32_t seed) {
  const float sigma = noise_fraction * test::diagonal(test::sphere(1.f, {.n = 1000}));
  PointCloud cloud = test::sphere(1.f, {.n = 30000, .seed = seed, .noise_sigma = sigma});
  cloud.normals.clear();
  return cloud;
}

struct NoiseCase {
  float fraction;      ///< noise σ, fraction of the diagonal
  float tolerance_px;  ///< outline distance from the circle at 1024 px
};

class NoisySphereDrawing : public ::testing::TestWithParam<NoiseCase> {};

TEST_P(NoisySphereDrawing, OutlineOnTheCircleAndNoSpeckle) {
  const NoiseCase c = GetParam();
  const DrawOptions options;
  const Prepared prepared = prepare(unit_sphere(c.fraction, 3), options);
  const DrawResult r = draw_view(prepared, options.camera, options);
  const Circle circle = projected_unit_sphere(prepared, options.camera);
  std::size_t on = 0, vertices = 0;
  float circle_length = 0;
  for (const Stroke& s : r.drawing.strokes) {
    if (s.kind != LineKind::Contour || !s.visible) continue;
    std::size_t near = 0;
    for (const Vec2f& p : s.image_points) near += circle.distance(p) <= c.tolerance_px;
    on += near, vertices += s.image_points.size();
    // A stroke mostly off the circle is an interior contour: the sphere has none.
    if (2 * near < s.image_points.size())
      EXPECT_LE(length_px(s), 5.f) << "an interior contour of " << length_px(s) << " px";
    else
      circle_length += length_px(s);
  }
  ASSERT_GT(vertices, 0u);
  EXPECT_GE(static_cast<double>(on), 0.97 * static_cast<double>(vertices));
  EXPECT_GE(circle_length, 0.95f * 2.f * 3.14159265f * circle.radius);  // closed all round
}

INSTANTIATE_TEST_SUITE_P(TwoNoiseLevels, NoisySphereDrawing,
                         ::testing::Values(NoiseCase{0.001f, 2.f}, NoiseCase{0.003f, 4.f}));

struct OutlierCase {
  float fraction;
  std::size_t clump;
};

class SphereWithOutliers : public ::testing::TestWithParam<OutlierCase> {};

TEST_P(SphereWithOutliers, FrameAndOutlineAsWithoutThem) {
  const OutlierCase c = GetParam();
  const DrawOptions options;
  // 100k points: stray points within a few spacings of the surface cannot be told from it, and at this density that
  // shell is thin enough not to move the frame.
  PointCloud clean = test::sphere(1.f, {.n = 100000, .seed = 4});
  clean.normals.clear();
  PointCloud dirty = clean;
  test::add_outliers(dirty, c.fraction, c.clump);
  const Prepared reference = prepare(std::move(clean), options);
  const Prepared prepared = prepare(std::move(dirty), options);
  std::size_t left = 0;
  for (const std::uint32_t s : prepared.cloud.source_index) left += s == test::kOutlier;
  EXPECT_LE(static_cast<double>(left), 0.05 * c.fraction * 100000.0);
  EXPECT_EQ(prepared.surface.outliers.size() + prepared.cloud.size(), 100000u + std::lround(c.fraction * 100000.f));

  const Circle expected = projected_unit_sphere(reference, options.camera);
  const Circle framed = projected_unit_sphere(prepared, options.camera);
  EXPECT_NEAR(framed.radius, expected.radius, 0.01f * expected.radius);
  EXPECT_LE((framed.centre - expected.centre).norm(), 0.01f * expected.radius);

  const DrawResult r = draw_view(prepared, options.camera, options);
  std::size_t on = 0, vertices = 0;
  for (const Stroke& s : r.drawing.strokes) {
    if (s.kind != LineKind::Contour || !s.visible) continue;
    for (const Vec2f& p : s.image_points) on += framed.distance(p) <= 2.f;
    vertices += s.image_points.size();
  }
  ASSERT_GT(vertices, 0u);
  EXPECT_GE(static_cast<double>(on), 0.95 * static_cast<double>(vertices));
}

INSTANTIATE_TEST_SUITE_P(UniformAndClumps, SphereWithOutliers,
                         ::testing::Values(OutlierCase{0.01f, 1}, OutlierCase{0.02f, 20}));

/// Distance from q to the polyline of a stroke's image points, pixels.
float distance_to(const Stroke& s, const Vec2f& q) {
  float best = s.image_points.empty() ? 1e9f : (s.image_points[0] - q).norm();
  for (std::size_t i = 1; i < s.image_points.size(); ++i) {
    const Vec2f a = s.image_points[i - 1], ab = s.image_points[i] - a;
    const float t = ab.squaredNorm() > 0 ? std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.f, 1.f) : 0.f;
    best = std::min(best, (a + t * ab - q).norm());
  }
  return best;
}

/// Fraction of `circle` (sampled every degree) within `tolerance` px of a visible stroke of `kind`.
/// The fraction of the circle's degrees within `tolerance` of a visible stroke that `counts`.
template <class Counts>
double circle_covered_by(const Drawing& drawing, const Circle& circle, float tolerance, Counts&& counts) {
  std::size_t hit = 0;
  for (int degree = 0; degree < 360; ++degree) {
    const float t = static_cast<float>(degree) * 3.14159265f / 180.f;
    const Vec2f q = circle.centre + circle.radius * Vec2f(std::cos(t), std::sin(t));
    hit += std::any_of(drawing.strokes.begin(), drawing.strokes.end(), [&](const Stroke& s) {
      return counts(s) && s.visible && distance_to(s, q) <= tolerance;
    });
  }
  return static_cast<double>(hit) / 360.0;
}

double circle_covered(const Drawing& drawing, LineKind kind, const Circle& circle, float tolerance) {
  return circle_covered_by(drawing, circle, tolerance, [kind](const Stroke& s) { return s.kind == kind; });
}

TEST(OpenScan, BandsOfDensityAndAHole) {
  // A unit sphere of 60k points in bands of width 1/3 across the view at full and at a quarter density (4:1), with a
  // hole of 30° angular radius facing the camera (which looks along +z): its rim is a circle of radius 1/2.
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  const PointCloud sphere = test::sphere(1.f, {.n = 60000, .seed = 9});
  PointCloud cloud;
  for (const Vec3f& p : sphere.positions) {
    const bool sparse = static_cast<int>(std::floor(3.f * p.x())) % 2 != 0;
    if (-p.z() > std::cos(30.f * 3.14159265f / 180.f) || (sparse && u(rng) >= 0.25f)) continue;
    cloud.positions.push_back(p);
  }
  const DrawOptions options;
  const Prepared prepared = prepare(std::move(cloud), options);
  const DrawResult r = draw_view(prepared, options.camera, options);
  const Circle outline = projected_unit_sphere(prepared, options.camera);
  const Circle rim{outline.centre, 0.5f * outline.radius};
  // The outline closed across the sparse bands; the rim drawn as a boundary (within 2h, about 9 px here), not as a
  // contour.
  EXPECT_GE(circle_covered(r.drawing, LineKind::Contour, outline, 3.f), 0.95);
  EXPECT_GE(circle_covered(r.drawing, LineKind::Boundary, rim, 9.f), 0.80);  // 83% measured: gaps in the sparse bands
  EXPECT_LE(circle_covered(r.drawing, LineKind::Contour, rim, 9.f), 0.05);
  std::size_t vertices = 0, on_rim = 0;
  for (const Stroke& s : r.drawing.strokes)
    if (s.kind == LineKind::Boundary && s.visible)
      for (const Vec2f& p : s.image_points) ++vertices, on_rim += rim.distance(p) <= 9.f;
  EXPECT_GE(static_cast<double>(on_rim), 0.9 * static_cast<double>(vertices));
}

TEST(OpenScan, SparseHalfSphereSeenFromItsOpenSideIsClosed) {
  // The half of a sparse unit sphere (2,000 points) that faces the camera, as a scanner on that side records it:
  // its border is the circle of the view's outline. The border points of so sparse a scan leave gaps the boundary
  // tracer does not cross; the outline, free to run along a drawn border, closes the drawing there, and where both
  // run together the border is what is painted.
  PointCloud cloud;
  for (const Vec3f& p : test::sphere(1.f, {.n = 4000, .seed = 4}).positions)
    if (p.z() < 0) cloud.positions.push_back(p);
  const DrawOptions options;
  const Prepared prepared = prepare(std::move(cloud), options);
  const DrawResult r = draw_view(prepared, options.camera, options);
  const Circle outline = projected_unit_sphere(prepared, options.camera);
  const auto painted = [](const Stroke& s) {
    return !s.fused_into && (s.kind == LineKind::Contour || s.kind == LineKind::Boundary);
  };
  const float h_px = prepared.surface.spacing * outline.radius;  // about 13 px
  // Within h of the circle, a painted line all round (0.79 when no outline point could lie on a border), and it is
  // the border's line where the two run together.
  EXPECT_GE(circle_covered_by(r.drawing, outline, h_px, painted), 0.95);
  EXPECT_GE(circle_covered(r.drawing, LineKind::Boundary, outline, 2 * h_px), 0.9);
  // Without border lines (--no-boundaries) the border is not drawn as an outline either.
  DrawOptions no_borders = options;
  no_borders.lines.boundaries = false;
  const DrawResult without = draw_view(prepared, options.camera, no_borders);
  EXPECT_LE(circle_covered_by(without.drawing, outline, h_px, painted), 0.2);
}


/// Visible contour and boundary strokes of a drawing of the unit sphere: how much of its circle they cover (within
/// `tolerance`), and their length in pixels off it.
struct SphereStrokes {
  double covered = 0;
  float off = 0;
};
SphereStrokes sphere_strokes(const Prepared& prepared, const DrawOptions& options, float tolerance) {
  const DrawResult r = draw_view(prepared, options.camera, options);
  const Circle circle = projected_unit_sphere(prepared, options.camera);
  const auto drawn = [](const Stroke& s) { return s.visible && (s.kind == LineKind::Contour || s.kind == LineKind::Boundary); };
  SphereStrokes out{circle_covered_by(r.drawing, circle, tolerance, drawn), 0.f};
  for (const Stroke& s : r.drawing.strokes)
    if (drawn(s))
      for (std::size_t i = 1; i < s.image_points.size(); ++i)
        if (circle.distance(s.image_points[i]) > tolerance)
          out.off += (s.image_points[i] - s.image_points[i - 1]).norm();
  return out;
}

TEST(ScanLines, SphereOnRingsIsDrawnAsItsCircle) {
  // 40 rings of latitude, 20 times denser along them than apart, seen from the side: drawn as they are, every ring is
  // a line across the disc; thinned to the rings' spacing, the drawing is the sphere's outline. The same with noise
  // of an eighth of the spacing, which the rings' own PCA no longer sees as lines.
  for (const float noise : {0.f, 0.125f}) {
    SCOPED_TRACE(noise);
    PointCloud cloud;
    cloud.positions = test::sphere_rings(40, 20.f, noise, 2);
    const DrawOptions options;
    const Prepared prepared = prepare(PointCloud(cloud), options);
    ASSERT_TRUE(prepared.surface.scan_lines.found());
    EXPECT_EQ(prepared.cloud.size() + prepared.surface.thinned.size(), cloud.size());
    EXPECT_LT(prepared.cloud.size(), cloud.size() / 4);
    const SphereStrokes thinned = sphere_strokes(prepared, options, 6.f);
    EXPECT_GE(thinned.covered, 0.9);
    DrawOptions keep = options;
    keep.surface.scan_lines.enabled = false;
    const SphereStrokes kept = sphere_strokes(prepare(std::move(cloud), keep), keep, 6.f);
    EXPECT_LT(thinned.off, 0.1f * kept.off) << thinned.off << " px off the circle, " << kept.off << " kept";
  }
}

TEST(ScanLines, SparseRingsKeepTheirOutline) {
  // 80 rings 4 and 6 times denser along them than apart, seen from the side. Drawn as they are, the outline broke
  // where it crosses the rings (a point's 16 nearest all lie on its own ring, so the outline test sees the gaps between
  // rings as empty); thinned to the rings' spacing, it goes all round.
  for (const float density : {4.f, 6.f}) {
    SCOPED_TRACE(density);
    PointCloud cloud;
    cloud.positions = test::sphere_rings(80, density);
    const DrawOptions options;
    const Prepared prepared = prepare(PointCloud(cloud), options);
    ASSERT_TRUE(prepared.surface.scan_lines.found());
    const SphereStrokes thinned = sphere_strokes(prepared, options, 6.f);
    EXPECT_GE(thinned.covered, 0.95);
    DrawOptions keep = options;
    keep.surface.scan_lines.enabled = false;
    const SphereStrokes kept = sphere_strokes(prepare(std::move(cloud), keep), keep, 6.f);
    EXPECT_LT(kept.covered, thinned.covered - 0.1) << kept.covered << " of the circle drawn from every point";
  }
}

}  // namespace
}  // namespace pcsketch
