// Streamed read with thinning (the XYZ family): the same kept points, normals, colours, intensity, counts, warnings
// and column layout as the whole read followed by decimate(), for any chunk size and any way the layout is given
// (guessed, header row, commented header, --columns, PTS); a malformed line fails as in the whole read.

#include <gtest/gtest.h>

#include <algorithm>

#include "io_test_util.h"
#include "pcsketch/io/decimate.h"
#include "pcsketch/io/read_cloud.h"

namespace pcsketch::io {
namespace {

using test::expect_as_whole_read;
using test::expect_same_cloud;
using test::text_of;


struct TextLayout {
  std::string header;         ///< lines before the rows
  std::size_t columns = 9;    ///< x y z, nx ny nz, r g b, intensity: the first `columns` of these
  std::string sep = " ";      ///< between values
  bool comments = false;      ///< a comment and a blank line every 50 rows
  double colour_scale = 1.0;  ///< 1/255: colours as fractions of 1
};

// `n` points on a noisy unit sphere around `centre`, one per line, every 89th NaN.
std::string sphere_text(std::size_t n, const TextLayout& l, double centre = 0.0) {
  std::string out = l.header;
  const std::vector<test::SpherePoint> sphere = test::noisy_sphere(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d& d = sphere[i].direction;
    const Vec3d p = Vec3d::Constant(centre) + sphere[i].radius * d;
    const std::array<double, 10> values{i % 89 == 3 ? std::nan("") : p.x(),
                                        p.y(),
                                        p.z(),
                                        d.x(),
                                        d.y(),
                                        d.z(),
                                        double(i % 256) * l.colour_scale,
                                        double(i / 256 % 256) * l.colour_scale,
                                        7 * l.colour_scale,
                                        double(i % 1000)};
    for (std::size_t c = 0; c < l.columns; ++c) out += (c ? l.sep : "") + text_of(values[c]);
    out += i % 3 ? "\n" : "\r\n";
    if (l.comments && i % 50 == 0) out += "# a comment\n\n" + l.sep + l.sep + "\n";
  }
  return out;
}

TEST(XyzStream, EveryLayoutKeepsThePointsOfTheWholeReadForAnyChunk) {
  const std::vector<std::pair<std::string, TextLayout>> cases{
      {"guessed.xyz", {}},
      {"guessed_commas.csv", {.sep = ",", .comments = true}},
      {"fractions.txt", {.sep = ";", .colour_scale = 1.0 / 255}},
      {"normals_only.xyz", {.columns = 6, .comments = true}},
      {"header.csv", {.header = "X,Y,Z,Nx,Ny,Nz,R,G,B,Intensity\n", .columns = 10, .sep = ","}},
      {"cloudcompare.asc", {.header = "//X;Y;Z;R;G;B;Nx;Ny;Nz\n", .sep = ";"}},  // colours named as normals
      {"plain.xyz", {.columns = 3}},
      {"ten_columns.xyz", {.columns = 10}},
      {"counted.pts", {.header = "3000\n", .columns = 7}},
  };
  for (const auto& [name, layout] : cases) {
    SCOPED_TRACE(name);
    expect_as_whole_read(sphere_text(3000, layout), name, {});
  }
  // --columns, with the header row skipped; far from the origin.
  const std::vector<Column> columns{Column::X,    Column::Y,   Column::Z,     Column::Skip, Column::Skip,
                                    Column::Skip, Column::Red, Column::Green, Column::Blue, Column::Intensity};
  expect_as_whole_read(sphere_text(3000, {.header = "a b c d e f g h i j\n", .columns = 10}, 512345.0), "cols.xyz",
                       {.columns = columns});
}

TEST(XyzStream, CropAndNormalsOffAsInTheWholeRead) {
  const std::string bytes = sphere_text(4000, {.comments = true});
  expect_as_whole_read(bytes, "crop.xyz", {.crop = CropBox{{-2, -2, 0}, {2, 2, 2}}});
  expect_as_whole_read(bytes, "plain.xyz", {.keep_normals = false, .keep_colors = false});
}

TEST(XyzStream, BudgetDecidedOnTheExactCount) {
  const std::string bytes = sphere_text(3000, {});
  const ReadResult over = test::expect_budget_rule(bytes, "s.xyz");
  ASSERT_TRUE(over.decimation.has_value());
  EXPECT_NE(over.decimation->reason.find("3000 points, over the 1000 budget"), std::string::npos)
      << over.decimation->reason;
  // A short first row makes the estimate about 15000 rows (the file size over 18 bytes); the first pass counts 3001,
  // within a budget of 4000: read as before.
  const std::string short_first = "0 0 0 0 0 1 0 0 0\n" + bytes;
  ReadOptions options;
  options.decimate.resolution = OutputResolution{.width = 40, .height = 40, .budget_points = 4000};
  const ReadResult counted = read_point_cloud_from_memory(short_first, "s.xyz", options);
  EXPECT_FALSE(counted.decimation.has_value());
  expect_same_cloud(counted.cloud, read_point_cloud_from_memory(short_first, "s.xyz").cloud);
}

// The count estimate takes the shortest of the first 1,024 lines; here they are long (17-digit values) and the rest
// short, so it is under the budget while the rows are over it. The decision must not trust it: the file is streamed
// (never held whole), with the points of the whole read thinned by the same cell.
TEST(XyzStream, LongFirstLinesDoNotHideRowsOverTheBudget) {
  std::string bytes;
  std::size_t shortest = std::string::npos;
  for (const test::SpherePoint& s : test::noisy_sphere(1024)) {
    const Vec3d p = s.radius * s.direction;
    const std::string line = text_of(p.x()) + " " + text_of(p.y()) + " " + text_of(p.z()) + "\n";
    shortest = std::min(shortest, line.size());
    bytes += line;
  }
  for (std::size_t i = 0; i < 20000; ++i)  // a 100 x 200 grid at z = 0.5, spacing 0.01: "0.37 1.99 0.5"
    bytes += text_of(double(i % 100) / 100) + " " + text_of(double(i / 100) / 100) + " 0.5\n";
  const std::size_t rows = 21024;
  ASSERT_LT(bytes.size() / shortest, 8000u);  // the estimate
  ReadOptions options;
  options.decimate.resolution = OutputResolution{.width = 40, .height = 40, .budget_points = 8000};
  options.stream_chunk_points = 1000;
  const ReadResult over = read_point_cloud_from_memory(bytes, "long_first.xyz", options);
  ASSERT_TRUE(over.decimation.has_value());
  EXPECT_TRUE(over.decimation->streamed);
  EXPECT_EQ(over.points_in_file, rows);
  EXPECT_NE(over.decimation->reason.find("21024 points, over the 8000 budget"), std::string::npos)
      << over.decimation->reason;
  ReadResult whole = read_point_cloud_from_memory(bytes, "long_first.xyz");
  decimate(whole.cloud, {.voxel = over.decimation->cell});
  expect_same_cloud(over.cloud, whole.cloud);
}

TEST(XyzStream, MalformedFilesFailAsInTheWholeRead) {
  const std::string good = sphere_text(300, {.comments = true});
  const auto line_start = [&](std::size_t line) {
    std::size_t at = 0;
    for (std::size_t i = 1; i < line; ++i) at = good.find('\n', at) + 1;
    return at;
  };
  std::string word = good, shorter = good, longer = good;
  word.insert(line_start(200) + 2, "x");
  shorter.insert(line_start(150), "1 2\n");
  longer.insert(line_start(250), "1 2 3 4 5 6 7 8 9 10\n");
  const std::vector<std::string> hostile{word,
                                         shorter,
                                         longer,
                                         "1 2\n3 4\n",
                                         "x y\n1 2 3\n",
                                         "# only\n\n",
                                         "nan 0 0\n0 nan 0\n",
                                         "1 2 3\n4 5 1e999\n",
                                         "\xEF\xBB\xBF"
                                         "1 2 3\n4 5\n"};
  test::expect_same_errors(hostile, "bad.xyz", [](const std::string& bytes, const std::string& name, bool thinned) {
    read_point_cloud_from_memory(bytes, name, {.decimate = {.voxel = thinned ? std::optional(0.1) : std::nullopt}});
  });
}

TEST(XyzStream, MappedFileGivesTheSamePoints) {
  const test::TempDir dir;
  const std::string bytes = sphere_text(20000, {.columns = 10});
  const std::string path = dir.write("s.xyz", bytes);
  ReadOptions options;
  options.decimate.voxel = 0.05;
  options.stream_chunk_points = 1000;  // pages released between chunks
  expect_same_cloud(read_point_cloud(path, options).cloud, read_point_cloud_from_memory(bytes, "s.xyz", options).cloud);
}

TEST(XyzStream, RowsEstimatedFromLinesSampledThroughTheFile) {
  // The file of LongFirstLinesDoNotHideRowsOverTheBudget: long first lines, short ones after, a header row and
  // comments; --full-resolution's early memory check takes this estimate where no header declares a count.
  std::string bytes = "x y z\n# scanned 2026\n";
  for (const test::SpherePoint& s : test::noisy_sphere(1024)) {
    const Vec3d p = s.radius * s.direction;
    bytes += text_of(p.x()) + " " + text_of(p.y()) + " " + text_of(p.z()) + "\n";
  }
  for (std::size_t i = 0; i < 20000; ++i) {
    bytes += text_of(double(i % 100) / 100) + " " + text_of(double(i / 100) / 100) + " 0.5\n";
    if (i % 1000 == 0) bytes += "# a comment line\n";
  }
  const test::TempDir dir;
  const std::optional<std::uint64_t> rows = estimated_text_rows(dir.write("s.xyz", bytes));
  ASSERT_TRUE(rows.has_value());
  EXPECT_NEAR(static_cast<double>(*rows), 21024.0, 0.05 * 21024.0);
  EXPECT_FALSE(estimated_text_rows(dir.write("s.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                                     "property float y\nproperty float z\nend_header\n0 0 0\n"))
                   .has_value());
  EXPECT_FALSE(estimated_text_rows(dir.write("one.xyz", "1 2 3")).has_value());  // one line: read whole
}

}  // namespace
}  // namespace pcsketch::io
