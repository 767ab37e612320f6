// pcsketch draw --config: a drawing's recorded parameters replay it byte for byte; flags override them.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.h"

namespace pcsketch {
namespace {

using test::CommandRun;
using test::slurp;
using CliConfig = test::CliTest;

const std::string kBunny = PCSKETCH_DATA "/bunny.ply";

TEST_F(CliConfig, ReplayFromTheSvgAndTheJsonGivesTheSameBytes) {
  // Non-default options of several stages, a named view and a size: all must come back from the record.
  ASSERT_EQ(run("-q draw " + kBunny +
                " --size 160x120 --view left --alpha 0.3 --rho-max 4 --shadow paper "
                "--no-fusion --hidden-lines dashed -o " +
                path("a.svg") + " --json " + path("a.json"))
                .status,
            0);
  for (const char* config : {"a.svg", "a.json"}) {
    SCOPED_TRACE(config);
    const CommandRun r =
        run("-q draw " + kBunny + " --config " + path(config) + " -o " + path("b.svg") + " --json " + path("b.json"));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(slurp(path("b.svg")), slurp(path("a.svg")));
    EXPECT_EQ(slurp(path("b.json")), slurp(path("a.json")));
  }
}

TEST_F(CliConfig, FlagsOverrideRecordedValuesInAnyOrder) {
  ASSERT_EQ(run("-q draw " + kBunny + " --size 96x96 --rho-max 4 --alpha 0.3 -o " + path("a.svg")).status, 0);
  for (const std::string& flags :
       {"--rho-max 5 --config " + path("a.svg"), "--config " + path("a.svg") + " --rho-max 5"}) {
    const CommandRun r = run("draw --print-config " + flags);
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["thickness"]["rho_max"], 5.0) << flags;
    EXPECT_EQ(j["features"]["detection"]["ridge_threshold_alpha"], 0.3) << flags;  // recorded, not given
    EXPECT_EQ(j["camera"]["width"], 96) << flags;
  }
  // A sight flag replaces the recorded sight whole: the recorded named view does not conflict with --azimuth.
  ASSERT_EQ(run("-q draw " + kBunny + " --size 96x96 --view left -o " + path("left.svg")).status, 0);
  const CommandRun turned = run("draw --print-config --config " + path("left.svg") + " --azimuth 30");
  ASSERT_EQ(turned.status, 0) << turned.err;
  EXPECT_EQ(nlohmann::json::parse(turned.out)["camera"]["named"], nullptr);
  EXPECT_EQ(nlohmann::json::parse(turned.out)["camera"]["azimuth_deg"], 30.0);
  // Setting a flag to its default still overrides the record.
  const CommandRun r = run("draw --config " + path("a.svg") + " --rho-max 3 --print-config");
  EXPECT_EQ(nlohmann::json::parse(r.out)["thickness"]["rho_max"], 3.0);
}

TEST_F(CliConfig, PrintConfigReplaysItself) {
  const CommandRun first = run("draw --print-config --no-brush --size 300x200 --shadow-k 0.25 0.5");
  ASSERT_EQ(first.status, 0) << first.err;
  std::ofstream(path("c.json")) << first.out;
  const CommandRun again = run("draw --print-config --config " + path("c.json"));
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(again.out, first.out);
  EXPECT_EQ(nlohmann::json::parse(first.out)["shadow"]["k_set"], nlohmann::json({0.25, 0.5}));
}

TEST_F(CliConfig, AMalformedConfigIsOneErrorNamingTheFile) {
  const std::vector<std::pair<std::string, std::string>> configs = {
      {"truncated.json", R"({"thickness": {)"},
      {"unknown.json", R"({"thickness": {"rho_mix": 1}})"},
      {"type.json", R"({"shadow": {"mode": 3}})"},
      {"range.json", R"({"features": {"detection": {"ridge_threshold_alpha": 0}}})"},
      {"nodesc.svg", "<svg></svg>"}};
  for (const auto& [name, text] : configs) {
    SCOPED_TRACE(name);
    std::ofstream(path(name)) << text;
    const CommandRun r = run("draw " + kBunny + " --config " + path(name) + " -o " + path("x.svg"));
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(path(name)), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(run("draw " + kBunny + " --config " + path("missing.json") + " -o " + path("x.svg")).status, 2);
}

TEST_F(CliConfig, RangesAreCheckedWhileParsing) {
  // The library's range, refused as a bad command line before anything is read.
  const CommandRun r = run("draw missing.ply -o " + path("x.svg") + " --alpha 0");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--alpha: must be in (0, 1), got 0"), std::string::npos) << r.err;
  const CommandRun help = run("draw --help");
  EXPECT_NE(help.out.find("--no-brush "), std::string::npos);
  EXPECT_EQ(help.out.find("--no-brush{"), std::string::npos);
  EXPECT_NE(help.out.find("=combined"), std::string::npos);  // a choice shows its default
}

}  // namespace
}  // namespace pcsketch
