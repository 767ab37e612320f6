#include "pcsketch/io/read_cloud.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>

#include "io_test_util.h"
#include "pcsketch/core/error.h"

namespace pcsketch::io {
namespace {

using test::error_of;

const std::string kOk = std::string(PCSKETCH_FIXTURES) + "/ok/";
const std::string kBad = std::string(PCSKETCH_FIXTURES) + "/malformed/";

const std::vector<Vec3d> kFive{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};

void expect_five(const ReadResult& r) {
  ASSERT_EQ(r.cloud.size(), kFive.size());
  for (std::size_t i = 0; i < kFive.size(); ++i) EXPECT_EQ(r.cloud.world(i), kFive[i]) << i;
}

TEST(ReadCloud, EveryOkFixtureReadsTheSameFivePoints) {
  for (const char* name : {"tiny_ascii.ply", "tiny_binary_le.ply", "tiny_binary_be.ply", "points.xyz", "points.pts",
                           "points.csv", "points_ascii.pcd", "points_binary.pcd", "points.las", "points_14.las"}) {
    SCOPED_TRACE(name);
    expect_five(read_point_cloud(kOk + name));
  }
}

TEST(ReadCloud, AttributesOfTheFixtures) {
  const ReadResult ply = read_point_cloud(kOk + "tiny_ascii.ply");
  EXPECT_EQ(ply.format, "ply ascii");
  EXPECT_EQ(ply.cloud.colors.at(4), (Rgb8{10, 20, 30}));
  EXPECT_TRUE(read_point_cloud(kOk + "tiny_binary_le.ply").cloud.has_normals());
  const ReadResult xyz = read_point_cloud(kOk + "points.xyz");
  EXPECT_EQ(xyz.cloud.normals.at(2), Vec3f(0, 0, 1));
  const ReadResult pts = read_point_cloud(kOk + "points.pts");
  EXPECT_EQ(pts.cloud.colors.at(0), (Rgb8{255, 128, 0}));
  ASSERT_NE(pts.cloud.attribute("intensity"), nullptr);
  EXPECT_EQ(pts.cloud.attribute("intensity")->values.at(0), 17.f);
  EXPECT_EQ(pts.columns, "x,y,z,i,r,g,b (the PTS convention)");
  const ReadResult csv = read_point_cloud(kOk + "points.csv");
  EXPECT_FALSE(csv.cloud.has_normals());
  ASSERT_NE(csv.cloud.attribute("intensity"), nullptr);
  EXPECT_EQ(csv.cloud.attribute("intensity")->values.at(4), 0.5f);
  for (const char* las : {"points.las", "points_14.las"}) {
    const ReadResult r = read_point_cloud(kOk + las);
    EXPECT_EQ(r.cloud.colors.at(1), (Rgb8{255, 128, 0})) << las;
    EXPECT_EQ(r.cloud.attribute("classification")->values.at(3), 2.f) << las;
    EXPECT_EQ(r.cloud.attribute("intensity")->values.at(3), 103.f) << las;
  }
  for (const char* pcd : {"points_ascii.pcd", "points_binary.pcd"}) {
    const ReadResult r = read_point_cloud(kOk + pcd);
    ASSERT_TRUE(r.cloud.has_colors()) << pcd;
    EXPECT_EQ(r.cloud.colors[3], (Rgb8{0x10, 0x20, 0x30})) << pcd;
  }
}

TEST(ReadCloud, MeshesFromOffObjAndPly) {
  for (const char* name : {"cube.off", "cube.obj"}) {
    SCOPED_TRACE(name);
    const Mesh m = read_mesh(kOk + name);
    EXPECT_EQ(m.vertices.size(), 8u);
    ASSERT_EQ(m.faces.size(), 12u);  // 6 quads, 2 triangles each
    // Every face of the unit cube lies in a coordinate plane x, y or z = 0 or 1.
    for (const auto& f : m.faces) {
      bool planar = false;
      for (int axis = 0; axis < 3; ++axis)
        planar |= m.vertices[f[0]][axis] == m.vertices[f[1]][axis] && m.vertices[f[1]][axis] == m.vertices[f[2]][axis];
      EXPECT_TRUE(planar);
    }
    EXPECT_EQ(read_point_cloud(kOk + name).cloud.size(), 8u);
  }
  EXPECT_EQ(read_mesh(kOk + "tiny_binary_be.ply").faces.size(), 3u);
  EXPECT_NE(error_of([] { read_mesh(kOk + "points.xyz"); }).find("holds no faces"), std::string::npos);
}

TEST(ReadCloud, PcdBinaryCompressed) {
  // A hand-made LZF stream: one literal run with the first point, then one back reference repeating it.
  const float p[3] = {1.5f, -2.f, 3.25f};
  // Field-major layout of 2 identical points: x x y y z z.
  std::string plain;
  for (const float v : {p[0], p[0], p[1], p[1], p[2], p[2]}) plain.append(reinterpret_cast<const char*>(&v), 4);
  std::string lzf;
  lzf += char(23);  // 24 literal bytes
  lzf += plain;
  std::string body = std::string(24, '\0');
  std::memcpy(body.data(), plain.data(), 24);
  const std::uint32_t sizes[2] = {std::uint32_t(lzf.size()), 24};
  const std::string header =
      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\n"
      "DATA binary_compressed\n";
  const std::string file = header + std::string(reinterpret_cast<const char*>(sizes), 8) + lzf;
  // The two points are equal by construction (that is what the back reference repeats): keep both.
  const ReadOptions keep{.recentre = false, .collapse_duplicates = false};
  const ReadResult r = read_point_cloud_from_memory(file, "c.pcd", keep);
  ASSERT_EQ(r.cloud.size(), 2u);
  EXPECT_EQ(r.cloud.positions[1], Vec3f(p[0], p[1], p[2]));

  // Same data, the second half as a back reference: ctrl (len-2)<<5 | offset>>8 with len 4, offset 4-1.
  std::string x4(reinterpret_cast<const char*>(&p[0]), 4), y4(reinterpret_cast<const char*>(&p[1]), 4);
  std::string zz = plain.substr(16);
  std::string lzf2;
  lzf2 += char(3) + x4;
  lzf2 += char((4 - 2) << 5);
  lzf2 += char(3);  // copy 4 bytes from 4 back
  lzf2 += char(3) + y4;
  lzf2 += char((4 - 2) << 5);
  lzf2 += char(3);
  lzf2 += char(7) + zz;
  const std::uint32_t sizes2[2] = {std::uint32_t(lzf2.size()), 24};
  const ReadResult r2 = read_point_cloud_from_memory(
      header + std::string(reinterpret_cast<const char*>(sizes2), 8) + lzf2, "c.pcd", keep);
  ASSERT_EQ(r2.cloud.size(), 2u);
  EXPECT_EQ(r2.cloud.positions[0], Vec3f(p[0], p[1], p[2]));
  EXPECT_EQ(r2.cloud.positions[1], Vec3f(p[0], p[1], p[2]));
}

TEST(ReadCloud, NonFinitePointsAreDroppedWithOneWarning) {
  const std::string text = "0 0 0\nnan 1 1\n1 1 1\n2 inf 2\n3 3 -inf\n4 4 4\n";
  const ReadResult r = read_point_cloud_from_memory(text, "n.xyz");
  EXPECT_EQ(r.cloud.size(), 3u);
  EXPECT_EQ(r.dropped_non_finite, 3u);
  EXPECT_EQ(r.points_in_file, 6u);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("dropped 3 of 6"), std::string::npos);
  EXPECT_EQ(r.cloud.world(2), Vec3d(4, 4, 4));
}

TEST(ReadCloud, ZeroNormalsAreIgnoredWithAWarning) {
  const ReadResult r = read_point_cloud_from_memory("x y z nx ny nz\n0 0 0 0 0 1\n1 1 1 0 0 0\n", "z.xyz");
  EXPECT_FALSE(r.cloud.has_normals());
  EXPECT_EQ(r.warnings.size(), 1u);
}

TEST(ReadCloud, SniffingBeatsTheExtension) {
  const std::string ply = test::make_ply(
      {{"vertex", {{"float", "x", ""}, {"float", "y", ""}, {"float", "z", ""}}, {{1, 2, 3}}}}, test::Layout::BinaryLE);
  EXPECT_EQ(read_point_cloud_from_memory(ply, "misnamed.xyz").format, "ply binary_little_endian");
  EXPECT_EQ(read_point_cloud_from_memory(ply, "no_extension").format, "ply binary_little_endian");
  EXPECT_EQ(read_point_cloud_from_memory("OFF\n1 0 0\n1 2 3\n", "x.txt").format, "off");
  EXPECT_EQ(read_point_cloud_from_memory("1;2;3\n", "semicolons.txt").cloud.size(), 1u);
  // Lines of separators only are blank (found by fuzzing: ".;" crashed the column count).
  EXPECT_EQ(read_point_cloud_from_memory(";\n1,2,3\n, ,\n4,5,6\n", "blank.csv").cloud.size(), 2u);
  EXPECT_THROW(read_point_cloud_from_memory(";", "blank.xyz"), Error);
}

TEST(ReadCloud, UtmTextKeepsSubMillimetrePrecision) {
  const ReadResult r =
      read_point_cloud_from_memory("500000.123 4649776.456 100.001\n500000.124 4649776.457 100.002\n", "utm.xyz");
  EXPECT_EQ(r.cloud.origin, Vec3d(500000, 4649776, 100));
  EXPECT_NEAR(r.cloud.world(0).x(), 500000.123, 1e-5);
  EXPECT_NEAR(r.cloud.world(1).y(), 4649776.457, 1e-5);
  EXPECT_NEAR(r.cloud.positions[1].x() - r.cloud.positions[0].x(), 0.001, 1e-6);
}

struct Malformed {
  const char* file;
  const char* expected;  ///< part of the message (after the file name and place)
  bool mesh = false;
};

TEST(ReadCloud, EveryMalformedFixtureGivesOneClearError) {
  const std::vector<Malformed> cases{
      {"empty.ply", "empty.ply: empty file"},
      {"bad_magic.ply", "bad_magic.ply (byte 0): PLY: wrong magic"},
      {"huge_count.ply", "huge_count.ply (byte 127): PLY: element \"vertex\" claims 1000000000000 entries"},
      {"truncated.ply", "truncated.ply (byte 115): PLY: element \"vertex\" claims 3 entries"},
      {"truncated_faces.ply", "(byte 214): PLY: element \"face\": file ends in the middle", true},
      {"no_end_header.ply", "no_end_header.ply:5: PLY: header has no end_header"},
      {"no_z.ply", "no_z.ply:3: PLY: element \"vertex\" lacks one of the scalar properties x, y, z"},
      {"nonnumeric.ply", "nonnumeric.ply:9: PLY: element \"vertex\": non-numeric value \"five\""},
      {"nonnumeric.xyz", "nonnumeric.xyz:3: XYZ: non-numeric value \"abc\" in column 2"},
      {"two_columns.xyz", "two_columns.xyz:1: XYZ: too few columns (2; need x y z)"},
      {"short_row.xyz", "short_row.xyz:3: XYZ: 2 columns where the first line has 3"},
      {"all_nan.xyz", "all_nan.xyz: xyz: all 3 points have a NaN or infinite coordinate"},
      {"comments_only.xyz", "comments_only.xyz: xyz: the file holds no points"},
      {"huge_count.off", "huge_count.off:2: OFF: header claims 1000000000000 vertices"},
      {"truncated.off", "truncated.off:5: OFF: file ends after 2 of 3 vertices"},
      {"huge_points.pcd", "huge_points.pcd (byte 121): PCD: header claims 1000000000000 points"},
      {"compressed_garbage.pcd", "compressed_garbage.pcd (byte 116): PCD: corrupt LZF-compressed body"},
      {"unknown.dat", "unknown.dat: unknown format"},
  };
  std::size_t fixtures = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kBad)) {
    (void)entry;
    ++fixtures;
  }
  EXPECT_EQ(fixtures, cases.size()) << "every fixture in tests/fixtures/malformed needs an expected message here";
  for (const Malformed& c : cases) {
    SCOPED_TRACE(c.file);
    const std::string path = kBad + c.file;
    const std::string message = error_of([&] { c.mesh ? (void)read_mesh(path) : (void)read_point_cloud(path); });
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(ReadCloud, MissingFileAndDirectory) {
  EXPECT_NE(error_of([] { read_point_cloud("/nonexistent/x.ply"); }).find("/nonexistent/x.ply: cannot open"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_point_cloud(PCSKETCH_FIXTURES); }).find("not a regular file"), std::string::npos);
}

