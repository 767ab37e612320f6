// Known answers for the whole ridge/valley step: analytic shapes and meshes whose sharp edges are known.

#include "pcsketch/features/ridge_valley_lines.h"

#include <gtest/gtest.h>
#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "pcsketch/io/read_cloud.h"
#include "pcsketch/io/sample_mesh.h"
#include "support/analytic_shapes.h"
#include "support/mesh_ground_truth.h"

namespace pcsketch::features {
namespace {

using Segment = std::array<Vec3f, 2>;  // as test::SharpEdges holds them

float segment_distance(const Vec3f& p, const Vec3f& a, const Vec3f& b) {
  const Vec3f ab = b - a;
  const float len2 = ab.squaredNorm();
  const float t = len2 > 0.f ? std::clamp((p - a).dot(ab) / len2, 0.f, 1.f) : 0.f;
  return (p - (a + t * ab)).norm();
}

// Distance from p to a polyline (its segments, or its single vertex).
float polyline_distance(const Vec3f& p, const Polyline& line) {
  if (line.size() == 1) return (p - line.points[0]).norm();
  float best = std::numeric_limits<float>::max();
  const std::size_t segments = line.closed ? line.size() : line.size() - 1;
  for (std::size_t s = 0; s < segments; ++s)
    best = std::min(best, segment_distance(p, line.points[s], line.points[(s + 1) % line.size()]));
  return best;
}

std::vector<const Polyline*> of_kind(const std::vector<Polyline>& lines, LineKind kind) {
  std::vector<const Polyline*> out;
  for (const Polyline& l : lines)
    if (l.kind == kind) out.push_back(&l);
  return out;
}

// How well `lines` cover `edges`: each edge sampled every h/2; a sample is covered when a line passes within `tol`.
struct Coverage {
  double covered = 0, total = 0;       // length
  std::vector<double> edge_fraction;   // per edge
  std::vector<std::size_t> pieces;     // per edge: distinct lines covering some sample
  double fraction() const { return total > 0 ? covered / total : 1.0; }
};

Coverage coverage(const std::vector<Segment>& edges, const std::vector<const Polyline*>& lines, float h, float tol) {
  Coverage c;
  for (const Segment& e : edges) {
    const float length = (e[1] - e[0]).norm();
    const int samples = std::max(1, static_cast<int>(std::ceil(length / (0.5f * h))));
    int hit = 0;
    std::map<std::size_t, int> samples_of_line;
    for (int s = 0; s < samples; ++s) {
      const Vec3f p = e[0] + ((static_cast<float>(s) + 0.5f) / static_cast<float>(samples)) * (e[1] - e[0]);
      bool covered = false;
      for (std::size_t l = 0; l < lines.size(); ++l)
        if (polyline_distance(p, *lines[l]) <= tol) {
          covered = true;
          ++samples_of_line[l];
        }
      hit += covered;
    }
    const double fraction = static_cast<double>(hit) / samples;
    c.edge_fraction.push_back(fraction);
    // A piece runs along the edge for more than 4h (8 samples); the line of another edge ending at a shared corner
    // comes within tol of a few samples only.
    c.pieces.push_back(static_cast<std::size_t>(
        std::count_if(samples_of_line.begin(), samples_of_line.end(), [](const auto& kv) { return kv.second > 8; })));
    c.covered += fraction * length;
    c.total += length;
  }
  return c;
}

// Fraction of the vertices of `lines` within `tol` of some edge.
double precision(const std::vector<const Polyline*>& lines, const std::vector<Segment>& edges, float tol) {
  std::size_t near = 0, total = 0;
  for (const Polyline* l : lines)
    for (const Vec3f& p : l->points) {
      ++total;
      near += std::any_of(edges.begin(), edges.end(),
                          [&](const Segment& e) { return segment_distance(p, e[0], e[1]) <= tol; });
    }
  return total ? static_cast<double>(near) / static_cast<double>(total) : 1.0;
}

struct Analysed {
  PointCloud cloud;
  differential::Surface surface;
  RidgeValleyLines result;
};

// The surface analysis (with the cloud's normals, if it has them), then the three steps.
Analysed analyse(PointCloud cloud, const RidgeValleyOptions& options = {}) {
  Analysed r;
  r.surface = differential::analyse_surface(cloud);
  r.result = extract_ridge_valley_lines(cloud, r.surface, options);
  r.cloud = std::move(cloud);
  return r;
}

// The pipeline as a user runs it on a scan: normals estimated from the points, then the three steps.
Analysed run(PointCloud cloud, const RidgeValleyOptions& options = {}) {
  cloud.normals.clear();
  return analyse(std::move(cloud), options);
}

std::vector<Segment> cube_edges(float a) {
  std::vector<Segment> edges;
  for (int axis = 0; axis < 3; ++axis)
    for (float s : {-a, a})
      for (float t : {-a, a}) {
        Vec3f p, q;
        p[axis] = -a;
        q[axis] = a;
        p[(axis + 1) % 3] = q[(axis + 1) % 3] = s;
        p[(axis + 2) % 3] = q[(axis + 2) % 3] = t;
        edges.push_back({p, q});
      }
  return edges;
}

/// What a traced cube must show: every edge covered over `fraction` of its length within 2h, in at most `pieces`
/// lines, and `precise` of the ridge samples within 2h of an edge; no valley.
struct CubeExpectation {
  double fraction = 0.9;
  std::size_t pieces = 2;
  double precise = 0.95;
};

void expect_cube_edges_traced(const Analysed& r, float a, const CubeExpectation& expected = {}) {
  const float h = r.surface.spacing;
  const std::vector<Segment> edges = cube_edges(a);
  const auto ridges = of_kind(r.result.lines, LineKind::Ridge);
  EXPECT_TRUE(of_kind(r.result.lines, LineKind::Valley).empty());
  const Coverage c = coverage(edges, ridges, h, 2.f * h);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    EXPECT_GE(c.edge_fraction[e], expected.fraction) << "edge " << e;
    EXPECT_LE(c.pieces[e], expected.pieces) << "edge " << e;
  }
  EXPECT_GE(precision(ridges, edges, 2.f * h), expected.precise);
}

TEST(RidgeValleyLines, CubeEdgesAreRidges) {
  const Analysed r = run(test::cube(1.f, {.n = 30000, .seed = 42}));
  expect_cube_edges_traced(r, 1.f);
}

TEST(RidgeValleyLines, NoisyCubeEdgesAreRidges) {
  const float a = 1.f;
  const float sigma = 0.001f * 2.f * std::sqrt(3.f) * a;  // 0.1% of the diagonal
  const Analysed r = run(test::cube(a, {.n = 30000, .seed = 7, .noise_sigma = sigma}));
  // Denoised (the noise is about 0.3 h here): one edge of twelve now breaks into 3 pieces instead of 2.
  expect_cube_edges_traced(r, a, {.pieces = 3});
}

TEST(RidgeValleyLines, CubeEdgesAreRidgesUnderNoiseOfPointThreePercent) {
  const float a = 1.f;
  const float sigma = 0.003f * 2.f * std::sqrt(3.f) * a;  // 0.3% of the diagonal: about h at 30k points
  const Analysed r = run(test::cube(a, {.n = 30000, .seed = 8, .noise_sigma = sigma}));
  // Measured: every edge covered over 75–100% of its length (the weakest 0.75), 88% of the ridge samples on an edge.
  expect_cube_edges_traced(r, a, {.fraction = 0.7, .pieces = 4, .precise = 0.85});
}

TEST(RidgeValleyLines, NoisySphereAndTorusHaveNoLines) {
  for (const float fraction : {0.001f, 0.003f}) {
    SCOPED_TRACE("noise " + std::to_string(fraction) + " of the diagonal");
    const float sphere_sigma = fraction * test::diagonal(test::sphere(1.f, {.n = 1000}));
    const Analysed sphere = run(test::sphere(1.f, {.n = 20000, .seed = 5, .noise_sigma = sphere_sigma}));
    EXPECT_TRUE(sphere.result.lines.empty()) << sphere.result.lines.size() << " lines";
    const float torus_sigma = fraction * test::diagonal(test::torus(1.f, 0.3f, {.n = 1000}));
    const Analysed torus = run(test::torus(1.f, 0.3f, {.n = 20000, .seed = 6, .noise_sigma = torus_sigma}));
    EXPECT_TRUE(torus.result.lines.empty()) << torus.result.lines.size() << " lines";
  }
}

TEST(RidgeValleyLines, NoValleysBesideTheEdgesOfASparseCube) {
  // At 12k points with the exact face normals (as `draw` keeps them) the quadric fit next to a convex edge overshoots
  // into a weaker concave lobe 1–2h off the edge on the face, which passed every threshold of the Salient rule and
  // gave a short valley line (seed 42). Only the stronger convex edge beside it may win.
  for (const std::uint32_t seed : {42u, 3u, 11u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Analysed r = analyse(test::cube(1.f, {.n = 12000, .seed = seed}));
    const float h = r.surface.spacing;
    const auto ridges = of_kind(r.result.lines, LineKind::Ridge);
    EXPECT_TRUE(of_kind(r.result.lines, LineKind::Valley).empty());
    // The edges are still ridges (0.76–0.84 covered within 2h at this density; 0.77–0.86 before the fix).
    EXPECT_GE(coverage(cube_edges(1.f), ridges, h, 2.f * h).fraction(), 0.7);
  }
}

TEST(RidgeValleyLines, SameOutputForOneAndTwoThreads) {
  const PointCloud cloud = test::cube(1.f, {.n = 10000, .seed = 3, .noise_sigma = 0.003f});
  const auto with_threads = [&](std::size_t threads) {
    oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, threads);
    return run(cloud);
  };
  const Analysed one = with_threads(1);
  const Analysed two = with_threads(2);
  EXPECT_GE(one.result.lines.size(), 12u);  // something to compare: the cube's edges
  EXPECT_EQ(one.result.detection.labels, two.result.detection.labels);
  ASSERT_EQ(one.result.lines.size(), two.result.lines.size());
  for (std::size_t l = 0; l < one.result.lines.size(); ++l) {
    EXPECT_EQ(one.result.lines[l].points, two.result.lines[l].points);
    EXPECT_EQ(one.result.lines[l].point_index, two.result.lines[l].point_index);
  }
}

TEST(RidgeValleyLines, SphereAndCylinderHaveNoLines) {
  const Analysed sphere = run(test::sphere(1.f, {.n = 20000, .seed = 5}));
  EXPECT_TRUE(sphere.result.lines.empty()) << sphere.result.lines.size() << " lines";
  const Analysed cylinder = run(test::cylinder(1.f, 2.f, {.n = 20000, .seed = 6}));
  EXPECT_TRUE(cylinder.result.lines.empty()) << cylinder.result.lines.size() << " lines";
}

TEST(RidgeValleyLines, PaperRuleMarksEverySpherePoint) {
  // The plain relative rule has nothing to separate uniform curvature from an edge: what the Salient rule fixes.
  RidgeValleyOptions paper;
  paper.detection.rule = DetectionRule::Paper;
  const Analysed sphere = run(test::sphere(1.f, {.n = 5000, .seed = 5}), paper);
  EXPECT_GT(sphere.result.detection.ridge_points, 4500u);
}

TEST(RidgeValleyLines, NotchedBoxInnerEdgesAreValleysOuterEdgesRidges) {
  // Box [-1,1]×[-Y,Y]×[-0.6,0.6] with a notch x ∈ [-w,w], z ∈ [top-d, top] cut across the top face along y.
  const float Y = 0.8f, top = 0.6f, w = 0.3f, d = 0.4f, floor = top - d;
  const Mesh mesh = test::notched_box();
  const Analysed r = run(io::sample_mesh(mesh, {.n = 30000, .seed = 9}));
  const float h = r.surface.spacing;
  const std::vector<Segment> inner = {Segment{Vec3f(-w, -Y, floor), Vec3f(-w, Y, floor)},
                                      Segment{Vec3f(w, -Y, floor), Vec3f(w, Y, floor)}};
  const std::vector<Segment> rim = {Segment{Vec3f(-w, -Y, top), Vec3f(-w, Y, top)},
                                    Segment{Vec3f(w, -Y, top), Vec3f(w, Y, top)}};
  const auto valleys = of_kind(r.result.lines, LineKind::Valley);
  const auto ridges = of_kind(r.result.lines, LineKind::Ridge);
  const Coverage valley_cover = coverage(inner, valleys, h, 2.f * h);
  const Coverage rim_cover = coverage(rim, ridges, h, 2.f * h);
  EXPECT_GE(valley_cover.fraction(), 0.9);
  EXPECT_GE(rim_cover.fraction(), 0.9);
  // Inner edges are not ridges, rims are not valleys, and valley lines lie on the inner edges only.
  EXPECT_LT(coverage(inner, ridges, h, 2.f * h).fraction(), 0.1);
  EXPECT_LT(coverage(rim, valleys, h, 2.f * h).fraction(), 0.1);
  EXPECT_GE(precision(valleys, inner, 2.f * h), 0.95);
}

void expect_fandisk_edges(const Analysed& r, const test::SharpEdges& sharp, double min_convex, double min_concave) {
  const float h = r.surface.spacing;
  const Coverage convex = coverage(sharp.convex, of_kind(r.result.lines, LineKind::Ridge), h, 2.f * h);
  const Coverage concave = coverage(sharp.concave, of_kind(r.result.lines, LineKind::Valley), h, 2.f * h);
  EXPECT_GE(convex.fraction(), min_convex) << "convex sharp edges covered by ridges";
  EXPECT_GE(concave.fraction(), min_concave) << "concave sharp edges covered by valleys";
}

// Fandisk (tests/fixtures/fandisk.off, copied from the shared data set: a CAD part with sharp convex and concave
// edges and non-uniform vertex density).
TEST(RidgeValleyLines, FandiskSharpEdges) {
  const std::string path = std::string(PCSKETCH_FIXTURES) + "/fandisk.off";
  const Mesh mesh = io::read_mesh(path);
  const test::SharpEdges sharp = test::sharp_edges(mesh, 40.f);
  ASSERT_GT(sharp.convex.size(), 100u);
  ASSERT_GT(sharp.concave.size(), 20u);
  // The sample shares the mesh's origin, so mesh and cloud coordinates agree.
  expect_fandisk_edges(run(io::sample_mesh(mesh, {.n = 100000, .seed = 1})), sharp, 0.85, 0.85);
}

// Noisy fandisk (σ = 0.1% of the diagonal, 100k samples, so it is denoised): where a wide fit's support holds a
// crease, its points are fitted over their shared neighbours in the denoised copy, whose creases the bilateral filter
// kept sharp. Fitted on their own 512-point balls of the noisy points, as before, seed 3 gave ridge / valley
// precision 0.82 / 0.90 and coverage 0.92 / 0.89; now 0.98 / 0.99 and 0.94 / 0.97.
TEST(RidgeValleyLines, NoisyFandiskCreasesAreTracedOnTheirEdges) {
  const Mesh mesh = io::read_mesh(std::string(PCSKETCH_FIXTURES) + "/fandisk.off");
  const test::SharpEdges sharp = test::sharp_edges(mesh, 40.f);
  const Analysed r = run(io::sample_mesh(mesh, {.n = 100000, .noise_sigma_factor = 0.001, .seed = 3}));
  ASSERT_TRUE(r.surface.denoised);
  const float h = r.surface.spacing;
  const auto ridges = of_kind(r.result.lines, LineKind::Ridge);
  const auto valleys = of_kind(r.result.lines, LineKind::Valley);
  EXPECT_GE(precision(ridges, sharp.convex, 2.f * h), 0.95);
  EXPECT_GE(precision(valleys, sharp.concave, 2.f * h), 0.95);
  expect_fandisk_edges(r, sharp, 0.9, 0.9);
}

TEST(RidgeValleyLines, FandiskVertices) {
  const std::string path = std::string(PCSKETCH_FIXTURES) + "/fandisk.off";
  const Mesh mesh = io::read_mesh(path);
  io::ReadResult read = io::read_point_cloud(path);
  ASSERT_EQ(read.cloud.origin, mesh.origin);
  // The 6,475 non-uniform CAD vertices (large triangles between dense strips along the edges): 0.90 convex and 0.99
  // concave measured. Orientation across the sharp edges decides this: with Hoppe's |n_i·n_j| criterion a third of
  // the normals came out inward, their edges read with the wrong sign, and coverage fell to about 0.61.
  expect_fandisk_edges(run(std::move(read.cloud)), test::sharp_edges(mesh, 40.f), 0.85, 0.85);
}


// Orientation under noise of about h, over seeds (not the one seed a test was tuned on): with seed 3, pairs of
// points stacked along their normals by the noise made the reflect test flip two faces inward (11,207 of 30,000
// normals), their edges drawn as 11 valley lines and one edge not at all. Measured now: at most 2 normals inward,
// every edge covered over 0.66–0.91 of its length.
TEST(RidgeValleyLines, NoisyCubeFacesStayOutwardOverSeeds) {
  const float a = 1.f;
  const float sigma = 0.003f * 2.f * std::sqrt(3.f) * a;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Analysed r = run(test::cube(a, {.n = 30000, .seed = seed, .noise_sigma = sigma}));
    std::size_t inward = 0;
    for (std::size_t i = 0; i < r.cloud.size(); ++i) {
      const Vec3f& p = r.cloud.positions[i];
      Eigen::Index axis = 0;
      p.cwiseAbs().maxCoeff(&axis);
      inward += r.cloud.normals[i][axis] * p[axis] < 0;
    }
    EXPECT_LE(inward, r.cloud.size() / 1000);
    EXPECT_TRUE(of_kind(r.result.lines, LineKind::Valley).empty());
    const Coverage c = coverage(cube_edges(a), of_kind(r.result.lines, LineKind::Ridge), r.surface.spacing,
                                2.f * r.surface.spacing);
    for (std::size_t e = 0; e < c.edge_fraction.size(); ++e) EXPECT_GE(c.edge_fraction[e], 0.6) << "edge " << e;
  }
}

}  // namespace
}  // namespace pcsketch::features
