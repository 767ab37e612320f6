// Hostile and odd inputs (issue 10): line ends, row widths, number ranges, endless lines, long or binary text in
// messages, non-regular files, duplicates and impossible scales. One test per class of problem.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstring>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "io_test_util.h"
#include "pcsketch/core/error.h"
#include "pcsketch/io/read_cloud.h"

namespace pcsketch::io {
namespace {

using test::error_of;

std::string xyz_error(const std::string& text) {
  return error_of([&] { read_point_cloud_from_memory(text, "t.xyz"); });
}

TEST(HostileInput, TextLineEndsCrLfCrlfAndBom) {
  for (const std::string& text : {std::string("1 2 3\r4 5 6\r7 8 9\r"), std::string("1 2 3\n4 5 6\n7 8 9"),
                                  std::string("1 2 3\r\n4 5 6\r\n7 8 9\r\n"), std::string("1 2 3\r4 5 6\n7 8 9\r\n"),
                                  std::string("\xEF\xBB\xBF"
                                              "1 2 3\r\n4 5 6\r\n7 8 9\r\n")}) {
    SCOPED_TRACE(text);
    const ReadResult r = read_point_cloud_from_memory(text, "t.xyz");
    ASSERT_EQ(r.cloud.size(), 3u);
    EXPECT_EQ(r.cloud.world(2), Vec3d(7, 8, 9));
  }
  // Line numbers count CR-only lines too.
  EXPECT_NE(xyz_error("1 2 3\r4 5 x\r").find("t.xyz:2: XYZ: non-numeric value \"x\""), std::string::npos);
}

TEST(HostileInput, RowWithExtraOrMissingColumnsNamesItsLine) {
  EXPECT_NE(xyz_error("1 2 3\n4 5 6 7\n8 9 10\n").find("t.xyz:2: XYZ: 4 columns where the first line has 3"),
            std::string::npos);
  EXPECT_NE(xyz_error("x,y,z,i\n1,2,3,4\n5,6,7\n").find("t.xyz:3: XYZ: 3 columns where the first line has 4"),
            std::string::npos);
  // An ascii PLY row with a value too many would shift every later value into the next rows.
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
      "end_header\n1 2 3 4\n5 6 7\n";
  EXPECT_NE(
      error_of([&] { read_point_cloud_from_memory(ply, "t.ply"); }).find("t.ply:8: PLY: element \"vertex\": more"),
      std::string::npos);
}

TEST(HostileInput, OverflowingNumbersAreOutOfRange) {
  EXPECT_NE(xyz_error("1 2 1e309\n").find("out-of-range value \"1e309\" in column 3"), std::string::npos);
  EXPECT_NE(xyz_error("1 2 abc\n").find("non-numeric value \"abc\""), std::string::npos);
}

TEST(HostileInput, EndlessLineIsRefusedWithoutCopyingIt) {
  const std::string endless(3 << 20, '7');
  const std::string message = xyz_error(endless);
  EXPECT_NE(message.find("t.xyz:1: line longer than 1048576 bytes"), std::string::npos) << message.substr(0, 200);
  EXPECT_LT(message.size(), 200u);
}

TEST(HostileInput, MessagesQuoteLittleAndEscapeControlBytes) {
  const std::string keyword = "ply\nformat ascii 1.0\n" + std::string(100000, 'k') + "\nend_header\n";
  const std::string long_message = error_of([&] { read_point_cloud_from_memory(keyword, "t.ply"); });
  EXPECT_LT(long_message.size(), 300u);
  EXPECT_NE(long_message.find("kkk...\""), std::string::npos) << long_message;
  const std::string nasty = std::string("ply\nformat ascii 1.0\n\x1b[31m\0red\nend_header\n", 42);
  const std::string message = error_of([&] { read_point_cloud_from_memory(nasty, "t\n.ply"); });
  EXPECT_NE(message.find("t\\x0a.ply"), std::string::npos) << message;
  EXPECT_NE(message.find("\"\\x1b[31m\\x00red\""), std::string::npos) << message;
  EXPECT_EQ(std::strlen(message.c_str()), message.size());
  for (const char c : message) EXPECT_GE(static_cast<unsigned char>(c), 0x20);
}

TEST(HostileInput, NonRegularFilesAreRefusedBeforeOpening) {
  const test::TempDir dir;
  const std::string fifo = dir.file("f.xyz");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // open() on a FIFO without a writer would block forever.
  EXPECT_NE(error_of([&] { read_point_cloud(fifo); }).find("f.xyz: not a regular file"), std::string::npos);
  EXPECT_NE(error_of([] { read_point_cloud("/dev/null"); }).find("not a regular file"), std::string::npos);
  EXPECT_NE(error_of([] { read_point_cloud("-"); }).find("standard input is not supported"), std::string::npos);
}

TEST(HostileInput, ExactDuplicatesAreCollapsedAtLoad) {
  std::string text = "0 0 0 0 0 1\n";
  for (int i = 0; i < 100000; ++i) text += "1 2 3 0 0 1\n";
  text += "-0 0 0 0 0 1\n5 5 5 0 0 1\n1 2 3.0000001 0 0 1\n";
  const ReadResult r = read_point_cloud_from_memory(text, "d.xyz");
  ASSERT_EQ(r.cloud.size(), 4u);
  EXPECT_EQ(r.duplicates, 100000u - 1 + 1);  // the copies of (1,2,3) and -0 = +0
  EXPECT_EQ(r.cloud.world(1), Vec3d(1, 2, 3));
  EXPECT_EQ(r.cloud.world(2), Vec3d(5, 5, 5));
  EXPECT_EQ(r.cloud.normals.size(), 4u);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("100000 points repeat an earlier point"), std::string::npos) << r.warnings[0];
  const ReadResult kept = read_point_cloud_from_memory(text, "d.xyz", {.collapse_duplicates = false});
  EXPECT_EQ(kept.cloud.size(), 100004u);
}

TEST(HostileInput, DuplicatesAmongManyPointsKeepEachFirstCopyInOrder) {
  // Enough points for the parallel bucketing to split them into slices; the simple rule is a set of lines seen.
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> coordinate(0, 40);
  std::vector<std::string> lines;
  for (int i = 0; i < 60000; ++i)
    lines.push_back(i % 4 == 3 ? lines[rng() % lines.size()]
                               : std::to_string(coordinate(rng)) + " " + std::to_string(coordinate(rng)) + " " +
                                     std::to_string(coordinate(rng) + 1000 * (i % 7)));
  std::string text;
  std::set<std::string> seen;
  std::vector<Vec3f> first;
  for (const std::string& line : lines) {
    text += line + "\n";
    if (!seen.insert(line).second) continue;
    std::istringstream in(line);
    Vec3f p;
    in >> p.x() >> p.y() >> p.z();
    first.push_back(p);
  }
  const ReadResult r = read_point_cloud_from_memory(text, "d.xyz", {.recentre = false});
  EXPECT_EQ(r.duplicates, lines.size() - first.size());
  EXPECT_EQ(r.cloud.positions, first);
}

TEST(HostileInput, ScalesFloatCannotHoldAreRefusedWithAReason) {
  for (const double scale : {1e30, 1e-30}) {
    const std::string text = "0 0 0\n" + number(scale) + " 0 0\n0 " + number(scale) + " 0\n0 0 " + number(scale) + "\n";
    const ReadResult r = read_point_cloud_from_memory(text, "t.xyz");
    EXPECT_NE(error_of([&] { check_scale(r.cloud, "t.xyz"); }).find("t.xyz: the points span " + number(scale)),
              std::string::npos);
  }
  // One stray point at 1e30 among unit-scale points.
  const ReadResult stray = read_point_cloud_from_memory("0 0 0\n1 0 0\n0 1 0\n0 0 1e30\n", "t.xyz");
  EXPECT_NE(error_of([&] { check_scale(stray.cloud, "t.xyz"); }).find("span 1e+30 units"), std::string::npos);
  EXPECT_NO_THROW(check_scale(read_point_cloud_from_memory("0 0 0\n1 0 0\n", "t.xyz").cloud, "t.xyz"));
  // Beyond float range, the reader itself refuses (a float position would be infinite).
  EXPECT_NE(xyz_error("0 0 0\n1e39 0 0\n").find("t.xyz: point 1 lies 1e+39 units from"), std::string::npos);
}

TEST(HostileInput, SecondFaceElementIsNotReadWithTheFirstsList) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nelement face 1\nproperty list uchar int other\n"
      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 2 1 0\n";
  const Mesh mesh = read_mesh_from_memory(ply, "f.ply");
  ASSERT_EQ(mesh.faces.size(), 1u);
  EXPECT_EQ(mesh.faces[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
}

TEST(HostileInput, PcdCompressedSizesAreCheckedBeforeAllocating) {
  // The size header (12 bytes) contradicts POINTS x record (18000): refused before the point arrays are sized (the
  // allocation itself is what fuzz-smoke's malloc limit watches).
  const std::string pcd = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1500\nPOINTS 1500\nDATA binary_compressed\n";
  const std::uint32_t sizes[2] = {4, 12};
  const std::string body = std::string(reinterpret_cast<const char*>(sizes), 8) + std::string(2000, '\0');
  EXPECT_NE(error_of([&] {
              read_point_cloud_from_memory(pcd + body, "c.pcd");
            }).find("PCD: uncompressed size 12 is not POINTS x record size 18000"),
            std::string::npos);
}

}  // namespace
}  // namespace pcsketch::io
