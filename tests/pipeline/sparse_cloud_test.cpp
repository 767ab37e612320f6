// Sparse clouds (a few thousand points, as a coarse mesh's vertices or a quick scan): their surface bends a visible
// angle between neighbours, which must not be taken for noise. Scored against the exact contours of the mesh they
// were sampled from (tests/support/mesh_ground_truth.h).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pcsketch/differential/normals.h"
#include "pcsketch/differential/surface.h"
#include "pcsketch/io/read_cloud.h"
#include "pcsketch/io/sample_mesh.h"
#include "pcsketch/pipeline.h"
#include "support/mesh_ground_truth.h"

namespace pcsketch {
namespace {

/// Torus around z (tube radius r at distance R), a `u` × `v` grid of quads split in two.
Mesh torus_mesh(float R, float r, std::uint32_t u, std::uint32_t v) {
  Mesh mesh;
  const float two_pi = 2 * std::numbers::pi_v<float>;
  for (std::uint32_t i = 0; i < u; ++i)
    for (std::uint32_t j = 0; j < v; ++j) {
      const float a = two_pi * static_cast<float>(i) / static_cast<float>(u);
      const float b = two_pi * static_cast<float>(j) / static_cast<float>(v);
      mesh.vertices.emplace_back((R + r * std::cos(b)) * std::cos(a), (R + r * std::cos(b)) * std::sin(a),
                                 r * std::sin(b));
    }
  const auto at = [&](std::uint32_t i, std::uint32_t j) { return (i % u) * v + j % v; };
  for (std::uint32_t i = 0; i < u; ++i)
    for (std::uint32_t j = 0; j < v; ++j) {
      mesh.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return mesh;
}

PointCloud sampled_torus(std::size_t n) {
  PointCloud cloud = io::sample_mesh(torus_mesh(1.f, 0.35f, 192, 96), {.n = n, .seed = 7});
  cloud.normals.clear();
  return cloud;
}

// 1,500 points on a torus: the PCA normals of 8 neighbours spread by 0.09 rad from the bending alone, which the
// contours' persistence rule would take for noise; σ̂ finds no noise, so none is reported.
TEST(SparseCloud, BendingIsNotTakenForNormalNoise) {
  PointCloud cloud = sampled_torus(1500);
  const differential::Surface surface = differential::analyse_surface(cloud);
  EXPECT_GT(differential::normal_noise(cloud.normals, surface.neighbourhoods), 0.05f);
  EXPECT_LT(surface.normal_noise, 0.01f);
}

// Noise keeps its measured spread: σ = 0.3% of the diagonal, far above what the cap lets through.
TEST(SparseCloud, NoisyCloudsKeepTheirNormalNoise) {
  PointCloud cloud =
      io::sample_mesh(torus_mesh(1.f, 0.35f, 192, 96), {.n = 30000, .noise_sigma_factor = 0.003, .seed = 7});
  cloud.normals.clear();
  const differential::Surface surface = differential::analyse_surface(cloud);
  EXPECT_TRUE(surface.denoised);
  EXPECT_EQ(surface.normal_noise, differential::normal_noise(cloud.normals, surface.neighbourhoods));
}

// With 5 neighbours the noise is not estimated (a quadric needs 6 points): nothing separates noise from bending, and
// the measured spread stands.
TEST(SparseCloud, UnestimatedNoiseLeavesTheNormalNoiseAsMeasured) {
  PointCloud cloud =
      io::sample_mesh(torus_mesh(1.f, 0.35f, 192, 96), {.n = 30000, .noise_sigma_factor = 0.003, .seed = 7});
  cloud.normals.clear();
  differential::SurfaceOptions options;
  options.neighbourhood.k = 5;
  const differential::Surface surface = differential::analyse_surface(cloud, options);
  EXPECT_FALSE(surface.denoised);
  EXPECT_GT(surface.normal_noise, 0.f);
  EXPECT_EQ(surface.normal_noise, differential::normal_noise(cloud.normals, surface.neighbourhoods));
}

/// Contour precision and recall (3 px at 1024 px) of a drawing of `cloud` against the visible contours of `mesh`.
test::LineMatch contour_scores(PointCloud cloud, const Mesh& mesh, const Vec3d& direction, bool* denoised = nullptr) {
  DrawOptions options;
  options.camera.direction = direction;
  const Prepared prepared = prepare(std::move(cloud), options);
  if (denoised) *denoised = prepared.surface.denoised;
  const DrawResult result = draw_view(prepared, options.camera, options);
  const view::Camera camera = view::make_camera(prepared.cloud.positions, prepared.cloud.origin, options.camera);
  return test::match_lines(test::sample_visible_strokes(result.drawing, LineKind::Contour),
                           test::mesh_contours(mesh, camera).visible, 3.f);
}

// 3,000 points on a torus, 15 px apart at 1024 px: the rims, the hole's included, within 3 px of the mesh's.
TEST(SparseCloud, TorusContoursFollowTheMeshs) {
  const Mesh mesh = torus_mesh(1.f, 0.35f, 192, 96);
  for (const Vec3d& direction : {Vec3d(0, 1, 1.2), Vec3d(1, 0.4, 0.3), Vec3d(0.3, -0.6, 1)}) {
    const test::LineMatch m = contour_scores(sampled_torus(3000), mesh, direction);
    EXPECT_GE(m.precision, 0.9) << direction.transpose();
    EXPECT_GE(m.recall, 0.9) << direction.transpose();
  }
}

// A coarse mesh's vertices as the cloud (the paper's inputs): the shape's misfit between vertices 10–20 px apart
// reads as σ̂ ≈ 0.08 h on the elephant, below the denoising trigger, and the rims' normals' spread is not noise.
// Denoised, with the spread taken for noise, the elephant's contour recall was 0.31 and the camel's 0.76 (precision
// 0.64 and 0.89). The triceratops (a decimated mesh, 2,770 vertices, held out of every other rule) reads as
// σ̂ = 0.13 h with the two fit sizes, over the trigger; its misfit grows at 40 neighbours, so it is not noise
// (noise_share 0.66). Denoised, its contours scored P / R 0.60 / 0.44 (mean of 3 views, bench_scans).
// The femur (3,897 vertices, CGAL's demo data like the others) is rough at the scale of its vertices: σ̂ = 0.24 h,
// and its residual stays at 40 neighbours (noise_share 0.94), so by both tests it is noise; but moved by the
// denoising (0.32 h RMS), its outermost points were pushed out and its contours scored P / R 0.29 / 0.18 from this
// view. Under the trigger of 0.25 h (raised from 0.12 h) it is drawn raw: 0.69 / 0.50.
TEST(SparseCloud, CoarseMeshVerticesKeepTheirContours) {
  struct Case {
    const char* file;
    double precision, recall;
  };
  for (const Case& c : {Case{"elephant.off", 0.68, 0.53}, Case{"camel.off", 0.86, 0.78},
                        Case{"triceratops.off", 0.9, 0.72}, Case{"femur.off", 0.6, 0.45}}) {
    const std::string path = std::string(PCSKETCH_FIXTURES) + "/meshes/" + c.file;
    const Mesh mesh = io::read_mesh(path);
    PointCloud cloud = io::read_point_cloud(path).cloud;
    bool denoised = true;
    const test::LineMatch m = contour_scores(std::move(cloud), mesh, Vec3d(0, 0, 1), &denoised);
    EXPECT_FALSE(denoised) << c.file;
    EXPECT_GE(m.precision, c.precision) << c.file;
    EXPECT_GE(m.recall, c.recall) << c.file;
  }
}

// 8,000 samples of the camel with noise of 0.1% of the diagonal: σ̂ ≈ 0.2 h, under the trigger (0.25 h), so drawn
// raw. Denoised (the trigger was 0.12 h), the moves of a sparse cloud's points span pixels: mean P / R over the three
// views 0.84 / 0.58; raw 0.89 / 0.69 (seed 3). bench_scans -n 8000 at 0.1% gained on 8 of 10 models and lost on none.
TEST(SparseCloud, SparseNoisySamplesAreDrawnRaw) {
  const Mesh mesh = io::read_mesh(PCSKETCH_FIXTURES "/meshes/camel.off");
  PointCloud cloud = io::sample_mesh(mesh, {.n = 8000, .noise_sigma_factor = 0.001, .seed = 3});
  cloud.normals.clear();
  double precision = 0, recall = 0;
  for (const Vec3d& direction : {Vec3d(0, 0, 1), Vec3d(1, 0.15, 0.6), Vec3d(1, 1, 1)}) {
    bool denoised = true;
    const test::LineMatch m = contour_scores(cloud, mesh, direction, &denoised);
    EXPECT_FALSE(denoised) << direction.transpose();
    precision += m.precision / 3, recall += m.recall / 3;
  }
  EXPECT_GE(precision, 0.87);
  EXPECT_GE(recall, 0.66);
}

/// Contour precision and outline recall (3 px at 1024 px, against the mesh's filled silhouette's edge) of 5,000
/// samples of a fixture mesh, from one direction, with the outline's bridges of the given radius factor.
std::pair<double, double> outline_scores(const Mesh& mesh, const Vec3d& direction, float bridge_radius_factor) {
  PointCloud cloud = io::sample_mesh(mesh, {.n = 5000, .seed = 7});
  cloud.normals.clear();
  DrawOptions options;
  options.camera.direction = direction;
  options.view.contours.bridge_radius_factor = bridge_radius_factor;
  const Prepared prepared = prepare(std::move(cloud), options);
  const DrawResult result = draw_view(prepared, options.camera, options);
  const view::Camera camera = view::make_camera(prepared.cloud.positions, prepared.cloud.origin, options.camera);
  const std::vector<Vec2f> drawn = test::sample_visible_strokes(result.drawing, LineKind::Contour);
  return {test::match_lines(drawn, test::mesh_contours(mesh, camera).visible, 3.f).precision,
          test::match_lines(drawn, test::mesh_outline(mesh, camera), 3.f).recall};
}

// 5,000 samples (about 10 px apart at 1024 px): the gap test passes only every few rim points there, and the traced
// outline broke into pieces. The rolled disc bridges them. Measured over these 9 views, mean outline recall
// 0.755 → 0.780 (it rose in every view), mean contour precision 0.801 → 0.788 (a bridge cuts across a notch
// narrower than the disc).
TEST(SparseCloud, OutlineGapsAreBridged) {
  double recall_on = 0, recall_off = 0, precision_on = 0, precision_off = 0;
  for (const char* file : {"elephant.off", "camel.off", "triceratops.off"}) {
    const Mesh mesh = io::read_mesh(std::string(PCSKETCH_FIXTURES) + "/meshes/" + file);
    for (const Vec3d& direction : {Vec3d(0, 0, 1), Vec3d(1, 0.15, 0.6), Vec3d(1, 1, 1)}) {
      const auto [p_on, r_on] = outline_scores(mesh, direction, view::ContourOptions{}.bridge_radius_factor);
      const auto [p_off, r_off] = outline_scores(mesh, direction, 0.f);
      EXPECT_GE(r_on, r_off) << file << " " << direction.transpose();
      recall_on += r_on / 9, recall_off += r_off / 9, precision_on += p_on / 9, precision_off += p_off / 9;
    }
  }
  EXPECT_GE(recall_on, recall_off + 0.02);
  EXPECT_GE(precision_on, precision_off - 0.03);
}

}  // namespace
}  // namespace pcsketch
