// Streamed read with thinning (PLY; more ascii cases in ascii_stream_test.cpp): the same kept points as the in-memory
// read followed by decimate(), for any chunk size; clouds within the resolution budget are read as before; malformed
// files still fail cleanly.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "io_test_util.h"
#include "pcsketch/io/decimate.h"
#include "pcsketch/io/read_cloud.h"

namespace pcsketch::io {
namespace {

using test::expect_same_cloud;
using test::Layout;
using test::make_ply;
using test::PlyElem;

// `n` points on a noisy sphere of radius 1 around `centre`, unit normals, colours, and every 97th point NaN.
std::string sphere_ply(std::size_t n, Layout layout, const std::string& type = "float", double centre = 0.0,
                       bool with_nan = true) {
  PlyElem vertex{"vertex",
                 {{type, "x"},
                  {type, "y"},
                  {type, "z"},
                  {"float", "nx"},
                  {"float", "ny"},
                  {"float", "nz"},
                  {"uchar", "red"},
                  {"uchar", "green"},
                  {"uchar", "blue"},
                  {"float", "quality"}},
                 {}};
  const std::vector<test::SpherePoint> sphere = test::noisy_sphere(n);
  // Float coordinates rounded here, so that an ascii file holds the values of the binary one. (The test of the type
  // stays out of the lambda: GCC 12 at -O2 left `type == "float" ? double(float(v)) : v` unrounded there.)
  const bool as_float = type == "float";
  const auto coordinate = [as_float](double v) { return as_float ? double(float(v)) : v; };
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d& d = sphere[i].direction;
    const double r = sphere[i].radius;
    const double x =
        with_nan && i % 97 == 5 ? std::numeric_limits<double>::quiet_NaN() : coordinate(centre + r * d.x());
    vertex.rows.push_back({x, coordinate(centre + r * d.y()), coordinate(centre + r * d.z()), d.x(), d.y(), d.z(),
                           double(i % 256), double(i / 256 % 256), 7.0, double(i)});
  }
  return make_ply({vertex}, layout);
}

// The reference: the whole cloud read, then thinned in memory.
PointCloud read_then_decimate(const std::string& bytes, const DecimateOptions& d, ReadOptions options = {}) {
  options.collapse_duplicates = true;
  ReadResult whole = read_point_cloud_from_memory(bytes, "ref.ply", options);
  decimate(whole.cloud, d);
  return whole.cloud;
}

TEST(StreamRead, VoxelKeepsThePointsOfTheInMemoryReadThenDecimate) {
  for (const Layout layout : {Layout::BinaryLE, Layout::BinaryBE}) {
    for (const std::string type : {"float", "double"}) {
      SCOPED_TRACE(type);
      const std::string bytes = sphere_ply(20000, layout, type);
      ReadOptions options;
      options.decimate.voxel = 0.05;
      const ReadResult streamed = read_point_cloud_from_memory(bytes, "s.ply", options);
      ASSERT_TRUE(streamed.decimation.has_value());
      EXPECT_TRUE(streamed.decimation->streamed);
      EXPECT_EQ(streamed.decimation->reason, "--voxel");
      EXPECT_EQ(streamed.points_in_file, 20000u);
      EXPECT_EQ(streamed.dropped_non_finite, 207u);  // i % 97 == 5 for i < 20000
      EXPECT_EQ(streamed.decimation->points_before, 20000u - 207u);
      EXPECT_LT(streamed.cloud.size(), 10000u);  // 6820 cells of 0.05 on the sphere
      EXPECT_EQ(streamed.decimation->points_after, streamed.cloud.size());
      EXPECT_EQ(streamed.format, layout == Layout::BinaryLE ? "ply binary_little_endian" : "ply binary_big_endian");
      EXPECT_EQ(streamed.other_attributes, std::vector<std::string>{"quality"});
      expect_same_cloud(streamed.cloud, read_then_decimate(bytes, {.voxel = 0.05}));
    }
  }
}

TEST(StreamRead, FarAwayCloudIsRecentredAsInMemory) {
  // UTM-like offsets: the origin moves, the grid is anchored on the float box as decimate() anchors it.
  const std::string bytes = sphere_ply(5000, Layout::BinaryLE, "double", 512345.678, false);
  ReadOptions options;
  options.decimate.voxel = 0.1;
  const ReadResult streamed = read_point_cloud_from_memory(bytes, "utm.ply", options);
  EXPECT_EQ(streamed.cloud.origin, Vec3d::Constant(512346.0));
  expect_same_cloud(streamed.cloud, read_then_decimate(bytes, {.voxel = 0.1}));
}

TEST(StreamRead, ChunkSizeDoesNotChangeTheKeptPoints) {
  const std::string bytes = sphere_ply(3000, Layout::BinaryLE);
  ReadOptions options;
  options.decimate.voxel = 0.08;
  const PointCloud reference = read_point_cloud_from_memory(bytes, "s.ply", options).cloud;
  for (const std::size_t chunk : {std::size_t{1}, std::size_t{7}, std::size_t{1000}, std::size_t{2999}}) {
    SCOPED_TRACE(chunk);
    options.stream_chunk_points = chunk;
    expect_same_cloud(read_point_cloud_from_memory(bytes, "s.ply", options).cloud, reference);
  }
}

TEST(StreamRead, CropAppliesWhileStreaming) {
  const std::string bytes = sphere_ply(8000, Layout::BinaryLE);
  ReadOptions options;
  options.crop = CropBox{{-2, -2, 0}, {2, 2, 2}};
  options.decimate.voxel = 0.05;
  const ReadResult streamed = read_point_cloud_from_memory(bytes, "s.ply", options);
  EXPECT_TRUE(streamed.decimation->streamed);
  ReadOptions whole = options;
  whole.decimate = {};
  const ReadResult in_memory = read_point_cloud_from_memory(bytes, "s.ply", whole);
  EXPECT_EQ(streamed.dropped_by_filter, in_memory.dropped_by_filter);
  EXPECT_GT(streamed.dropped_by_filter, 3000u);
  expect_same_cloud(streamed.cloud, read_then_decimate(bytes, {.voxel = 0.05}, whole));
}

TEST(StreamRead, CloudWithinTheResolutionBudgetIsReadAsBefore) {
  const std::string bytes = sphere_ply(20000, Layout::BinaryLE);
  ReadOptions options;
  options.decimate.resolution = OutputResolution{};  // 1024 x 1024: a budget of 2,097,152 points
  const ReadResult r = read_point_cloud_from_memory(bytes, "s.ply", options);
  EXPECT_FALSE(r.decimation.has_value());
  expect_same_cloud(r.cloud, read_point_cloud_from_memory(bytes, "s.ply").cloud);
}

TEST(StreamRead, CloudOverTheBudgetIsThinnedToAPixel) {
  const std::string bytes = sphere_ply(20000, Layout::BinaryLE, "float", 0.0, false);
  ReadOptions options;
  options.decimate.resolution = OutputResolution{.width = 64, .height = 32, .budget_points = 10000};
  const ReadResult r = read_point_cloud_from_memory(bytes, "s.ply", options);
  ASSERT_TRUE(r.decimation.has_value());
  EXPECT_TRUE(r.decimation->streamed);
  EXPECT_NE(r.decimation->reason.find("over the 10000 budget of a 64x32 orthographic image"), std::string::npos)
      << r.decimation->reason;
  // The robust box of the unit sphere samples is a little under 2 a side: 2/64 at most.
  EXPECT_GT(r.decimation->cell, 0.028);
  EXPECT_LT(r.decimation->cell, 2.02 / 64);
  // The same rule on a format read whole (OFF, the same float positions) keeps the same points.
  std::string off = "OFF\n20000 0 0\n";
  for (const test::SpherePoint& s : test::noisy_sphere(20000)) {
    for (const double v : s.radius* s.direction) off += test::text_of(double(float(v))) + ' ';
    off.back() = '\n';
  }
  const ReadResult whole = read_point_cloud_from_memory(off, "a.off", options);
  ASSERT_TRUE(whole.decimation.has_value());
  EXPECT_FALSE(whole.decimation->streamed);
  EXPECT_EQ(whole.decimation->cell, r.decimation->cell);
  EXPECT_EQ(whole.cloud.positions, r.cloud.positions);
  // Ascii PLY streams too, with the same cell and points.
  const std::string ascii = sphere_ply(20000, Layout::Ascii, "float", 0.0, false);
  const ReadResult text = read_point_cloud_from_memory(ascii, "a.ply", options);
  ASSERT_TRUE(text.decimation.has_value());
  EXPECT_TRUE(text.decimation->streamed);
  EXPECT_EQ(text.decimation->cell, r.decimation->cell);
  expect_same_cloud(r.cloud, text.cloud);
}

TEST(StreamRead, ResolutionCellKnownAnswers) {
  // Orthographic: the median side over the larger image side (half of it with cell_pixels 0.5).
  EXPECT_DOUBLE_EQ(resolution_cell({.width = 1000, .height = 500}, Vec3d(4, 2, 1)), 2.0 / 1000);
  EXPECT_DOUBLE_EQ(resolution_cell({.width = 1000, .height = 500, .cell_pixels = 0.5}, Vec3d(4, 2, 1)), 1.0 / 1000);
  // Perspective, fov 60: the nearest depth R / sin 30 - R = R, a pixel 2 R tan 30 / height.
  const double r = 0.5 * std::sqrt(3.0);
  EXPECT_NEAR(resolution_cell({.height = 100, .perspective = true, .fov_deg = 60}, Vec3d(1, 1, 1)),
              2.0 * r * std::tan(std::acos(-1.0) / 6) / 100, 1e-12);
}

TEST(StreamRead, MalformedFilesStillFailWithTheByte) {
  ReadOptions options;
  options.decimate.voxel = 0.05;
  const std::string good = sphere_ply(100, Layout::BinaryLE);
  // Cut inside the 60th vertex: the header's count no longer fits the bytes, refused before any point is read.
  const std::string cut = good.substr(0, good.size() - 40 * 27 - 5);
  EXPECT_NE(test::error_of([&] { read_point_cloud_from_memory(cut, "cut.ply", options); }).find("cut.ply (byte "),
            std::string::npos);
  std::string huge = good;
  huge.replace(huge.find("element vertex 100"), 18, "element vertex 1000000000000");
  const std::string message = test::error_of([&] { read_point_cloud_from_memory(huge, "huge.ply", options); });
  EXPECT_NE(message.find("claims 1000000000000 entries"), std::string::npos) << message;
}

TEST(StreamRead, ProgressFalseCancels) {
  const std::string bytes = sphere_ply(5000, Layout::BinaryLE);
  ReadOptions options;
  options.decimate.voxel = 0.05;
  options.stream_chunk_points = 100;
  int calls = 0;
  options.progress = [&](std::string_view, double) { return ++calls < 5; };
  EXPECT_THROW(read_point_cloud_from_memory(bytes, "s.ply", options), Cancelled);
}

TEST(StreamRead, MappedFileGivesTheSamePoints) {
  const test::TempDir dir;
  const std::string bytes = sphere_ply(20000, Layout::BinaryLE);
  const std::string path = dir.write("s.ply", bytes);
  ReadOptions options;
  options.decimate.voxel = 0.03;
  options.stream_chunk_points = 1000;  // pages released between chunks
  expect_same_cloud(read_point_cloud(path, options).cloud, read_point_cloud_from_memory(bytes, "s.ply", options).cloud);
  EXPECT_EQ(points_in_header(path), 20000u);
}

}  // namespace
}  // namespace pcsketch::io
