#include "pcsketch/features/ridge_valley_points.h"

#include <gtest/gtest.h>

#include "pcsketch/core/error.h"
#include "pcsketch/neighbourhood/kd_tree.h"

namespace pcsketch::features {
namespace {

// A flat grid z = 0, spacing 1, x in [0, 40), y in [0, 20), with a synthetic curvature profile k(x) across a crease
// along y at x = 20 (principal direction of k1 along x, of k2 along y).
struct Grid {
  std::vector<Vec3f> points;
  differential::Curvature curvature;
  neighbourhood::Neighbourhoods neighbourhoods;
};

template <typename Profile>
Grid grid(Profile k_of_x) {
  Grid g;
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 40; ++x) {
      g.points.emplace_back(static_cast<float>(x), static_cast<float>(y), 0.f);
      const float k = k_of_x(x);
      g.curvature.k1.push_back(std::max(k, 0.f));
      g.curvature.k2.push_back(std::min(k, 0.f));
      g.curvature.dir1.push_back(k >= 0.f ? Vec3f::UnitX() : Vec3f::UnitY());
      g.curvature.dir2.push_back(k >= 0.f ? Vec3f::UnitY() : Vec3f::UnitX());
    }
  const neighbourhood::KdTree tree(g.points);
  g.neighbourhoods = neighbourhood::compute_neighbourhoods(tree, g.points, {.k = 8});
  return g;
}

std::size_t count_at(const DetectionResult& r, const Grid& g, PointLabel label, int x) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < g.points.size(); ++i) n += r.labels[i] == label && g.points[i].x() == static_cast<float>(x);
  return n;
}

constexpr float kH = 1.f;

TEST(DetectRidgeValleyPoints, KIsThePrincipalCurvatureOfLargerMagnitude) {
  differential::Curvature c;
  c.k1 = {0.5f, 2.f};
  c.k2 = {-3.f, -1.f};
  c.dir1 = {Vec3f::UnitX(), Vec3f::UnitX()};
  c.dir2 = {Vec3f::UnitY(), Vec3f::UnitY()};
  EXPECT_EQ(feature_curvature(c, 0), -3.f);
  EXPECT_EQ(feature_direction(c, 0), Vec3f::UnitY());
  EXPECT_EQ(feature_curvature(c, 1), 2.f);
  EXPECT_EQ(feature_direction(c, 1), Vec3f::UnitX());
}

TEST(DetectRidgeValleyPoints, SalientRuleKeepsTheCrestOfARidge) {
  // A ridge profile peaking at x = 20 (k = 1 = 1/h), falling off over 3 points each side; flat elsewhere.
  const Grid g = grid([](int x) { return std::max(0.f, 1.f - 0.3f * static_cast<float>(std::abs(x - 20))); });
  const DetectionResult r = detect_ridge_valley_points(g.points, g.curvature, g.neighbourhoods, kH);
  EXPECT_EQ(count_at(r, g, PointLabel::Ridge, 20), 20u);  // the whole crest
  EXPECT_EQ(r.ridge_points, 20u);                         // and nothing else
  EXPECT_EQ(r.valley_points, 0u);
  // The paper's rule keeps the whole band above α·max = 0.2: x in [18, 22].
  const DetectionResult paper =
      detect_ridge_valley_points(g.points, g.curvature, g.neighbourhoods, kH, {.rule = DetectionRule::Paper});
  EXPECT_EQ(paper.ridge_points, 5u * 20u);
}

TEST(DetectRidgeValleyPoints, ValleysMirrorRidges) {
  const Grid g = grid([](int x) { return -std::max(0.f, 1.f - 0.3f * static_cast<float>(std::abs(x - 10))); });
  const DetectionResult r = detect_ridge_valley_points(g.points, g.curvature, g.neighbourhoods, kH);
  EXPECT_EQ(count_at(r, g, PointLabel::Valley, 10), 20u);
  EXPECT_EQ(r.valley_points, 20u);
  EXPECT_EQ(r.ridge_points, 0u);
  EXPECT_LT(r.valley_threshold, 0.f);
}

// Peak curvature ±1 at `centre`, falling by 0.3 per point over 2 points each side, then a side lobe of the opposite
// sign (0.3) at 3 points: the overshoot of a quadric fit beside a sharp edge.
float crest_with_side_lobes(int x, int centre, float sign) {
  const int d = std::abs(x - centre);
  if (d <= 2) return sign * (1.f - 0.3f * static_cast<float>(d));
  return d == 3 ? -sign * 0.3f : 0.f;
}

