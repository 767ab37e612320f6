// Streamed read with thinning (ascii PLY and ascii PCD): the same kept points, normals, colours, counts and format as
// the whole read followed by decimate(), for any chunk size, line ends and layouts; a malformed row fails with the
// whole read's message and line.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "io_test_util.h"
#include "pcsketch/io/decimate.h"
#include "pcsketch/io/read_cloud.h"

namespace pcsketch::io {
namespace {

using test::expect_as_whole_read;
using test::expect_same_cloud;
using test::text_of;
using test::Layout;
using test::make_ply;
using test::PlyElem;

struct PlyShape {
  std::string colour_type = "uchar";  ///< "float": colours as fractions of 1
  bool element_before = true;         ///< a "camera" element (scalars and a list) before the vertices
  bool face_after = false;            ///< a "face" element after them
  std::vector<std::uint64_t> declared_counts = {};
};

// `n` points of a noisy unit sphere around `centre` as an ascii PLY (x y z nx ny nz red green blue quality), every
// 97th point NaN.
std::string sphere_ply(std::size_t n, const PlyShape& shape = {}, double centre = 0.0) {
  const std::string& c = shape.colour_type;
  const double scale = c == "float" ? 1.0 / 255 : 1.0;
  PlyElem vertex{"vertex",
                 {{"float", "x"},
                  {"float", "y"},
                  {"float", "z"},
                  {"float", "nx"},
                  {"float", "ny"},
                  {"float", "nz"},
                  {c, "red"},
                  {c, "green"},
                  {c, "blue"},
                  {"float", "quality"}},
                 {}};
  const std::vector<test::SpherePoint> sphere = test::noisy_sphere(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d& d = sphere[i].direction;
    const Vec3d p = Vec3d::Constant(centre) + sphere[i].radius * d;
    vertex.rows.push_back({i % 97 == 5 ? std::nan("") : p.x(), p.y(), p.z(), d.x(), d.y(), d.z(),
                           double(i % 256) * scale, double(i / 256 % 256) * scale, 7.0 * scale, double(i)});
  }
  std::vector<PlyElem> elements;
  if (shape.element_before)
    elements.push_back({"camera", {{"float", "focal"}, {"int", "ids", "uchar"}}, {{35.0, 3, 1, 2, 3}, {50.0, 0}}});
  elements.push_back(std::move(vertex));
  if (shape.face_after) elements.push_back({"face", {{"int", "vertex_indices", "uchar"}}, {{3, 0, 1, 2}}});
  return make_ply(elements, Layout::Ascii, shape.declared_counts);
}


// `n` points of the sphere as an ascii PCD (x y z, normals, packed rgb, a 3-value field, intensity), every 89th NaN,
// a blank line every 50 rows, CRLF on every third.
std::string sphere_pcd(std::size_t n, std::uint64_t declared = 0) {
  const std::string count = std::to_string(declared > 0 ? declared : n);
  std::string out =
      "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z normal_x normal_y normal_z rgb extra intensity\n"
      "SIZE 4 4 4 4 4 4 4 4 4\nTYPE F F F F F F F F F\nCOUNT 1 1 1 1 1 1 1 3 1\nWIDTH " +
      count + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + count + "\nDATA ascii\n";
  const std::vector<test::SpherePoint> sphere = test::noisy_sphere(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d& d = sphere[i].direction;
    const Vec3d p = sphere[i].radius * d;
    // The shortest text of the float rgb reads back as the same float, hence the same packed bits.
    const auto rgb = std::bit_cast<float>(std::uint32_t((i % 256) << 16 | (i / 256 % 256) << 8 | 7));
    for (const double v :
         {i % 89 == 3 ? std::nan("") : p.x(), p.y(), p.z(), d.x(), d.y(), d.z(), double(rgb), 1.0, 2.0, 3.0, double(i)})
      out += text_of(v) + " ";
    out += i % 3 ? "\n" : "\r\n";
    if (i % 50 == 0) out += "\n \t\n";
  }
  return out;
}

std::string crlf(const std::string& text) {
  std::string out;
  for (const char c : text) out += c == '\n' ? "\r\n" : std::string(1, c);
  return out;
}

TEST(AsciiStream, PlyKeepsThePointsOfTheWholeReadForAnyChunk) {
  const std::string plain = sphere_ply(3000);
  const std::string unterminated = plain.substr(0, plain.size() - 1);  // the last line without its newline
  ASSERT_EQ(plain.back(), '\n');
  const std::vector<std::pair<std::string, std::string>> cases{
      {"before.ply", plain},
      {"crlf.ply", crlf(plain)},
      {"unterminated.ply", unterminated},
      {"crlf_unterminated.ply", crlf(unterminated)},
      {"float_colours.ply", sphere_ply(3000, {.colour_type = "float"})},
      {"only_vertices.ply", sphere_ply(3000, {.element_before = false})},
      {"faces_after.ply", sphere_ply(3000, {.face_after = true})},
      {"utm.ply", sphere_ply(3000, {}, 512345.678)},
  };
  for (const auto& [name, bytes] : cases) {
    SCOPED_TRACE(name);
    expect_as_whole_read(bytes, name, {});
  }
  const ReadResult r = read_point_cloud_from_memory(plain, "s.ply", {.decimate = {.voxel = 0.1}});
  EXPECT_EQ(r.format, "ply ascii");
  EXPECT_EQ(r.other_attributes, std::vector<std::string>{"quality"});
  EXPECT_EQ(r.dropped_non_finite, 31u);  // i % 97 == 5 for i < 3000
  EXPECT_TRUE(r.cloud.has_normals());
  EXPECT_TRUE(r.cloud.has_colors());
  expect_as_whole_read(plain, "crop.ply", {.crop = CropBox{{-2, -2, 0}, {2, 2, 2}}});
  expect_as_whole_read(plain, "plain.ply", {.keep_normals = false, .keep_colors = false});
}

TEST(AsciiStream, PcdKeepsThePointsOfTheWholeReadForAnyChunk) {
  const std::string plain = sphere_pcd(3000);
  expect_as_whole_read(plain, "s.pcd", {});
  expect_as_whole_read(plain.substr(0, plain.size() - 1), "unterminated.pcd", {});
  expect_as_whole_read(plain, "crop.pcd", {.crop = CropBox{{-2, -2, 0}, {2, 2, 2}}});
  const ReadResult r = read_point_cloud_from_memory(plain, "s.pcd", {.decimate = {.voxel = 0.1}});
  EXPECT_EQ(r.format, "pcd ascii");
  EXPECT_EQ(r.other_attributes, (std::vector<std::string>{"extra", "intensity"}));
  EXPECT_EQ(r.dropped_non_finite, 34u);  // i % 89 == 3 for i < 3000
  EXPECT_TRUE(r.cloud.has_normals());
  EXPECT_TRUE(r.cloud.has_colors());
}

TEST(AsciiStream, BudgetRuleStreamsOverTheBudgetOnly) {
  for (const auto& [name, bytes] : {std::pair{"s.ply", sphere_ply(3000)}, std::pair{"s.pcd", sphere_pcd(3000)}}) {
    SCOPED_TRACE(name);
    const ReadResult over = test::expect_budget_rule(bytes, name);
    ASSERT_TRUE(over.decimation.has_value());
    EXPECT_NE(over.decimation->reason.find("3000 points, over the 1000 budget"), std::string::npos)
        << over.decimation->reason;
  }
}

// The offset of line `line` (from 1) of `text`.
std::size_t line_start(const std::string& text, std::size_t line) {
  std::size_t at = 0;
  for (std::size_t i = 1; i < line; ++i) at = text.find('\n', at) + 1;
  return at;
}

// The number (from 1) of the line holding byte `offset` of `text`.
std::size_t line_of(const std::string& text, std::size_t offset) {
  return 1 + static_cast<std::size_t>(std::count(text.data(), text.data() + offset, '\n'));
}

// The whole and the streamed read of `bytes` fail alike, with `expected` in the message.
void expect_error(const std::string& bytes, const std::string& name, const std::string& expected) {
  for (const bool thinned : {false, true}) {
    SCOPED_TRACE(thinned);
    const std::string message = test::error_of([&] {
      read_point_cloud_from_memory(bytes, name, {.decimate = {.voxel = thinned ? std::optional(0.1) : std::nullopt}});
    });
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
}

TEST(AsciiStream, MalformedPlyFailsAsInTheWholeRead) {
  const std::string good = sphere_ply(300);
  const std::size_t body = good.find("end_header\n") + 11;
  const auto row = [&](std::size_t i) { return body + line_start(good.substr(body), i + 1); };  // line i of the body
  std::string fewer = good, more = good, word = good, huge_value = good, bad_list = good;
  const std::size_t end_150 = good.find('\n', row(150)), last_150 = good.rfind(' ', end_150);
  fewer.erase(last_150, end_150 - last_150);  // its last value: a short row, not a gap for the next row to fill
  more.insert(good.find('\n', row(200)), " 4");
  word.insert(row(250) + 2, "x");
  huge_value.insert(row(100), "1e999 ");
  bad_list.replace(row(0), 4, "35 -1");  // the camera's list count
  const std::vector<std::string> hostile{
      fewer,
      more,
      word,
      huge_value,
      bad_list,
      sphere_ply(300, {.declared_counts = {2, 320}}),         // more vertices than rows, fewer than the bytes allow
      sphere_ply(300, {.declared_counts = {2, 1000000000}}),  // more than the bytes allow
      good.substr(0, row(120) + 7),                           // cut inside a row
      good.substr(0, body) + std::string(std::size_t{3} << 20, '1'),  // a line longer than any point's
  };
  test::expect_same_errors(hostile, "bad.ply", [](const std::string& bytes, const std::string& name, bool thinned) {
    read_point_cloud_from_memory(bytes, name, {.decimate = {.voxel = thinned ? std::optional(0.1) : std::nullopt}});
  });
}

// A vertex line one value short names its own line (not the next, whose first value it would otherwise take), and a
// line with a value too many its own; the entries before and after the vertices are lines too.
TEST(AsciiStream, PlyRowOfTheWrongLengthNamesItsLine) {
  const std::string good = sphere_ply(300, {.face_after = true});
  const std::size_t body = good.find("end_header\n") + 11;
  const std::size_t row_150 = body + line_start(good.substr(body), 151);  // the camera's 2 lines, then vertex 148
  std::string fewer = good, more = good, short_camera = good;
  const std::size_t end_150 = good.find('\n', row_150), last_150 = good.rfind(' ', end_150);
  fewer.erase(last_150, end_150 - last_150);
  more.insert(end_150, " 4");
  short_camera.replace(body, good.find('\n', body) - body, "35 3 1 2");  // its list one item short
  const std::string line = "bad.ply:" + std::to_string(line_of(good, row_150)) + ": ";
  expect_error(fewer, "bad.ply", line + "PLY: element \"vertex\": too few values on the line");
  expect_error(more, "bad.ply", line + "PLY: element \"vertex\": more values on the line");
  expect_error(short_camera, "bad.ply",
               "bad.ply:" + std::to_string(line_of(good, body)) + ": PLY: element \"camera\": too few values");
  // The last vertex one value short: the face's line is not read as its end.
  std::string last = good;
  const std::size_t face = good.rfind("3 0 1 2"), end_last = face - 1, last_space = good.rfind(' ', end_last);
  last.erase(last_space, end_last - last_space);
  expect_error(last, "bad.ply",
               "bad.ply:" + std::to_string(line_of(good, end_last)) + ": PLY: element \"vertex\": too few values");
}

TEST(AsciiStream, MalformedPcdFailsAsInTheWholeRead) {
  const std::string good = sphere_pcd(300);
  const std::size_t body = good.find("DATA ascii\n") + 11;
  const auto row = [&](std::size_t line) { return body + line_start(good.substr(body), line); };
  std::string fewer = good, more = good, word = good, huge_value = good;
  fewer.insert(row(150), "1 2 3\n");
  more.insert(row(150), "1 2 3 4 5 6 7 8 9 10 11 12\n");  // the fields need 11 values (COUNT 3 for "extra")
  word.insert(row(200) + 2, "x");
  huge_value.insert(row(100), "1e999 ");
  const std::vector<std::string> hostile{
      fewer,
      more,
      word,
      huge_value,
      sphere_pcd(300, 320),         // more points than rows, fewer than the bytes allow
      sphere_pcd(300, 1000000000),  // more than the bytes allow
      good.substr(0, row(120) + 7),
  };
  test::expect_same_errors(hostile, "bad.pcd", [](const std::string& bytes, const std::string& name, bool thinned) {
    read_point_cloud_from_memory(bytes, name, {.decimate = {.voxel = thinned ? std::optional(0.1) : std::nullopt}});
  });
}

// A row holds exactly the sum of the COUNTs (PCD spec: one point a line, COUNT values a field): one more is an error
// naming its line, not ignored (a value too many means the fields are not what the header says).
TEST(AsciiStream, PcdRowWithAValueTooManyNamesItsLine) {
  const std::string good = sphere_pcd(300);
  const std::size_t body = good.find("DATA ascii\n") + 11;
  const std::size_t row_150 = body + line_start(good.substr(body), 150);
  std::string more = good, last = good;
  more.insert(row_150, "1 2 3 4 5 6 7 8 9 10 11 12\n");
  const std::string line = "bad.pcd:" + std::to_string(line_of(more, row_150)) + ": ";
  expect_error(more, "bad.pcd", line + "PCD: too many values (12; the fields need 11)");
  last.insert(good.rfind(' '), " 5");  // the last row: nothing after it to go wrong
  expect_error(last, "bad.pcd",
               "bad.pcd:" + std::to_string(line_of(good, good.size() - 1)) + ": PCD: too many values (12;");
}

TEST(AsciiStream, MappedFilesGiveTheSamePoints) {
  const test::TempDir dir;
  ReadOptions options;
  options.decimate.voxel = 0.05;
  options.stream_chunk_points = 1000;  // pages released between chunks
  for (const auto& [name, bytes] : {std::pair{"s.ply", sphere_ply(20000)}, std::pair{"s.pcd", sphere_pcd(20000)}}) {
    SCOPED_TRACE(name);
    const ReadResult mapped = read_point_cloud(dir.write(name, bytes), options);
    EXPECT_TRUE(mapped.decimation.has_value() && mapped.decimation->streamed);
    expect_same_cloud(mapped.cloud, read_point_cloud_from_memory(bytes, name, options).cloud);
  }
}

}  // namespace
}  // namespace pcsketch::io
