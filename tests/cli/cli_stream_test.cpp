// Large clouds through the CLI: thinning to the output's resolution only past the budget (2 x W x H points), the
// JSON and info saying what was kept, --full-resolution refused early over the available memory, and malformed
// files failing as before on the streamed path.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.h"

namespace pcsketch {
namespace {

using test::CommandRun;
using test::slurp;
using CliStream = test::CliTest;

const std::string kBunny = PCSKETCH_DATA "/bunny.ply";  // 37,706 points

TEST_F(CliStream, CloudWithinTheBudgetIsDrawnAsWithFullResolution) {
  // 1024 x 1024: a budget of 2,097,152 points; the bunny is untouched, byte for byte.
  ASSERT_EQ(run("-q draw " + kBunny + " --size 256x256 -o " + path("a.svg") + " --json " + path("a.json")).status, 0);
  ASSERT_EQ(run("-q draw " + kBunny + " --size 256x256 --full-resolution -o " + path("b.svg") + " --json " +
                path("b.json"))
                .status,
            0);
  EXPECT_EQ(slurp(path("a.svg")), slurp(path("b.svg")));
  EXPECT_EQ(slurp(path("a.json")), slurp(path("b.json")));
  EXPECT_FALSE(nlohmann::json::parse(slurp(path("a.json"))).contains("input"));
}

TEST_F(CliStream, CloudOverTheBudgetIsThinnedAndTheJsonSaysSo) {
  // 100 x 100: a budget of 20,000 points, under the bunny's 37,706.
  const CommandRun r = run("-q draw " + kBunny + " --size 100x100 --json " + path("a.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json input = nlohmann::json::parse(slurp(path("a.json")))["input"];
  EXPECT_EQ(input["points_in_file"], 37706);
  EXPECT_LT(input["points_kept"].get<int>(), 37706);
  EXPECT_GT(input["points_kept"].get<int>(), 1000);
  EXPECT_TRUE(input["thinning"]["streamed"].get<bool>());
  EXPECT_EQ(input["thinning"]["reason"],
            "37706 points, over the 20000 budget of a 100x100 orthographic image: cells of 1 px");
  // The bunny's box is about 1 x 1 x 0.77: the median side over 100 px.
  EXPECT_NEAR(input["thinning"]["cell"].get<double>(), 0.01, 0.001);
}

TEST_F(CliStream, InfoReportsTheThinning) {
  const CommandRun r = run("info " + kBunny + " --voxel 0.01 --k 4");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("reduced     voxel thinning 37706 -> "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("streamed) by --voxel"), std::string::npos) << r.out;
}

TEST_F(CliStream, FullResolutionRefusedOverTheAvailableMemory) {
  const CommandRun r =
      run("-q draw " + kBunny + " --full-resolution -o " + path("a.svg"), "1000000");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("--full-resolution"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("holds 37706 points, estimated to need 0.0"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("over the 0.001 GB available"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("a.svg")));
  // Without the flag the cloud is drawn (the budget leaves it whole; the analysis needs less than the machine has).
  EXPECT_EQ(run("-q draw " + kBunny + " -o " + path("a.svg"), "1000000").status, 0);
}

TEST_F(CliStream, FullResolutionRefusedOverTheAvailableMemoryForAnXyzFileToo) {
  // 5,000 rows and no count in the file: the estimate from its line lengths decides before any row is read.
  {
    std::ofstream out(path("grid.xyz"));
    for (int i = 0; i < 5000; ++i) out << (i % 100) * 0.01 << " " << (i / 100) * 0.01 << " 0.5\n";
  }
  const CommandRun r = run("-q draw " + path("grid.xyz") + " --full-resolution -o " + path("a.svg"), "100000");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  const std::size_t at = r.err.find("holds about ");
  ASSERT_NE(at, std::string::npos) << r.err;
  EXPECT_NEAR(std::stod(r.err.substr(at + 12)), 5000, 250) << r.err;
  EXPECT_NE(r.err.find("points (from its line lengths), estimated to need"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("a.svg")));
}

TEST_F(CliStream, MalformedFilesFailAsBeforeWhenThinned) {
  for (const char* file : {"truncated.ply", "huge_count.ply", "empty.ply"}) {
    SCOPED_TRACE(file);
    const std::string input = std::string(PCSKETCH_FIXTURES) + "/malformed/" + file;
    const CommandRun r = run("-q draw " + input + " --voxel 0.01 -o " + path("a.svg"));
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(input), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace pcsketch
