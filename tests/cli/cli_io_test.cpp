// Runs the built pcsketch binary: `info` and `sample` on good and bad input, checking exit status and output.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "pcsketch/io/read_cloud.h"
#include "cli_test_support.h"
#include "support/scan_lines.h"

namespace pcsketch {
namespace {

using test::CommandRun;
using test::slurp;
using CliIo = test::CliTest;

TEST_F(CliIo, InfoOnTheBundledBunny) {
  const CommandRun r = run("info " PCSKETCH_DATA "/bunny.ply");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("points      37706"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("format      ply binary_little_endian"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("spacing h   0.00"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("read time"), std::string::npos) << r.out;
}

TEST_F(CliIo, MalformedInputExitsWithStatus2AndOneLine) {
  for (const char* file : {"truncated.ply", "nonnumeric.xyz", "empty.ply", "huge_count.ply"}) {
    SCOPED_TRACE(file);
    const std::string path = std::string(PCSKETCH_FIXTURES) + "/malformed/" + file;
    const CommandRun r = run("info " + path);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(path), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  EXPECT_EQ(run("info /nonexistent.ply").status, 2);
}

TEST_F(CliIo, SampleWritesADeterministicCloud) {
  const std::string mesh = std::string(PCSKETCH_FIXTURES) + "/ok/cube.off";
  const std::string a = (dir_ / "a.ply").string(), b = (dir_ / "b.ply").string();
  ASSERT_EQ(run("sample " + mesh + " -n 2000 --noise 0.001 --seed 4 -o " + a).status, 0);
  ASSERT_EQ(run("--threads 1 sample " + mesh + " -n 2000 --noise 0.001 --seed 4 -o " + b).status, 0);
  EXPECT_EQ(slurp(a), slurp(b));
  const io::ReadResult r = io::read_point_cloud(a);
  EXPECT_EQ(r.cloud.size(), 2000u);
  EXPECT_FALSE(r.cloud.has_normals());
  ASSERT_EQ(run("sample " + mesh + " -n 10 --keep-normals -o " + b).status, 0);
  EXPECT_TRUE(io::read_point_cloud(b).cloud.has_normals());
  // A cloud without faces, and a bad count.
  EXPECT_EQ(run("sample " + std::string(PCSKETCH_FIXTURES) + "/ok/points.xyz -n 10 -o " + a).status, 2);
  EXPECT_EQ(run("sample " + mesh + " -n 0 -o " + a).status, 1);
}

TEST_F(CliIo, FeaturesLabelsTheBorderOfAnOpenSheet) {
  // 6,000 random points on the unit square (h about 0.006): an open scan whose border is the square's edge.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<Vec2f> points(6000);
  {
    std::ofstream out(path("sheet.xyz"));
    for (Vec2f& p : points) {
      p = Vec2f(u(rng), u(rng));
      out << p.x() << " " << p.y() << " 0\n";
    }
  }
  const CommandRun r = run("-q features " + path("sheet.xyz") + " --ascii -o " + path("f.ply"));
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream ply(slurp(path("f.ply")));
  std::string line;
  while (std::getline(ply, line) && line != "end_header") {
  }
  std::size_t border = 0, row = 0;
  for (; std::getline(ply, line) && row < points.size(); ++row) {
    const int label = std::stoi(line.substr(line.find_last_of(' ') + 1));
    if (label != 4) continue;
    ++border;
    const float to_edge = std::min({points[row].x(), points[row].y(), 1 - points[row].x(), 1 - points[row].y()});
    EXPECT_LT(to_edge, 0.05f) << "a border label inside the sheet, row " << row;
  }
  EXPECT_EQ(row, points.size());
  // The edge is 4 long: a row of points about 2h apart along it holds some 300.
  EXPECT_GE(border, 150u);
  const CommandRun off = run("-q features " + path("sheet.xyz") + " --ascii --no-boundary-detection -o " + path("g.ply"));
  ASSERT_EQ(off.status, 0) << off.err;
  EXPECT_EQ(slurp(path("g.ply")).find(" 4\n"), std::string::npos);
}

TEST_F(CliIo, FeaturesLabelsThePointsThinnedOnScanLines) {
  // A sphere on 40 rings, 20 times denser along them than apart: thinned, and every point of the file still written,
  // those left out labelled 5, in the file's order.
  const std::vector<Vec3f> rings = test::sphere_rings(40, 20.f);
  {
    std::ofstream out(path("rings.xyz"));
    for (const Vec3f& p : rings) out << p.x() << " " << p.y() << " " << p.z() << "\n";
  }
  const CommandRun r = run("features " + path("rings.xyz") + " --ascii -o " + path("r.ply"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("scan lines"), std::string::npos) << r.err;
  std::istringstream ply(slurp(path("r.ply")));
  std::string line;
  while (std::getline(ply, line) && line != "end_header") {
  }
  std::size_t row = 0, thinned = 0;
  for (; std::getline(ply, line); ++row) {
    ASSERT_LT(row, rings.size());
    std::istringstream fields(line);
    Vec3f p;
    fields >> p.x() >> p.y() >> p.z();
    EXPECT_LT((p - rings[row]).norm(), 1e-4f) << "row " << row;
    thinned += std::stoi(line.substr(line.find_last_of(' ') + 1)) == 5;
  }
  EXPECT_EQ(row, rings.size());
  EXPECT_GT(thinned, rings.size() / 2);
  const CommandRun kept = run("-q features " + path("rings.xyz") + " --ascii --keep-scan-lines -o " + path("k.ply"));
  ASSERT_EQ(kept.status, 0) << kept.err;
  EXPECT_EQ(slurp(path("k.ply")).find(" 5\n"), std::string::npos);
}

}  // namespace
}  // namespace pcsketch
