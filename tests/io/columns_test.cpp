// Text column layouts: colours are not taken as normals, header rows and --columns name the columns, and normals
// that are not unit vectors (text, PLY) are recomputed rather than trusted.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "io_test_util.h"
#include "pcsketch/io/read_cloud.h"

namespace pcsketch::io {
namespace {

const PointAttribute* intensity(const ReadResult& r) { return r.cloud.attribute("intensity"); }

bool mentions(const Warnings& warnings, const std::string& text) {
  return std::any_of(warnings.begin(), warnings.end(),
                     [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

TEST(Columns, CloudCompareRgbIsColourNotNormals) {
  const ReadResult r = read_point_cloud_from_memory("0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 10 20 30\n", "rgb.xyz");
  EXPECT_FALSE(r.cloud.has_normals());
  ASSERT_TRUE(r.cloud.has_colors());
  EXPECT_EQ(r.cloud.colors[2], (Rgb8{10, 20, 30}));
  EXPECT_EQ(r.columns, "x,y,z,r,g,b (guessed from the values)");
  EXPECT_TRUE(r.warnings.empty());
}

TEST(Columns, ColoursInUnitRangeAreScaled) {
  const ReadResult r = read_point_cloud_from_memory("0 0 0 0.2 0.4 0.6\n1 0 0 1 0.5 0\n", "unit.txt");
  EXPECT_FALSE(r.cloud.has_normals());
  ASSERT_TRUE(r.cloud.has_colors());
  EXPECT_EQ(r.cloud.colors[0], (Rgb8{51, 102, 153}));
  EXPECT_EQ(r.cloud.colors[1], (Rgb8{255, 128, 0}));
}

TEST(Columns, UnitNormalsStayNormals) {
  std::mt19937 rng(42);
  std::normal_distribution<double> gauss;
  std::string text;
  std::vector<Vec3f> expected;
  for (int i = 0; i < 200; ++i) {
    const Vec3d n = Vec3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    char line[128];
    std::snprintf(line, sizeof line, "%d 0 %d %.6f %.6f %.6f\n", i, i % 7, n.x(), n.y(), n.z());
    text += line;
    expected.push_back(n.cast<float>());
  }
  const ReadResult r = read_point_cloud_from_memory(text, "normals.xyz");
  ASSERT_TRUE(r.cloud.has_normals());
  EXPECT_FALSE(r.cloud.has_colors());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_LT((r.cloud.normals[i] - expected[i]).norm(), 1e-5f);
  EXPECT_EQ(r.columns, "x,y,z,nx,ny,nz (guessed from the values)");
}

TEST(Columns, IntensityThenColourInSevenColumns) {
  const ReadResult r = read_point_cloud_from_memory("0 0 0 0.37 200 100 50\n1 2 3 0.5 1 2 3\n", "xyzirgb.xyz");
  EXPECT_FALSE(r.cloud.has_normals());
  ASSERT_TRUE(r.cloud.has_colors());
  EXPECT_EQ(r.cloud.colors[0], (Rgb8{200, 100, 50}));
  ASSERT_NE(intensity(r), nullptr);
  EXPECT_EQ(intensity(r)->values, (std::vector<float>{0.37f, 0.5f}));
}

TEST(Columns, NormalsThenColoursInNineColumns) {
  const ReadResult r = read_point_cloud_from_memory("0 0 0 0 0 1 9 8 7\n1 0 0 0.6 0.8 0 1 2 3\n", "nine.xyz");
  ASSERT_TRUE(r.cloud.has_normals());
  ASSERT_TRUE(r.cloud.has_colors());
  EXPECT_EQ(r.cloud.normals[1], Vec3f(0.6f, 0.8f, 0.f));
  EXPECT_EQ(r.cloud.colors[0], (Rgb8{9, 8, 7}));
}

TEST(Columns, NeitherNormalsNorColoursAreIgnoredWithAWarning) {
  const ReadResult r = read_point_cloud_from_memory("0 0 0 3.5 -20 1000\n1 1 1 2.5 7 8\n", "odd.xyz");
  EXPECT_FALSE(r.cloud.has_normals());
  EXPECT_FALSE(r.cloud.has_colors());
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("columns 4-6 ignored"), std::string::npos) << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("--columns"), std::string::npos) << r.warnings[0];
  EXPECT_EQ(r.other_attributes, (std::vector<std::string>{"column 4", "column 5", "column 6"}));
}

TEST(Columns, HeaderRowsNameTheColumns) {
  struct Case {
    const char* name;
    const char* text;
  };
  const std::vector<Case> cases{
      {"cc.csv", "//X,Y,Z,R,G,B\n1.5,2.5,3.5,10,20,30\n"},
      {"quoted.csv", "\"X\",\"Y\",\"Z\",\"Red\",\"Green\",\"Blue\"\n1.5,2.5,3.5,10,20,30\n"},
      {"survey.csv", "Easting,Northing,Elevation,r,g,b\n1.5,2.5,3.5,10,20,30\n"},
      {"hash.txt", "# x y z red green blue\n1.5 2.5 3.5 10 20 30\n"},
      {"reordered.csv", "B;G;R;z;y;x\n30;20;10;3.5;2.5;1.5\n"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const ReadResult r = read_point_cloud_from_memory(c.text, c.name, {.recentre = false});
    ASSERT_EQ(r.cloud.size(), 1u);
    EXPECT_EQ(r.cloud.world(0), Vec3d(1.5, 2.5, 3.5));
    ASSERT_TRUE(r.cloud.has_colors());
    EXPECT_EQ(r.cloud.colors[0], (Rgb8{10, 20, 30}));
    EXPECT_FALSE(r.cloud.has_normals());
    EXPECT_NE(r.columns.find("(header)"), std::string::npos) << r.columns;
  }
}

TEST(Columns, ExplicitColumnsOverrideTheGuess) {
  const std::string text = "id,x,y,z,i,nx,ny,nz\n7,1,2,3,40,0,0,1\n8,4,5,6,41,0,1,0\n";
  const ReadResult r = read_point_cloud_from_memory(
      text, "mapped.csv", {.recentre = false, .columns = parse_columns("skip,x,y,z,i,nx,ny,nz")});
  ASSERT_EQ(r.cloud.size(), 2u);
  EXPECT_EQ(r.cloud.world(1), Vec3d(4, 5, 6));
  EXPECT_EQ(r.cloud.normals[1], Vec3f(0, 1, 0));
  EXPECT_EQ(intensity(r)->values, (std::vector<float>{40, 41}));
  EXPECT_EQ(r.columns, "skip,x,y,z,i,nx,ny,nz (--columns)");
  // Without --columns the same six values after the id would be a guess; with it, rgb ints are taken as asked.
  const ReadResult rgb =
      read_point_cloud_from_memory("0 0 0 0 0 1\n", "n.xyz", {.columns = parse_columns("x,y,z,r,g,b")});
  EXPECT_EQ(rgb.cloud.colors.at(0), (Rgb8{0, 0, 1}));
}

TEST(Columns, BadColumnListsAreRejected) {
  EXPECT_NE(test::error_of([] { parse_columns("x,y,q"); }).find("unknown column \"q\""), std::string::npos);
  EXPECT_NE(test::error_of([] { parse_columns("x,x,y,z"); }).find("named twice"), std::string::npos);
  EXPECT_NE(test::error_of([] { parse_columns("x,y,r,g,b"); }).find("must include x, y and z"), std::string::npos);
  EXPECT_EQ(parse_columns("X,Y,Z,skip,skip,Intensity").size(), 6u);
}

TEST(Columns, NonUnitPlyNormalsAreRecomputedWithAWarning) {
  const auto ply_with_nz = [](double nz) {
    test::PlyElem vertex{"vertex", {}, {}};
    for (const char* name : {"x", "y", "z", "nx", "ny", "nz"}) vertex.props.push_back({"float", name, ""});
    for (int i = 0; i < 10; ++i) vertex.rows.push_back({double(i), 0, 0, 0, 0, nz});
    return test::make_ply({vertex}, test::Layout::BinaryLE);
  };
  const ReadResult r = read_point_cloud_from_memory(ply_with_nz(2.0), "long.ply");
  EXPECT_FALSE(r.cloud.has_normals());
  EXPECT_TRUE(mentions(r.warnings, "not unit vectors")) << (r.warnings.empty() ? "" : r.warnings[0]);
  const ReadResult ok = read_point_cloud_from_memory(ply_with_nz(1.0), "unit.ply");
  EXPECT_TRUE(ok.cloud.has_normals());
  EXPECT_TRUE(ok.warnings.empty());
}

}  // namespace
}  // namespace pcsketch::io
