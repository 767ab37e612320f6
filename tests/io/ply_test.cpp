#include "pcsketch/io/ply.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "io_test_util.h"
#include "pcsketch/core/error.h"
#include "pcsketch/io/read_cloud.h"

namespace pcsketch::io {
namespace {

using test::Layout;
using test::make_ply;
using test::PlyElem;
using test::PlyProp;

constexpr std::array kLayouts{Layout::Ascii, Layout::BinaryLE, Layout::BinaryBE};
// Every scalar type under both of its names.
constexpr std::array<const char*, 16> kTypes{"char",   "int8",    "uchar",  "uint8",  "short", "int16",
                                             "ushort", "uint16",  "int",    "int32",  "uint",  "uint32",
                                             "float",  "float32", "double", "float64"};

bool is_signed(const std::string& t) { return t[0] != 'u'; }

// A vertex element whose coordinates are of type `t`, wrapped in a leading element and trailing faces that the
// reader must skip, with an unrelated property before x and one between the coordinates.
std::vector<PlyElem> every_feature(const std::string& t) {
  const double neg = is_signed(t) ? -1.0 : 0.0;
  PlyElem camera{"camera", {{"float", "fov", ""}, {"int", "ids", "uchar"}}, {{0.5, 2, 7, 9}, {1.5, 0}}};
  PlyElem vertex{"vertex",
                 {{"short", "confidence", ""},
                  {t, "x", ""},
                  {t, "y", ""},
                  {"float", "intensity", ""},
                  {t, "z", ""},
                  {"float", "nx", ""},
                  {"float", "ny", ""},
                  {"float", "nz", ""},
                  {"uchar", "red", ""},
                  {"uchar", "green", ""},
                  {"uchar", "blue", ""}},
                 {}};
  for (int i = 0; i < 5; ++i)
    vertex.rows.push_back({double(-i), double(i), 2.0 * i + neg * 3, 0.25, 100.0 - i, 0, 0, 1, double(i), 200, 255});
  PlyElem face{
      "face", {{"int", "vertex_indices", "uchar"}, {"uchar", "flags", ""}}, {{3, 0, 1, 2, 1}, {4, 1, 2, 3, 4, 0}}};
  return {camera, vertex, face};
}

TEST(Ply, EveryScalarTypeAndLayoutRoundTrips) {
  test::TempDir dir;
  for (const Layout layout : kLayouts) {
    for (const std::string t : kTypes) {
      SCOPED_TRACE(std::string(test::layout_name(layout)) + " " + t);
      const std::string path = dir.write("cloud.ply", make_ply(every_feature(t), layout));
      const ReadResult r = read_point_cloud(path, {.recentre = false});
      EXPECT_EQ(r.format, std::string("ply ") + test::layout_name(layout));
      ASSERT_EQ(r.cloud.size(), 5u);
      ASSERT_TRUE(r.cloud.has_normals());
      ASSERT_TRUE(r.cloud.has_colors());
      const double neg = is_signed(t) ? -1.0 : 0.0;
      for (int i = 0; i < 5; ++i) {
        EXPECT_EQ(r.cloud.world(i), Vec3d(i, 2.0 * i + neg * 3, 100.0 - i));
        EXPECT_EQ(r.cloud.normals[i], Vec3f(0, 0, 1));
        EXPECT_EQ(r.cloud.colors[i], (Rgb8{std::uint8_t(i), 200, 255}));
      }
      EXPECT_EQ(r.other_attributes, (std::vector<std::string>{"confidence", "intensity"}));
      EXPECT_EQ(r.dropped_non_finite, 0u);

      const Mesh mesh = read_mesh(path);
      ASSERT_EQ(mesh.vertices.size(), 5u);
      // The quad becomes a fan of two triangles.
      ASSERT_EQ(mesh.faces.size(), 3u);
      EXPECT_EQ(mesh.faces[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
      EXPECT_EQ(mesh.faces[1], (std::array<std::uint32_t, 3>{1, 2, 3}));
      EXPECT_EQ(mesh.faces[2], (std::array<std::uint32_t, 3>{1, 3, 4}));
    }
  }
}

TEST(Ply, FloatColoursScaleFromUnitRange) {
  test::TempDir dir;
  const PlyElem v{"vertex",
                  {{"float", "x", ""},
                   {"float", "y", ""},
                   {"float", "z", ""},
                   {"float", "red", ""},
                   {"float", "green", ""},
                   {"float", "blue", ""}},
                  {{0, 0, 0, 1.0, 0.5, 0.0}}};
  const ReadResult r = read_point_cloud(dir.write("c.ply", make_ply({v}, Layout::BinaryLE)));
  EXPECT_EQ(r.cloud.colors[0], (Rgb8{255, 128, 0}));
}

PointCloud utm_cloud() {
  PointCloud c;
  c.origin = Vec3d(500000.0, 4649776.0, 200.0);
  for (int i = 0; i < 100; ++i)
    c.positions.push_back(Vec3f(0.123f + 0.001f * float(i), 0.456f - 0.002f * float(i), 0.789f));
  c.normals.assign(100, Vec3f(0, 1, 0));
  c.colors.assign(100, Rgb8{1, 2, 3});
  return c;
}

TEST(PlyWriter, RoundTripsEveryLayoutWithAttributes) {
  test::TempDir dir;
  const PointCloud cloud = utm_cloud();
  std::vector<float> curvature(cloud.size());
  std::vector<std::int32_t> label(cloud.size());
  std::vector<std::uint8_t> flag(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    curvature[i] = 0.1f * float(i) - 3.f;
    label[i] = int(i) * 1000 - 7;
    flag[i] = std::uint8_t(i);
  }
  const std::vector<PlyAttribute> attributes{{"k1", std::span<const float>(curvature)},
                                             {"label", std::span<const std::int32_t>(label)},
                                             {"flag", std::span<const std::uint8_t>(flag)}};
  for (const PlyFormat f : {PlyFormat::Ascii, PlyFormat::BinaryLittleEndian, PlyFormat::BinaryBigEndian}) {
    const std::string path = dir.file("out.ply");
    write_ply(path, cloud, attributes, {.format = f, .comments = {"written by a test"}});
    const ReadResult r = read_point_cloud(path);
    ASSERT_EQ(r.cloud.size(), cloud.size());
    EXPECT_NE(r.cloud.origin, Vec3d::Zero());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      // World coordinates went through double: relative positions come back within float rounding of the origin.
      EXPECT_LT((r.cloud.world(i) - cloud.world(i)).norm(), 1e-6);
      EXPECT_EQ(r.cloud.normals[i], cloud.normals[i]);
      EXPECT_EQ(r.cloud.colors[i], cloud.colors[i]);
    }
    EXPECT_EQ(r.other_attributes, (std::vector<std::string>{"k1", "label", "flag"}));
  }
}

TEST(PlyWriter, NoOriginWritesExactFloats) {
  test::TempDir dir;
  PointCloud cloud;
  cloud.positions = {Vec3f(0.1f, -0.2f, 0.3f), Vec3f(1e-7f, 3.4e38f, -0.f)};
  const std::string path = dir.file("f.ply");
  write_ply(path, cloud);
  const ReadResult r = read_point_cloud(path, {.recentre = false});
  EXPECT_EQ(r.cloud.positions, cloud.positions);
  EXPECT_FALSE(r.cloud.has_normals());
}

TEST(PlyWriter, RejectsBadAttributes) {
  test::TempDir dir;
  const PointCloud cloud = utm_cloud();
  const std::vector<float> short_values(3);
  EXPECT_THROW(write_ply(dir.file("a.ply"), cloud, {{"k", std::span<const float>(short_values)}}), Error);
  const std::vector<float> values(cloud.size());
  EXPECT_THROW(write_ply(dir.file("a.ply"), cloud, {{"two words", std::span<const float>(values)}}), Error);
  EXPECT_THROW(write_ply(dir.file("no/such/dir/a.ply"), cloud), Error);
}

TEST(Ply, UtmOffsetsKeepSubMillimetrePrecision) {
  test::TempDir dir;
  PlyElem v{"vertex", {{"double", "x", ""}, {"double", "y", ""}, {"double", "z", ""}}, {}};
  for (int i = 0; i < 50; ++i) v.rows.push_back({500000.123 + 0.0001 * i, 4649776.456 - 0.0007 * i, 312.5 + 0.01 * i});
  for (const Layout layout : kLayouts) {
    const ReadResult r = read_point_cloud(dir.write("utm.ply", make_ply({v}, layout)));
    EXPECT_NE(r.cloud.origin, Vec3d::Zero());
    for (int i = 0; i < 50; ++i) {
      const Vec3d expected(v.rows[i][0], v.rows[i][1], v.rows[i][2]);
      EXPECT_LT((r.cloud.world(i) - expected).cwiseAbs().maxCoeff(), 1e-4) << i;  // 0.1 mm
    }
    // Differences between points, what geometry uses, survive at the 0.1 mm step.
    EXPECT_NEAR(r.cloud.positions[1].x() - r.cloud.positions[0].x(), 0.0001, 1e-6);
  }
  // Without recentring float positions of 4.6e6 are only good to 0.5 m: the option matters.
  const ReadResult raw = read_point_cloud(dir.file("utm.ply"), {.recentre = false});
  EXPECT_GT(std::abs(raw.cloud.world(0).y() - 4649776.456), 1e-3);
}

TEST(Ply, SinglePointAndKeepOptions) {
  test::TempDir dir;
  const PlyElem v{"vertex",
                  {{"float", "x", ""},
                   {"float", "y", ""},
                   {"float", "z", ""},
                   {"float", "nx", ""},
                   {"float", "ny", ""},
                   {"float", "nz", ""}},
                  {{1, 2, 3, 0, 0, 1.01}}};
  const std::string path = dir.write("one.ply", make_ply({v}, Layout::Ascii));
  const ReadResult r = read_point_cloud(path);
  ASSERT_EQ(r.cloud.size(), 1u);
  EXPECT_EQ(r.cloud.world(0), Vec3d(1, 2, 3));
  // Within the unit-length tolerance: normalised (further off, they would be recomputed: Columns.NonUnitPly…).
  EXPECT_LT((r.cloud.normals[0] - Vec3f(0, 0, 1)).norm(), 1e-6f);
  EXPECT_FALSE(read_point_cloud(path, {.keep_normals = false}).cloud.has_normals());
}

}  // namespace
}  // namespace pcsketch::io