TEST(DetectRidgeValleyPoints, SideLobesOfTheOppositeSignAreSuppressed) {
  // A valley at x = 10 and a ridge at x = 28, each with lobes of the other sign beside it. The lobes pass every
  // threshold (0.3 ≥ 0.2 · extreme and ≥ the floors) and are the largest of their sign across their own direction,
  // but a stronger feature of the other sign is their neighbour across it: only the two crests remain.
  const Grid g = grid([](int x) { return crest_with_side_lobes(x, 10, -1.f) + crest_with_side_lobes(x, 28, 1.f); });
  const DetectionResult r = detect_ridge_valley_points(g.points, g.curvature, g.neighbourhoods, kH);
  EXPECT_EQ(count_at(r, g, PointLabel::Valley, 10), 20u);
  EXPECT_EQ(count_at(r, g, PointLabel::Ridge, 28), 20u);
  EXPECT_EQ(r.valley_points, 20u);
  EXPECT_EQ(r.ridge_points, 20u);
}

TEST(DetectRidgeValleyPoints, UniformCurvatureGivesNothingUnderTheSalientRule) {
  // A cylinder-like uniform curvature 0.5/h: every point is at the extreme; the plain rule takes them all.
  const Grid g = grid([](int) { return 0.5f; });
  EXPECT_EQ(detect_ridge_valley_points(g.points, g.curvature, g.neighbourhoods, kH).ridge_points, 0u);
  const DetectionResult paper =
      detect_ridge_valley_points(g.points, g.curvature, g.neighbourhoods, kH, {.rule = DetectionRule::Paper});
  EXPECT_EQ(paper.ridge_points, g.points.size());
}

TEST(DetectRidgeValleyPoints, OneOutlierMovesTheMinMaxExtremeButNotThePercentile) {
  // Ramp of ridge curvature k = x / 40 over x, plus one outlier of 1000.
  Grid g = grid([](int x) { return static_cast<float>(x + 1) / 40.f; });
  g.curvature.k1[5] = 1000.f;
  const DetectionOptions paper{.rule = DetectionRule::Paper};
  const DetectionResult robust = detect_ridge_valley_points(g.points, g.curvature, g.neighbourhoods, kH, paper);
  DetectionOptions minmax = paper;
  minmax.extreme = CurvatureExtreme::MinMax;
  const DetectionResult fragile = detect_ridge_valley_points(g.points, g.curvature, g.neighbourhoods, kH, minmax);
  EXPECT_FLOAT_EQ(fragile.convex_extreme, 1000.f);
  EXPECT_EQ(fragile.ridge_points, 1u);  // only the outlier reaches 0.2 · 1000
  EXPECT_NEAR(robust.convex_extreme, 1.f, 0.03f);
  EXPECT_EQ(robust.ridge_points, 33u * 20u + 1u);  // k ≥ 0.2: x in [7, 39], plus the outlier at x = 5
}

TEST(DetectRidgeValleyPoints, SaliencyFloorScalesWithSpacing) {
  // The same crest of peak curvature 1 is an edge at spacing h = 1 (k·h = 1) but not at h = 0.01 (k·h = 0.01).
  const Grid g = grid([](int x) { return std::max(0.f, 1.f - 0.3f * static_cast<float>(std::abs(x - 20))); });
  EXPECT_EQ(detect_ridge_valley_points(g.points, g.curvature, g.neighbourhoods, 1.f).ridge_points, 20u);
  EXPECT_EQ(detect_ridge_valley_points(g.points, g.curvature, g.neighbourhoods, 0.01f).ridge_points, 0u);
}

TEST(DetectRidgeValleyPoints, RejectsMismatchedInputAndBadOptions) {
  const Grid g = grid([](int) { return 0.f; });
  differential::Curvature short_curvature = g.curvature;
  short_curvature.k1.pop_back();
  EXPECT_THROW(detect_ridge_valley_points(g.points, short_curvature, g.neighbourhoods, kH), Error);
  EXPECT_THROW(detect_ridge_valley_points(g.points, g.curvature, g.neighbourhoods, kH, {.ridge_threshold_alpha = 1.5f}),
               Error);
  EXPECT_THROW(detect_ridge_valley_points(g.points, g.curvature, g.neighbourhoods, 0.f), Error);
}

}  // namespace
}  // namespace pcsketch::features
