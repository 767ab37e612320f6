// The flag blocks `features` and `draw` share (cli/options.h): --orientation reaches the surface analysis of both.

#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.h"

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
