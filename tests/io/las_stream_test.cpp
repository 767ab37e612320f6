// Streamed read with thinning (LAS): the same kept points, colours and attributes as the in-memory read followed by
// decimate(), for any chunk size; class filters while streaming; files within the budget read as before; malformed
// headers fail with the same message on both paths.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "io_test_util.h"
#include "pcsketch/io/decimate.h"
#include "pcsketch/io/read_cloud.h"
#include "support/las_writer.h"

namespace pcsketch::io {
namespace {

using test::expect_same_cloud;
using test::LasFile;
using test::LasPoint;

// `n` points of a terrain tile at UTM offsets, one per metre of a jittered grid (no two alike, so that the whole
// read's duplicate collapse has nothing to do), classes 2, 6 and 7, intensities and return numbers varying.
LasFile terrain(std::size_t n, unsigned minor, unsigned format, std::uint16_t colour_scale = 257) {
  LasFile f{.minor = minor, .format = format, .scale = Vec3d(0.001, 0.001, 0.001), .offset = Vec3d(500000, 4649000, 0)};
  std::mt19937 mt(42);
  std::uniform_real_distribution<double> jitter(-0.4, 0.4);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = double(i % 80) + jitter(mt), y = double(i / 80) + jitter(mt);
    LasPoint p;
    p.position = Vec3d(500000 + x, 4649000 + y, 100 + 3 * std::sin(x / 7) + std::cos(y / 5) + 0.2 * jitter(mt));
    p.intensity = static_cast<std::uint16_t>(i * 37 % 65536);
    p.return_number = static_cast<std::uint8_t>(1 + i % 3);
    p.number_of_returns = 3;
    p.classification = std::array<std::uint8_t, 3>{2, 6, 7}[i % 3 == 0 ? 0 : i % 5 == 0 ? 2 : 1];
    p.rgb = {static_cast<std::uint16_t>(i % 256 * colour_scale),
             static_cast<std::uint16_t>(i / 256 % 256 * colour_scale), static_cast<std::uint16_t>(7 * colour_scale)};
    f.points.push_back(p);
  }
  return f;
}

// The reference: the whole cloud read (filters included), then thinned in memory.
PointCloud read_then_decimate(const std::string& bytes, const DecimateOptions& d, ReadOptions options = {}) {
  options.decimate = {};
  ReadResult whole = read_point_cloud_from_memory(bytes, "ref.las", options);
  decimate(whole.cloud, d);
  return whole.cloud;
}

TEST(LasStream, VoxelKeepsThePointsColoursAndAttributesOfTheInMemoryRead) {
  for (const unsigned format : {1u, 3u, 7u}) {
    SCOPED_TRACE("format " + std::to_string(format));
    const std::string bytes = test::write_las(terrain(6000, format < 6 ? 2 : 4, format));
    ReadOptions options;
    options.decimate.voxel = 2.5;
    const PointCloud reference = read_then_decimate(bytes, {.voxel = 2.5});
    ASSERT_LT(reference.size(), 2000u);
    for (const std::size_t chunk : {std::size_t{1}, std::size_t{7}, std::size_t{1000}, std::size_t{1} << 16}) {
      SCOPED_TRACE(chunk);
      options.stream_chunk_points = chunk;
      const ReadResult streamed = read_point_cloud_from_memory(bytes, "t.las", options);
      ASSERT_TRUE(streamed.decimation.has_value());
      EXPECT_TRUE(streamed.decimation->streamed);
      EXPECT_EQ(streamed.points_in_file, 6000u);
      EXPECT_EQ(streamed.format,
                "las 1." + std::to_string(format < 6 ? 2 : 4) + " point format " + std::to_string(format));
      EXPECT_EQ(streamed.other_attributes, read_point_cloud_from_memory(bytes, "t.las").other_attributes);
      EXPECT_EQ(streamed.cloud.has_colors(), format != 1);
      ASSERT_NE(streamed.cloud.attribute("return_number"), nullptr);
      expect_same_cloud(streamed.cloud, reference);
    }
  }
}

TEST(LasStream, ColourDepthIsDecidedOverTheWholeFile) {
  // 8-bit values stored unscaled stay as they are; one 16-bit value anywhere scales every colour.
  LasFile f = terrain(3000, 2, 2, /*colour_scale=*/1);
  for (const bool wide : {false, true}) {
    SCOPED_TRACE(wide);
    if (wide) f.points[2999].rgb = {65535, 0, 0};
    const std::string bytes = test::write_las(f);
    ReadOptions options;
    options.decimate.voxel = 3.0;
    options.stream_chunk_points = 100;
    const PointCloud streamed = read_point_cloud_from_memory(bytes, "c.las", options).cloud;
    expect_same_cloud(streamed, read_then_decimate(bytes, {.voxel = 3.0}));
    for (const Rgb8& c : streamed.colors) ASSERT_EQ(c[2], wide ? 0 : 7);  // every blue is 7
  }
}

TEST(LasStream, ClassFiltersAndCropApplyWhileStreaming) {
  const std::string bytes = test::write_las(terrain(6000, 2, 3));
  const CropBox crop{{500010, 4649000, 0}, {500060, 4649100, 200}};
  for (const ReadOptions& filters : {ReadOptions{.classes = {2, 6}}, ReadOptions{.drop_classes = {7}},
                                     ReadOptions{.classes = {2, 7}, .drop_classes = {7}, .crop = crop}}) {
    ReadOptions options = filters;
    options.decimate.voxel = 2.0;
    options.stream_chunk_points = 333;
    const ReadResult streamed = read_point_cloud_from_memory(bytes, "f.las", options);
    ASSERT_TRUE(streamed.decimation.has_value());
    EXPECT_TRUE(streamed.decimation->streamed);
    const ReadResult whole = read_point_cloud_from_memory(bytes, "f.las", filters);
    EXPECT_GE(streamed.dropped_by_filter, 800u);  // class 7: 800 of 6000
    EXPECT_EQ(streamed.dropped_by_filter, whole.dropped_by_filter);
    EXPECT_EQ(streamed.decimation->points_before, whole.cloud.size());
    expect_same_cloud(streamed.cloud, read_then_decimate(bytes, {.voxel = 2.0}, filters));
    for (const float c : streamed.cloud.attribute("classification")->values)
      EXPECT_TRUE(std::find(filters.drop_classes.begin(), filters.drop_classes.end(), int(c)) ==
                  filters.drop_classes.end());
  }
  // Nothing left: the whole read's message.
  ReadOptions none{.classes = {9}};
  const std::string expected = test::error_of([&] { read_point_cloud_from_memory(bytes, "f.las", none); });
  none.decimate.voxel = 2.0;
  EXPECT_EQ(test::error_of([&] { read_point_cloud_from_memory(bytes, "f.las", none); }), expected);
  EXPECT_NE(expected.find("none of the 6000 points is left by the class filters"), std::string::npos) << expected;
}

TEST(LasStream, WithinTheBudgetReadsAsBeforeOverItIsThinnedToAPixel) {
  const std::string bytes = test::write_las(terrain(6000, 4, 8));
  ReadOptions options;
  options.decimate.resolution = OutputResolution{};  // 2,097,152 points: far above
  const ReadResult within = read_point_cloud_from_memory(bytes, "t.las", options);
  EXPECT_FALSE(within.decimation.has_value());
  expect_same_cloud(within.cloud, read_point_cloud_from_memory(bytes, "t.las").cloud);

  options.decimate.resolution = OutputResolution{.width = 40, .height = 40, .budget_points = 1000};
  const ReadResult over = read_point_cloud_from_memory(bytes, "t.las", options);
  ASSERT_TRUE(over.decimation.has_value());
  EXPECT_TRUE(over.decimation->streamed);
  EXPECT_NE(over.decimation->reason.find("over the 1000 budget"), std::string::npos) << over.decimation->reason;
  expect_same_cloud(over.cloud, read_then_decimate(bytes, {.voxel = over.decimation->cell}));
  // --max-points after the stream keeps the attributes aligned, as decimate() on the whole cloud does.
  options.decimate.max_points = 100;
  const ReadResult fewer = read_point_cloud_from_memory(bytes, "t.las", options);
  ASSERT_LE(fewer.cloud.size(), 100u);
  EXPECT_EQ(fewer.cloud.attribute("intensity")->values.size(), fewer.cloud.size());
  EXPECT_EQ(fewer.cloud.colors.size(), fewer.cloud.size());
}

// `bytes` with `n` little-endian bytes of `value` written at `offset`.
std::string poked(std::string bytes, std::size_t offset, std::uint64_t value, std::size_t n) {
  test::poke(bytes, offset, value, n);
  return bytes;
}

TEST(LasStream, MalformedHeadersFailAsInTheWholeRead) {
  const std::string ok12 = test::write_las(terrain(50, 2, 0));
  const std::string ok14 = test::write_las(terrain(50, 4, 6));
  const std::vector<std::string> hostile{
      ok12.substr(0, 100),                                   // ends inside the header
      ok12.substr(0, ok12.size() - 5),                       // the last record cut
      poked(ok12, 107, 4000000000u, 4),                      // a lying count
      poked(ok14, 247, std::uint64_t{1} << 62, 8),           // a lying 64-bit count
      poked(test::write_las(terrain(50, 4, 1)), 107, 2, 4),  // legacy and 64-bit counts disagree
      poked(ok12, 105, 19, 2),                               // record shorter than its format
      poked(ok12, 96, ok12.size() + 1, 4),                   // points start past the end
      poked(ok12, 100, 1, 4),                                // a VLR overlapping the points
      poked(ok12, 104, 3 | 0x80, 1),                         // LAZ
      poked(ok12, 139, 0, 8),                                // zero scale
  };
  test::expect_same_errors(hostile, "bad.las", [](const std::string& bytes, const std::string& name, bool thinned) {
    read_point_cloud_from_memory(bytes, name, {.decimate = {.voxel = thinned ? std::optional(1.0) : std::nullopt}});
  });
}

TEST(LasStream, MappedFileGivesTheSamePointsAndItsHeaderCount) {
  const test::TempDir dir;
  const std::string bytes = test::write_las(terrain(20000, 4, 7));
  const std::string path = dir.write("t.las", bytes);
  ReadOptions options;
  options.decimate.voxel = 1.5;
  options.stream_chunk_points = 1000;  // pages released between chunks and while the kept records are read back
  expect_same_cloud(read_point_cloud(path, options).cloud, read_point_cloud_from_memory(bytes, "t.las", options).cloud);
  EXPECT_EQ(points_in_header(path), 20000u);
  EXPECT_THROW(points_in_header(dir.write("cut.las", bytes.substr(0, bytes.size() - 1))), Error);
}

}  // namespace
}  // namespace pcsketch::io
