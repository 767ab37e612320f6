// Views from the command line: named views, the three-quarter default of --up, refused combinations, several views
// from one analysis (--views, --turntable); and the plotter's recorded pen travel.

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.h"
#include "pcsketch/core/point_cloud.h"
#include "support/las_writer.h"

namespace pcsketch {
namespace {

namespace fs = std::filesystem;

using test::CommandRun;
using test::slurp;
using CliViews = test::CliTest;

const std::string kBunny = PCSKETCH_DATA "/bunny.ply";

/// True if `text` has a line starting with `name`, spaces and a number (a timings row).
bool has_row(const std::string& text, const std::string& name) {
  const std::size_t at = text.find("\n" + name + " ");
  if (at == std::string::npos) return false;
  const std::size_t value = text.find_first_not_of(' ', at + 1 + name.size());
  return value != std::string::npos && std::isdigit(static_cast<unsigned char>(text[value]));
}

/// Every "&quot;" of `text` as '"'. (No std::regex: GCC 12 warns inside it under -O2 with sanitizers.)
std::string unquote(std::string text) {
  for (std::size_t at = text.find("&quot;"); at != std::string::npos; at = text.find("&quot;", at + 1))
    text.replace(at, 6, "\"");
  return text;
}

std::size_t lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

Vec3d direction(const nlohmann::json& drawing) {
  const auto& d = drawing["camera"]["direction"];
  return {d[0].get<double>(), d[1].get<double>(), d[2].get<double>()};
}

TEST_F(CliViews, UpAloneGivesTheThreeQuarterView) {
  const CommandRun r = run("-q draw " + kBunny + " --size 96x96 --up 0,0,1 --json " + path("q.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(slurp(path("q.json")));
  const Vec3d f = direction(json);
  // 15 degrees down from the horizon of z up, not along it (the old default looked from underneath, along +z).
  EXPECT_NEAR(f.z(), -std::sin(15.0 * 3.14159265358979323846 / 180.0), 1e-5);
  EXPECT_EQ(json["parameters"]["camera"]["azimuth_deg"], -35.0);
}

// A LAS file's z is elevation: drawn with no view flag it stands upright (three-quarter view about z), named views
// are relative to z, and the flags still choose: --up, or a sight along z (which keeps up y instead of refusing).
TEST_F(CliViews, LasFilesAreZUp) {
  test::LasFile hill{.offset = Vec3d(500000, 4649000, 100)};
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x) {
      const double u = (x - 19.5) / 10, v = (y - 19.5) / 10;
      hill.points.push_back({Vec3d(500000 + u, 4649000 + v, 100 + std::exp(-(u * u + v * v)))});
    }
  const std::string las = path("hill.las");
  std::ofstream(las, std::ios::binary) << test::write_las(hill);
  const auto drawn = [&](const std::string& flags) {
    const CommandRun r = run("-q draw " + las + " --size 96x96 " + flags + " --json " + path("h.json"));
    EXPECT_EQ(r.status, 0) << flags << ": " << r.err;
    return nlohmann::json::parse(slurp(path("h.json")));
  };
  const double down = -std::sin(15.0 * 3.14159265358979323846 / 180.0);
  nlohmann::json json = drawn("");
  EXPECT_EQ(json["parameters"]["camera"]["up"], nlohmann::json::array({0.0, 0.0, 1.0}));
  EXPECT_NEAR(direction(json).z(), down, 1e-5);  // 15 degrees down onto the ground, not from underneath
  EXPECT_TRUE(direction(drawn("--view top")).isApprox(Vec3d(0, 0, -1), 1e-6));
  EXPECT_NEAR(direction(drawn("--azimuth 90 --elevation 30")).z(), -0.5, 1e-6);
  json = drawn("--up 0,1,0");
  EXPECT_EQ(json["parameters"]["camera"]["up"], nlohmann::json::array({0.0, 1.0, 0.0}));
  EXPECT_NEAR(direction(json).y(), down, 1e-5);
  json = drawn("--view 0,0,-1");  // a plan view along z: up stays y
  EXPECT_TRUE(direction(json).isApprox(Vec3d(0, 0, -1), 1e-6));
  EXPECT_EQ(json["parameters"]["camera"]["up"], nlohmann::json::array({0.0, 1.0, 0.0}));
}

TEST_F(CliViews, NamedViewRelativeToUp) {
  const CommandRun r = run("-q draw " + kBunny + " --size 96x96 --up 0,0,1 --view top --json " + path("t.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(slurp(path("t.json")));
  EXPECT_TRUE(direction(json).isApprox(Vec3d(0, 0, -1), 1e-6));
  EXPECT_EQ(json["parameters"]["camera"]["named"], "top");
  const CommandRun bad = run("draw " + kBunny + " -o " + path("x.svg") + " --view sideways");
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.err.find("--view"), std::string::npos) << bad.err;
}

TEST_F(CliViews, RefusedViewsNameTheFlagsOnOneLine) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"--view 0,0,1 --up 0,0,1", {"--view", "--up"}},
      {"--view 0,-3,0", {"--view", "--up"}},  // default up is y
      {"--azimuth 30 --view 1,0,0", {"--view", "--azimuth"}},
      {"--view front --elevation 20", {"--view", "--elevation"}},
      {"--views front,top --turntable 4", {"--views", "--turntable"}},
      {"--views front,top --azimuth 10", {"--views", "--azimuth"}},
      {"--turntable 4 --view 1,0,0", {"--turntable", "--view"}},
      {"--turntable 0", {"--turntable"}},
      {"--views front,sideways", {"--views"}}};
  for (const auto& [flags, named] : cases) {
    SCOPED_TRACE(flags);
    const CommandRun r = run("draw " + kBunny + " -o " + path("x.svg") + " " + flags);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    for (const std::string& flag : named) EXPECT_NE(r.err.find(flag), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir_ / "x.svg"));
}

TEST_F(CliViews, SeveralNamedViewsFromOneAnalysis) {
  const CommandRun r = run("-q draw " + kBunny + " --size 96x96 --views front,left,iso -o " + path("b.svg") +
                           " --json " + path("b.json") + " --timings");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(path("b.svg")));
  const std::map<std::string, Vec3d> expected = {
      {"front", {0, 0, 1}}, {"left", {-1, 0, 0}}, {"iso", Vec3d(1, -1, 1).normalized()}};
  for (const auto& [name, dir] : expected) {
    SCOPED_TRACE(name);
    EXPECT_NE(slurp(path("b-" + name + ".svg")).find("</svg>"), std::string::npos);
    const nlohmann::json json = nlohmann::json::parse(slurp(path("b-" + name + ".json")));
    EXPECT_TRUE(direction(json).isApprox(dir, 1e-5));
  }
  // One analysis: the view-independent rows appear once in the timings, the view rows summed over the views.
  EXPECT_TRUE(has_row(r.out, "normals"));
}