TEST(ReadCloud, HostileHeadersFromMemory) {
  using test::Layout;
  using test::make_ply;
  using test::PlyElem;
  const PlyElem v{"vertex", {{"float", "x", ""}, {"float", "y", ""}, {"float", "z", ""}}, {{1, 2, 3}}};
  const PlyElem f{"face", {{"int", "vertex_indices", "uint"}}, {{3, 0, 0, 7}}};
  for (const Layout layout : {Layout::Ascii, Layout::BinaryLE, Layout::BinaryBE}) {
    SCOPED_TRACE(test::layout_name(layout));
    // Counts far beyond the body, in the vertex element and in a later element.
    EXPECT_THROW(read_point_cloud_from_memory(make_ply({v}, layout, {1000000000000ull}), "h.ply"), Error);
    EXPECT_THROW(read_point_cloud_from_memory(make_ply({v, f}, layout, {1, 1ull << 40}), "h.ply"), Error);
    // A face index out of range.
    EXPECT_NE(error_of([&] {
                read_mesh_from_memory(make_ply({v, f}, layout), "h.ply");
              }).find("uses vertex 7 of 1"),
              std::string::npos);
  }
  // A list claiming 4 billion items with nothing after it.
  const std::string list_header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n";
  const std::string point(12, '\0');
  const std::string count("\xff\xff\xff\xff", 4);
  EXPECT_NE(error_of([&] { read_mesh_from_memory(list_header + point + count, "l.ply"); }).find("truncated"),
            std::string::npos);
  // A long list in an element before a fixed-size one: the header's size check assumed empty lists, so skipping
  // the fixed-size element must not run past the end (the fuzzer's heap overflow).
  const std::string list_first =
      "ply\nformat binary_little_endian 1.0\nelement a 1\nproperty list uchar int l\nelement b 3\n"
      "property float s\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  const std::string long_list = "\x04" + std::string(16, '\0');
  EXPECT_NE(error_of([&] {
              read_point_cloud_from_memory(list_first + long_list + std::string(8, '\0'), "s.ply");
            }).find("element \"b\": file ends in the middle"),
            std::string::npos);
  // An empty element without properties before the vertices is legal and skipped.
  const std::string empty_first =
      "ply\nformat binary_little_endian 1.0\nelement e 0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  EXPECT_EQ(read_point_cloud_from_memory(empty_first + point, "e.ply").cloud.size(), 1u);
  const std::string ascii_list =
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uint int vertex_indices\n"
      "end_header\n0 0 0\n4294967295 0 0\n";
  EXPECT_NE(error_of([&] { read_mesh_from_memory(ascii_list, "l.ply"); }).find("l.ply:11"), std::string::npos);
  // PCD compressed size beyond what LZF can expand to.
  const std::string pcd = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 100000\nPOINTS 100000\nDATA binary_compressed\n";
  const std::uint32_t sizes[2] = {1, 1200000};
  EXPECT_NE(error_of([&] {
              read_point_cloud_from_memory(
                  pcd + std::string(reinterpret_cast<const char*>(sizes), 8) + "\x00" + std::string(100000, '\0'),
                  "c.pcd");
            }).find("impossible for LZF"),
            std::string::npos);
  // Elements without properties, float list counts, unknown types and keywords.
  EXPECT_THROW(read_point_cloud_from_memory("ply\nformat ascii 1.0\nelement vertex 5\nend_header\n", "e.ply"), Error);
  EXPECT_THROW(read_point_cloud_from_memory(
                   "ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n1 2\n", "e.ply"),
               Error);
  EXPECT_THROW(
      read_point_cloud_from_memory("ply\nformat ascii 1.0\nelement vertex 1\nproperty half x\nend_header\n", "e.ply"),
      Error);
  EXPECT_THROW(read_point_cloud_from_memory("ply\nformat ascii 1.0\nbogus\nend_header\n", "e.ply"), Error);
  EXPECT_THROW(read_point_cloud_from_memory("ply\nelement vertex 0\nend_header\n", "e.ply"), Error);
}

// A text file reports "read" as its lines are parsed, forward only, at most ~20 times; false stops it.
TEST(ReadCloud, TextLinesReportProgressAndStopWhenAsked) {
  std::string text;
  for (int i = 0; i < 1000; ++i) text += std::to_string(i) + " " + std::to_string(i % 7) + " 0.5\n";
  std::vector<double> fractions;
  ReadOptions options;
  options.progress = [&](std::string_view stage, double fraction) {
    EXPECT_EQ(stage, "read");
    fractions.push_back(fraction);
    return true;
  };
  EXPECT_EQ(read_point_cloud_from_memory(text, "line.xyz", options).cloud.size(), 1000u);
  ASSERT_GE(fractions.size(), 10u);  // not only the start and the end
  EXPECT_LE(fractions.size(), 25u);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_EQ(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
  options.progress = [](std::string_view, double fraction) { return fraction < 0.5; };
  EXPECT_THROW(read_point_cloud_from_memory(text, "line.xyz", options), Cancelled);
}

}  // namespace
}  // namespace pcsketch::io
