// The input flags end to end: LAS through `info` (attributes, class histogram), --classes/--drop-classes, --crop,
// --columns, --voxel in `info` and `draw --timings`, and malformed LAS exiting with status 2.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "cli_test_support.h"
#include "support/las_writer.h"

namespace pcsketch {
namespace {

using test::CommandRun;
using CliInputs = test::CliTest;

test::LasFile three_classes() {
  test::LasFile f{.minor = 4, .format = 7, .offset = Vec3d(600000, 5000000, 0)};
  f.points = {{{600000.5, 5000000.5, 10.0}, 10, 1, 1, 2, {65535, 0, 0}},
              {{600001.5, 5000001.5, 12.0}, 4000, 1, 2, 6, {0, 65535, 0}},
              {{600002.5, 5000002.5, 11.0}, 20, 2, 2, 7, {0, 0, 65535}}};
  return f;
}

std::string write(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// An n x n grid of spacing 1 in the plane z = 0.
std::string grid_xyz(int n) {
  std::string text;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) text += std::to_string(x) + " " + std::to_string(y) + " 0\n";
  return text;
}

TEST_F(CliInputs, InfoListsEveryLasAttributeWithItsRange) {
  const std::string las = write(path("scan.las"), test::write_las(three_classes()));
  const CommandRun r = run("info " + las);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("format      las 1.4 point format 7"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("classification  2: 1 (33.3%), 6: 1 (33.3%), 7: 1 (33.3%)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("intensity       10 .. 4000"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("return_number   1 .. 2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("red             0 .. 255"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("bbox min    600000.500000 5000000.500000 10.000000"), std::string::npos) << r.out;
}

TEST_F(CliInputs, ClassAndCropFlags) {
  const std::string las = write(path("scan.las"), test::write_las(three_classes()));
  EXPECT_NE(run("info " + las + " --classes 2,6").out.find("points      2 "), std::string::npos);
  const CommandRun dropped = run("info " + las + " --drop-classes 7");
  EXPECT_NE(dropped.out.find("classification  2: 1 (50.0%), 6: 1 (50.0%)"), std::string::npos) << dropped.out;
  EXPECT_NE(dropped.out.find("reduced     1 outside the crop box or of classes not kept"), std::string::npos);
  const CommandRun cropped = run("info " + las + " --crop 600000,5000000,0,600001,5000001,100");
  EXPECT_NE(cropped.out.find("points      1 "), std::string::npos) << cropped.out;
  EXPECT_EQ(run("info " + las + " --crop 1,2,3").status, 1);
  EXPECT_EQ(run("info " + las + " --crop 5,0,0,1,1,1").status, 1);  // min > max
  EXPECT_EQ(run("info " + las + " --classes 300").status, 1);
}

TEST_F(CliInputs, MalformedLasExitsWithStatus2NamingTheByte) {
  const std::string good = test::write_las(three_classes());
  const std::string cut = write(path("cut.las"), good.substr(0, good.size() - 10));
  const CommandRun r = run("info " + cut);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find(cut + " (byte 247): LAS: header claims 3 points"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  std::string laz = good;
  test::poke(laz, 104, 7 | 0x80, 1);
  const CommandRun z = run("info " + write(path("scan.laz"), laz));
  EXPECT_EQ(z.status, 2);
  EXPECT_NE(z.err.find("LAZ, compressed LAS (point format 7), which is not supported"), std::string::npos) << z.err;
}

TEST_F(CliInputs, ColumnsAreGuessedShownAndOverridden) {
  const std::string xyz = write(path("rgb.xyz"), "0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n");
  const CommandRun guessed = run("info " + xyz);
  ASSERT_EQ(guessed.status, 0) << guessed.err;
  EXPECT_NE(guessed.out.find("columns     x,y,z,r,g,b (guessed from the values)"), std::string::npos) << guessed.out;
  const CommandRun mapped = run("info " + xyz + " --columns x,y,z,skip,skip,i");
  EXPECT_NE(mapped.out.find("intensity       0 .. 255"), std::string::npos) << mapped.out;
  const CommandRun bad = run("info " + xyz + " --columns x,y,q");
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.err.find("unknown column \"q\""), std::string::npos) << bad.err;
}

TEST_F(CliInputs, VoxelThinningIsReportedInInfoAndTimings) {
  const std::string xyz = write(path("grid.xyz"), grid_xyz(20));
  const CommandRun info = run("info " + xyz + " --voxel 2");
  ASSERT_EQ(info.status, 0) << info.err;
  EXPECT_NE(info.out.find("voxel thinning 400 -> 100 points (cell 2"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("points      100 "), std::string::npos) << info.out;
  const CommandRun draw = run("draw " + xyz + " --max-points 150 --timings -o " + path("g.svg"));
  ASSERT_EQ(draw.status, 0) << draw.err;
  EXPECT_NE(draw.out.find("read: reduced"), std::string::npos) << draw.out;
  EXPECT_NE(draw.out.find("voxel thinning 400 -> "), std::string::npos) << draw.out;
  EXPECT_EQ(run("info " + xyz + " --max-points 3").status, 1);
}

TEST_F(CliInputs, FullResolutionKnowsTheLasHeaderCount) {
  // The early memory check reads the LAS header's count, as it reads a PLY's (second argument: MemAvailable, kB).
  const std::string las = write(path("scan.las"), test::write_las(three_classes()));
  const CommandRun r = run("-q draw " + las + " --full-resolution -o " + path("a.svg"), "100");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("holds 3 points, estimated to need"), std::string::npos) << r.err;
  // Streamed through the CLI with --voxel, --classes applying while streaming.
  const CommandRun info = run("info " + las + " --voxel 0.1 --classes 2,6");
  ASSERT_EQ(info.status, 0) << info.err;
  EXPECT_NE(info.out.find("streamed) by --voxel"), std::string::npos) << info.out;
}

}  // namespace
}  // namespace pcsketch
