// LAS reader: round trips against tests/support/las_writer for every point format and version, VLRs/EVLRs and
// extra bytes skipped, class filters, LAZ refused, and the malformed-file table (each error names file and byte).

#include <gtest/gtest.h>

#include "io_test_util.h"
#include "pcsketch/io/read_cloud.h"
#include "support/las_writer.h"

namespace pcsketch::io {
namespace {

using test::LasFile;
using test::LasPoint;

// Three points of a georeferenced scan (UTM offsets), classes ground, building, noise.
LasFile utm_file(unsigned minor, unsigned format) {
  LasFile f{.minor = minor, .format = format, .scale = Vec3d(0.01, 0.01, 0.001), .offset = Vec3d(500000, 4649000, 0)};
  f.points = {
      {{500000.123, 4649776.456, 100.001}, 120, 1, 2, 2, {65535, 0, 32896}},
      {{500010.5, 4649780.25, 102.5}, 4000, 2, 2, 6, {0, 65535, 257}},
      {{500003.07, 4649790.0, 98.75}, 0, 1, 1, 7, {25700, 51400, 12850}},
  };
  return f;
}

// Versions that allow each point format: 0-1 since 1.0, 2-3 since 1.2, 4-5 since 1.3, 6-10 since 1.4.
unsigned minor_for(unsigned format) { return format < 2 ? 0 : format < 4 ? 2 : format < 6 ? 3 : 4; }

const PointAttribute& attribute(const ReadResult& r, const char* name) {
  const PointAttribute* a = r.cloud.attribute(name);
  EXPECT_NE(a, nullptr) << name;
  static const PointAttribute kNone;
  return a != nullptr ? *a : kNone;
}

// `bytes` with `n` little-endian bytes of `value` written at `offset`.
std::string poked(std::string bytes, std::size_t offset, std::uint64_t value, std::size_t n) {
  test::poke(bytes, offset, value, n);
  return bytes;
}

TEST(Las, EveryPointFormatReadsBackItsValues) {
  for (unsigned format = 0; format <= 10; ++format) {
    SCOPED_TRACE("format " + std::to_string(format));
    const LasFile f = utm_file(minor_for(format), format);
    const ReadResult r = read_point_cloud_from_memory(test::write_las(f), "scan.las");
    EXPECT_EQ(r.format, "las 1." + std::to_string(f.minor) + " point format " + std::to_string(format));
    ASSERT_EQ(r.cloud.size(), 3u);
    EXPECT_EQ(r.cloud.origin, Vec3d(500005, 4649783, 101));  // the existing recentring, fed in double
    for (std::size_t i = 0; i < 3; ++i) {
      const Vec3d expected = test::las_quantised(f, f.points[i].position);
      EXPECT_NEAR((r.cloud.world(i) - expected).cwiseAbs().maxCoeff(), 0.0, 1e-5) << i;
      EXPECT_EQ(attribute(r, "classification").values.at(i), f.points[i].classification);
      EXPECT_EQ(attribute(r, "intensity").values.at(i), f.points[i].intensity);
      EXPECT_EQ(attribute(r, "return_number").values.at(i), f.points[i].return_number);
    }
    const bool rgb = format == 2 || format == 3 || format == 5 || format == 7 || format == 8 || format == 10;
    ASSERT_EQ(r.cloud.has_colors(), rgb);
    if (rgb) {  // 16-bit colours scaled to 8 bits
      EXPECT_EQ(r.cloud.colors[0], (Rgb8{255, 0, 128}));
      EXPECT_EQ(r.cloud.colors[1], (Rgb8{0, 255, 1}));
      EXPECT_EQ(r.cloud.colors[2], (Rgb8{100, 200, 50}));
    }
  }
}

TEST(Las, ScaleAndOffsetAreAppliedInDouble) {
  // A 0.1 mm grid 5·10^6 from the origin: float arithmetic would lose it, double keeps it.
  LasFile f{.minor = 2, .format = 0, .scale = Vec3d::Constant(0.0001), .offset = Vec3d(500000, 5000000, 0)};
  f.points = {{{500000.0001, 5000000.0002, 0.0003}}, {{500000.0002, 5000000.0003, 0.0004}}};
  const ReadResult r = read_point_cloud_from_memory(test::write_las(f), "fine.las");
  ASSERT_EQ(r.cloud.size(), 2u);
  EXPECT_NEAR(r.cloud.positions[1].x() - r.cloud.positions[0].x(), 0.0001, 1e-7);
  EXPECT_NEAR(r.cloud.world(1).y(), 5000000.0003, 1e-6);
}

TEST(Las, EightBitColoursAreKeptAsTheyAre) {
  LasFile f = utm_file(2, 2);
  f.points[0].rgb = {255, 128, 0};
  f.points[1].rgb = {1, 2, 3};
  f.points[2].rgb = {0, 0, 0};
  const ReadResult r = read_point_cloud_from_memory(test::write_las(f), "8bit.las");
  EXPECT_EQ(r.cloud.colors[0], (Rgb8{255, 128, 0}));
  EXPECT_EQ(r.cloud.colors[1], (Rgb8{1, 2, 3}));
}

TEST(Las, VlrsEvlrsAndExtraBytesAreSkippedByTheirLengths) {
  LasFile f = utm_file(4, 6);
  f.vlr_payloads = {std::string(17, 'v'), std::string(), std::string(300, 'w')};
  f.evlr_payloads = {std::string(1000, 'e')};
  f.extra_bytes = 7;
  const ReadResult r = read_point_cloud_from_memory(test::write_las(f), "vlrs.las");
  ASSERT_EQ(r.cloud.size(), 3u);
  EXPECT_NEAR((r.cloud.world(2) - test::las_quantised(f, f.points[2].position)).norm(), 0.0, 1e-5);
  EXPECT_EQ(attribute(r, "classification").values, (std::vector<float>{2, 6, 7}));
  EXPECT_NE(std::find(r.other_attributes.begin(), r.other_attributes.end(), "extra bytes (7 per point)"),
            r.other_attributes.end());
}

TEST(Las, ClassesAreKeptAndDropped) {
  const std::string bytes = test::write_las(utm_file(2, 1));
  const ReadResult kept = read_point_cloud_from_memory(bytes, "c.las", {.classes = {2, 6}});
  EXPECT_EQ(attribute(kept, "classification").values, (std::vector<float>{2, 6}));
  EXPECT_EQ(kept.dropped_by_filter, 1u);
  const ReadResult dropped = read_point_cloud_from_memory(bytes, "c.las", {.drop_classes = {7}});
  EXPECT_EQ(attribute(dropped, "classification").values, (std::vector<float>{2, 6}));
  EXPECT_EQ(attribute(dropped, "intensity").values, (std::vector<float>{120, 4000}));  // arrays stay aligned
  const ReadResult both = read_point_cloud_from_memory(bytes, "c.las", {.classes = {2, 6}, .drop_classes = {6}});
  EXPECT_EQ(attribute(both, "classification").values, (std::vector<float>{2}));
  EXPECT_NE(test::error_of([&] {
              read_point_cloud_from_memory(bytes, "c.las", {.classes = {9}});
            }).find("none of the 3 points"),
            std::string::npos);
  EXPECT_NE(test::error_of([] {
              read_point_cloud_from_memory("0 0 0\n", "t.xyz", {.classes = {2}});
            }).find("no classification"),
            std::string::npos);
}

TEST(Las, CropIsInTheFilesCoordinates) {
  const ReadResult r = read_point_cloud_from_memory(test::write_las(utm_file(2, 0)), "crop.las",
                                                    {.crop = CropBox{{500000, 4649770, 90}, {500004, 4649800, 110}}});
  ASSERT_EQ(r.cloud.size(), 2u);
  EXPECT_EQ(attribute(r, "classification").values, (std::vector<float>{2, 7}));
  EXPECT_EQ(r.dropped_by_filter, 1u);
}

TEST(Las, LazIsRefusedWithOneClearError) {
  const std::string bytes = poked(test::write_las(utm_file(2, 3)), 104, 3 | 0x80, 1);  // LASzip sets bit 7
  const std::string message = test::error_of([&] { read_point_cloud_from_memory(bytes, "scan.laz"); });
  EXPECT_NE(message.find(
                "scan.laz (byte 104): LAS: the file is LAZ, compressed LAS (point format 3), which is not supported"),
            std::string::npos)
      << message;
  LasFile f = utm_file(2, 3);
  f.vlr_payloads = {"x"};
  std::string with_vlr = test::write_las(f);
  with_vlr.replace(227 + 2, 14, "laszip encoded");  // the LASzip VLR's user id, without the format bit
  EXPECT_NE(test::error_of([&] {
              read_point_cloud_from_memory(with_vlr, "vlr.laz");
            }).find("LAZ, compressed LAS (point format 3)"),
            std::string::npos);
}

struct Malformed {
  const char* name;
  std::string bytes;
  const char* expected;  ///< the place and the start of the message
};

std::vector<Malformed> malformed_table() {
  const std::string ok12 = test::write_las(utm_file(2, 0));
  const std::string ok14 = test::write_las(utm_file(4, 6));
  const std::string ok14_legacy = test::write_las(utm_file(4, 1));  // format 1 fills the legacy count too
  return {
      {"header_cut.las", ok12.substr(0, 100), "(byte 100): LAS: file ends inside the header"},
      {"points_cut.las", ok12.substr(0, ok12.size() - 5), "(byte 107): LAS: header claims 3 points of 20"},
      {"lying_count.las", poked(ok12, 107, 4000000000u, 4), "(byte 107): LAS: header claims 4000000000 points"},
      {"lying_count64.las", poked(ok14, 247, std::uint64_t{1} << 62, 8),
       "(byte 247): LAS: header claims 4611686018427387904 points"},
      {"counts_disagree.las", poked(ok14_legacy, 107, 2, 4), "(byte 107): LAS: the legacy point count 2 disagrees"},
      {"short_record.las", poked(ok12, 105, 19, 2), "(byte 105): LAS: point record length 19 is smaller than the 20"},
      {"offset_past_end.las", poked(ok12, 96, ok12.size() + 1, 4), "(byte 96): LAS: offset to point data"},
      // A 1.4 header must be 375 bytes.
      {"header_size.las", poked(ok14, 94, 227, 2), "(byte 94): LAS: header size 227 is not between 375"},
      // One VLR declared, none present: its header would overlap the points.
      {"vlr_overrun.las", poked(ok12, 100, 1, 4), "(byte 227): LAS: variable length record 1 of 1 runs past"},
      {"version.las", poked(ok12, 24, 2, 1), "(byte 24): LAS: version 2.2 is not supported"},
      {"format.las", poked(ok12, 104, 11, 1), "(byte 104): LAS: point data format 11 is not one of 0-10"},
      {"scale.las", poked(ok12, 139, 0, 8), "(byte 131): LAS: a scale factor is zero or not finite"},
      {"magic.las", "LASX" + ok12.substr(4), "(byte 0): LAS: wrong magic"},
  };
}

TEST(Las, EveryMalformedFileGivesOneErrorNamingFileAndByte) {
  const test::TempDir dir;
  for (const Malformed& m : malformed_table()) {
    SCOPED_TRACE(m.name);
    const std::string path = dir.write(m.name, m.bytes);
    const std::string message = test::error_of([&] { read_point_cloud(path); });
    EXPECT_NE(message.find(path + " " + m.expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace pcsketch::io
