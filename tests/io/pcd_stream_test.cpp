// Streamed read with thinning (binary PCD): the same kept points, normals and colours as the in-memory read followed
// by decimate(), for any chunk size; compressed PCD is still read whole; malformed headers fail as before.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "io_test_util.h"
#include "pcsketch/io/decimate.h"
#include "pcsketch/io/read_cloud.h"

namespace pcsketch::io {
namespace {

using test::expect_same_cloud;

// `n` points on a noisy unit sphere around `centre` as a binary PCD (x y z normal_x normal_y normal_z rgb
// intensity), every 89th point NaN.
std::string sphere_pcd(std::size_t n, double centre = 0.0) {
  std::string out =
      "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z normal_x normal_y normal_z rgb intensity\n"
      "SIZE 4 4 4 4 4 4 4 4\nTYPE F F F F F F F F\nCOUNT 1 1 1 1 1 1 1 1\nWIDTH " +
      std::to_string(n) + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(n) + "\nDATA binary\n";
  const std::vector<test::SpherePoint> sphere = test::noisy_sphere(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d& d = sphere[i].direction;
    const double r = sphere[i].radius;
    const float x = i % 89 == 3 ? std::numeric_limits<float>::quiet_NaN() : float(centre + r * d.x());
    const auto rgb = std::bit_cast<float>(std::uint32_t((i % 256) << 16 | (i / 256 % 256) << 8 | 7));
    for (const float v : {x, float(centre + r * d.y()), float(centre + r * d.z()), float(d.x()), float(d.y()),
                          float(d.z()), rgb, float(i)})
      out.append(reinterpret_cast<const char*>(&v), 4);
  }
  return out;
}

// The reference: the whole cloud read, then thinned in memory.
PointCloud whole_then_decimate(const std::string& bytes, const DecimateOptions& d) {
  ReadResult whole = read_point_cloud_from_memory(bytes, "ref.pcd");
  decimate(whole.cloud, d);
  return whole.cloud;
}

TEST(PcdStream, VoxelKeepsThePointsOfTheInMemoryReadForAnyChunk) {
  for (const double centre : {0.0, 512345.0}) {
    SCOPED_TRACE(centre);
    const std::string bytes = sphere_pcd(6000, centre);
    ReadOptions options;
    options.decimate.voxel = 0.1;
    const PointCloud reference = whole_then_decimate(bytes, {.voxel = 0.1});
    ASSERT_LT(reference.size(), 3000u);
    for (const std::size_t chunk : {std::size_t{1}, std::size_t{7}, std::size_t{1000}, std::size_t{1} << 16}) {
      SCOPED_TRACE(chunk);
      options.stream_chunk_points = chunk;
      const ReadResult streamed = read_point_cloud_from_memory(bytes, "s.pcd", options);
      ASSERT_TRUE(streamed.decimation.has_value());
      EXPECT_TRUE(streamed.decimation->streamed);
      EXPECT_EQ(streamed.format, "pcd binary");
      EXPECT_EQ(streamed.points_in_file, 6000u);
      EXPECT_EQ(streamed.dropped_non_finite, 68u);  // i % 89 == 3 for i < 6000
      EXPECT_EQ(streamed.other_attributes, std::vector<std::string>{"intensity"});
      EXPECT_TRUE(streamed.cloud.has_normals());
      EXPECT_TRUE(streamed.cloud.has_colors());
      expect_same_cloud(streamed.cloud, reference);
    }
  }
}

TEST(PcdStream, BudgetAndOtherLayouts) {
  const std::string bytes = sphere_pcd(6000);
  test::expect_budget_rule(bytes, "s.pcd");
  // ascii PCD streams too (ascii_stream_test.cpp); compressed PCD is read whole, then thinned by the same rule.
  const std::string ascii =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 3\nPOINTS 3\nDATA ascii\n0 0 0\n1 0 0\n0.01 0 0\n";
  const ReadResult text = read_point_cloud_from_memory(ascii, "a.pcd", {.decimate = {.voxel = 0.5}});
  ASSERT_TRUE(text.decimation.has_value());
  EXPECT_TRUE(text.decimation->streamed);
  EXPECT_EQ(text.cloud.size(), 2u);
  // Class filters on a streamable file without classes: the whole read's error, not a silently empty filter.
  const std::string message = test::error_of(
      [&] { read_point_cloud_from_memory(bytes, "s.pcd", {.classes = {2}, .decimate = {.voxel = 0.1}}); });
  EXPECT_NE(message.find("no classification to keep or drop classes by"), std::string::npos) << message;
}

TEST(PcdStream, MalformedHeadersFailAsInTheWholeRead) {
  const std::string good = sphere_pcd(50);
  std::string lying = good;
  lying.replace(lying.find("POINTS 50"), 9, "POINTS 5000");
  std::string bad_type = good;
  bad_type.replace(bad_type.find("TYPE F"), 6, "TYPE Q");
  const std::vector<std::string> hostile{good.substr(0, good.size() - 3), lying, bad_type,
                                         good.substr(0, good.find("DATA"))};
  test::expect_same_errors(hostile, "bad.pcd", [](const std::string& bytes, const std::string& name, bool thinned) {
    read_point_cloud_from_memory(bytes, name, {.decimate = {.voxel = thinned ? std::optional(0.1) : std::nullopt}});
  });
}

TEST(PcdStream, MappedFileGivesTheSamePoints) {
  const test::TempDir dir;
  const std::string bytes = sphere_pcd(20000);
  const std::string path = dir.write("s.pcd", bytes);
  ReadOptions options;
  options.decimate.voxel = 0.05;
  options.stream_chunk_points = 1000;  // pages released between chunks
  expect_same_cloud(read_point_cloud(path, options).cloud, read_point_cloud_from_memory(bytes, "s.pcd", options).cloud);
  EXPECT_EQ(points_in_header(path), 20000u);  // --full-resolution's early memory check
  EXPECT_THROW(points_in_header(dir.write("cut.pcd", bytes.substr(0, bytes.size() - 1))), Error);
}

}  // namespace
}  // namespace pcsketch::io
