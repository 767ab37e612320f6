// Runs the built pcsketch binary: `draw` end to end on the bundled bunny, bad input, tiny clouds, stage images.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_test_support.h"

namespace pcsketch {
namespace {

namespace fs = std::filesystem;

using test::CommandRun;
using test::slurp;
using CliDraw = test::CliTest;

TEST_F(CliDraw, BundledBunnyToAllFourOutputs) {
  const CommandRun r = run("draw " PCSKETCH_DATA "/bunny.ply --size 384x384 -o " + path("b.svg") + " -o " +
                           path("b.png") + " -o " + path("b.pdf") + " --json " + path("b.json") + " --timings");
  ASSERT_EQ(r.status, 0) << r.err;

  const std::string svg = slurp(path("b.svg"));
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("inkscape:label=\"1 contours\""), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  if (std::system("command -v xmllint > /dev/null 2>&1") == 0) {
    EXPECT_EQ(std::system(("xmllint --noout " + path("b.svg")).c_str()), 0);
  }

  const std::string png = slurp(path("b.png"));
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  const std::string pdf = slurp(path("b.pdf"));
  EXPECT_EQ(pdf.rfind("%PDF-", 0), 0u);
  EXPECT_GT(pdf.size(), 2000u);

  const nlohmann::json json = nlohmann::json::parse(slurp(path("b.json")));
  EXPECT_EQ(json["image"]["width"], 384);
  EXPECT_EQ(json["camera"]["projection"], "orthographic");
  // Every vertex is analysed or reported as an outlier (one bunny vertex lies off its neighbours' plane).
  const auto& resolved = json["parameters"]["resolved"];
  EXPECT_EQ(resolved["points"].get<std::size_t>() + resolved["outliers_removed"].get<std::size_t>(), 37706u);
  EXPECT_LE(resolved["outliers_removed"].get<std::size_t>(), 4u);
  std::size_t contours = 0;
  for (const auto& p : json["polylines"]) {
    contours += p["kind"] == "contour" && p["visible"].get<bool>();
    ASSERT_EQ(p["points"].size(), p["image_points"].size());
  }
  EXPECT_GE(contours, 1u);
  // The bunny's world coordinates: within its bounding box (about ±0.1 … 0.2 model units).
  for (const auto& q : json["polylines"][0]["points"])
    for (int a = 0; a < 3; ++a) EXPECT_LT(std::abs(q[a].get<double>()), 1.0);

  for (const char* row : {"ridge-valley points extraction", "ridge-valley points connection",
                          "contour points extraction", "contour line connection", "drawing", "total"})
    EXPECT_NE(r.out.find(row), std::string::npos) << row;
}

TEST_F(CliDraw, StagesWritesThePapersFigure19Columns) {
  const CommandRun r = run("-q draw " PCSKETCH_DATA "/bunny.ply --size 256x256 --stages " + path("stages"));
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* stem : {"b_contours", "c_ridges_valleys", "d_fused", "e_thickness", "f_shadow"})
    EXPECT_TRUE(fs::exists(dir_ / "stages" / (std::string(stem) + ".png"))) << stem;
}

TEST_F(CliDraw, PlotterSvgHasOnlyCentreLines) {
  const CommandRun r =
      run("draw " PCSKETCH_DATA "/bunny.ply --size 256x256 --plotter --pen-width-px 0.5 -o " + path("p.svg") + " -q");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string svg = slurp(path("p.svg"));
  EXPECT_EQ(svg.find("stroke-width=\"1"), std::string::npos);
  EXPECT_NE(svg.find("stroke-width=\"0.5\""), std::string::npos);
  // --pen-width is in page millimetres: 0.8 mm on a 128 mm page of 256 px is 1.6 px.
  ASSERT_EQ(run("-q draw " PCSKETCH_DATA "/bunny.ply --size 256x256 --plotter --pen-width 0.8 --page-width-mm 128 -o " +
                path("mm.svg"))
                .status,
            0);
  EXPECT_NE(slurp(path("mm.svg")).find("stroke-width=\"1.6\""), std::string::npos);
}

TEST_F(CliDraw, MalformedInputExitsWithTwo) {
  const CommandRun bad = run("draw " PCSKETCH_FIXTURES "/malformed/truncated.ply -o " + path("x.svg"));
  EXPECT_EQ(bad.status, 2) << bad.err;
  EXPECT_NE(bad.err.find("pcsketch: error:"), std::string::npos);
  EXPECT_FALSE(fs::exists(path("x.svg")));
  const CommandRun missing = run("draw " + path("no_such_file.ply") + " -o " + path("x.svg"));
  EXPECT_EQ(missing.status, 2) << missing.err;
}

TEST_F(CliDraw, TinyCloudGivesAnEmptyDrawingAndAWarning) {
  std::ofstream(path("tiny.xyz")) << "0 0 0\n1 0 0\n0 1 0\n";
  const CommandRun r = run("draw " + path("tiny.xyz") + " -o " + path("t.svg") + " --json " + path("t.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("pcsketch: warning:"), std::string::npos) << r.err;
  const nlohmann::json json = nlohmann::json::parse(slurp(path("t.json")));
  EXPECT_TRUE(json["polylines"].empty());
  EXPECT_NE(slurp(path("t.svg")).find("</svg>"), std::string::npos);
}

TEST_F(CliDraw, UsageErrorsExitWithOne) {
  EXPECT_EQ(run("draw " PCSKETCH_DATA "/bunny.ply").status, 1);  // nothing to write
  EXPECT_EQ(run("draw " PCSKETCH_DATA "/bunny.ply -o " + path("x.txt")).status, 1);
  EXPECT_EQ(run("draw " PCSKETCH_DATA "/bunny.ply -o " + path("x.svg") + " --view 1,2").status, 1);
  EXPECT_EQ(run("draw " PCSKETCH_DATA "/bunny.ply -o " + path("x.svg") + " --size 0x10").status, 1);
  EXPECT_EQ(run("draw " PCSKETCH_DATA "/bunny.ply -o " + path("x.svg") + " --hidden-lines dotted").status, 1);
  EXPECT_FALSE(fs::exists(path("x.svg")));
}

}  // namespace
}  // namespace pcsketch
