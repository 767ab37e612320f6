// The flag blocks `features` and `draw` share (cli/options.h): --orientation reaches the surface analysis of both.

#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "cli_test_support.h"
#include "pcsketch/io/ply.h"
#include "support/analytic_shapes.h"

namespace pcsketch {
namespace {

using test::CommandRun;
using test::slurp;
using CliOptions = test::CliTest;

struct FeatureCounts {
  std::size_t ridge_points = 0, valley_points = 0;
};

// fandisk.off's vertices carry no normals, so they are estimated and oriented: the orientation test decides the sign
// of every curvature, hence which feature points are ridges and which are valleys.
TEST_F(CliOptions, FeaturesOrientationReachesTheSurfaceAnalysis) {
  auto features = [&](const std::string& criterion) {
    const std::string lines = path(criterion + ".json");
    const CommandRun r = run("-q features " PCSKETCH_FIXTURES "/fandisk.off -o " + path(criterion + ".ply") +
                             " --lines " + lines + " --orientation " + criterion);
    EXPECT_EQ(r.status, 0) << r.err;
    const nlohmann::json json = nlohmann::json::parse(slurp(lines));
    return FeatureCounts{json["ridge_points"].get<std::size_t>(), json["valley_points"].get<std::size_t>()};
  };
  const FeatureCounts reflect = features("reflect");
  const FeatureCounts parallel = features("parallel");
  // Measured 671 ridge / 118 valley points (reflect) against 451 / 338 (parallel): Hoppe's |n_i.n_j| leaves whole
  // faces of the fandisk pointing inward, which turns their convex edges into valleys.
  EXPECT_GT(reflect.ridge_points, parallel.ridge_points + 100);
  EXPECT_LT(reflect.valley_points + 100, parallel.valley_points);
  EXPECT_GT(reflect.ridge_points, 4 * reflect.valley_points);  // the fandisk is mostly convex edges
}

TEST_F(CliOptions, DrawOrientationReachesTheSurfaceAnalysis) {
  auto ridge_points = [&](const std::string& criterion) {
    const std::string json_path = path(criterion + ".json");
    const CommandRun r = run("-q draw " PCSKETCH_FIXTURES "/fandisk.off --size 256x256 --json " + json_path +
                             " --orientation " + criterion);
    EXPECT_EQ(r.status, 0) << r.err;
    const nlohmann::json json = nlohmann::json::parse(slurp(json_path));
    std::size_t points = 0;
    for (const auto& p : json["polylines"])
      if (p["kind"] == "ridge") points += p["points"].size();
    return points;
  };
  // Measured 194 points on ridge strokes (reflect) against 158 (parallel).
  EXPECT_GT(ridge_points("reflect"), ridge_points("parallel"));
}

// A file whose normals have arbitrary signs: by default their signs are re-oriented with a warning; `trust` keeps
// them, `orient` always re-orients; the choice is recorded in the JSON.
TEST_F(CliOptions, FileNormalsModes) {
  PointCloud cloud = test::sphere(1.f, {.n = 3000, .seed = 8});
  for (std::size_t i = 0; i < cloud.size(); i += 3) cloud.normals[i] = -cloud.normals[i];
  const std::string input = path("flipped.ply");
  io::write_ply(input, cloud);
  auto draw = [&](const std::string& mode) {
    const std::string json_path = path(mode + ".json");
    const CommandRun r = run("draw " + input + " --size 128x128 --json " + json_path + " --file-normals " + mode);
    EXPECT_EQ(r.status, 0) << r.err;
    const nlohmann::json surface = nlohmann::json::parse(slurp(json_path))["parameters"]["surface"];
    return std::make_pair(r.err.find("not consistently oriented") != std::string::npos, surface);
  };
  const auto [auto_warned, auto_surface] = draw("auto");
  EXPECT_TRUE(auto_warned);
  EXPECT_EQ(auto_surface["orient_file_normals"], false);
  const auto [trust_warned, trust_surface] = draw("trust");
  EXPECT_FALSE(trust_warned);
  EXPECT_EQ(trust_surface["file_normal_disagreement"], 1.0);
  const auto [orient_warned, orient_surface] = draw("orient");
  EXPECT_FALSE(orient_warned);  // asked for: nothing to warn about
  EXPECT_EQ(orient_surface["orient_file_normals"], true);
  EXPECT_EQ(run("draw " + input + " --file-normals sometimes -o " + path("x.svg")).status, 1);
}

// The paper's rules that pcsketch replaces by default are each one flag away, and the JSON says which ran.
TEST_F(CliOptions, PaperRulesReachTheJsonParameters) {
  const std::string json_path = path("paper.json");
  const CommandRun r = run("-q draw " PCSKETCH_DATA "/bunny.ply --size 128x128 --json " + json_path +
                           " --no-uneven-spacing --no-visibility-lift --self-offset 2 --shadow-over-background");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json p = nlohmann::json::parse(slurp(json_path))["parameters"];
  EXPECT_EQ(p["view"]["contours"]["adaptive_spacing"], false);
  EXPECT_EQ(p["view"]["visibility"]["lift_to_source_plane"], false);
  EXPECT_EQ(p["view"]["visibility"]["self_offset_factor"], 2.0);
  EXPECT_EQ(p["shadow"]["clip_to_surface"], false);
}

TEST_F(CliOptions, UnknownOrientationIsAUsageError) {
  const std::string fandisk = PCSKETCH_FIXTURES "/fandisk.off";
  for (const std::string& command :
       {"features " + fandisk + " -o " + path("x.ply"), "draw " + fandisk + " -o " + path("x.svg")}) {
    const CommandRun r = run(command + " --orientation bogus");
    EXPECT_EQ(r.status, 1) << command;
    EXPECT_NE(r.err.find("--orientation"), std::string::npos) << r.err;
    EXPECT_EQ(run(command + " --outward sideways").status, 1) << command;
  }
  EXPECT_FALSE(std::filesystem::exists(path("x.ply")));
  EXPECT_FALSE(std::filesystem::exists(path("x.svg")));
}

}  // namespace
}  // namespace pcsketch