TEST_F(CliViews, TurntableNamesFilesByAzimuth) {
  const CommandRun r = run("-q draw " + kBunny + " --size 64x64 --turntable 4 --elevation 0 --json " + path("t.json") +
                           " --stages " + path("st"));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::map<std::string, Vec3d> expected = {
      {"az000", {0, 0, 1}}, {"az090", {-1, 0, 0}}, {"az180", {0, 0, -1}}, {"az270", {1, 0, 0}}};
  for (const auto& [name, dir] : expected) {
    SCOPED_TRACE(name);
    const nlohmann::json json = nlohmann::json::parse(slurp(path("t-" + name + ".json")));
    EXPECT_TRUE(direction(json).isApprox(dir, 1e-5));
    EXPECT_TRUE(fs::exists(dir_ / "st" / name / "f_shadow.png"));
  }
}

TEST_F(CliViews, PlotterRecordsPenTravelInTheSvgDesc) {
  const CommandRun r = run("-q draw " + kBunny + " --size 256x256 --plotter --page-width-mm 200 -o " + path("p.svg"));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string svg = slurp(path("p.svg"));
  const std::size_t open = svg.find("<desc>"), close = svg.find("</desc>");
  ASSERT_TRUE(open != std::string::npos && close != std::string::npos && close > open);
  const nlohmann::json record = nlohmann::json::parse(unquote(svg.substr(open + 6, close - open - 6)));
  const nlohmann::json& before = record["plotter"]["before_ordering"];
  const nlohmann::json& after = record["plotter"]["after_ordering"];
  EXPECT_GT(before["pen_up_mm"].get<double>(), 0.0);
  EXPECT_LT(after["pen_up_mm"].get<double>(), 0.7 * before["pen_up_mm"].get<double>());
  EXPECT_LE(after["strokes"].get<int>(), before["strokes"].get<int>());
  // The pen is 0.3 mm by default: 0.3 mm on a 200 mm page of 256 px is 0.38 px.
  EXPECT_NE(svg.find("stroke-width=\"0.38\""), std::string::npos);
  const CommandRun both = run("draw " + kBunny + " -o " + path("x.svg") + " --pen-width-px 1 --pen-width-mm 0.3");
  EXPECT_EQ(both.status, 1);
  EXPECT_NE(both.err.find("--pen-width"), std::string::npos) << both.err;
}

}  // namespace
}  // namespace pcsketch
