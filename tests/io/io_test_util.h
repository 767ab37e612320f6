#pragma once
// Helpers for the reader tests: a per-test temporary directory and a PLY encoder independent of the library's writer
// (so a reader bug and a writer bug cannot cancel out).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "pcsketch/core/error.h"
#include "pcsketch/core/point_cloud.h"
#include "pcsketch/io/decimate.h"
#include "pcsketch/io/read_cloud.h"

namespace pcsketch::test {

/// The message of the pcsketch::Error `f` throws ("" and a test failure if it throws none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no pcsketch::Error thrown";
  return "";
}

/// A fresh directory per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() / ("pcsketch_io_" + std::string(info->test_suite_name()) + "_" +
                                                      info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  /// Writes `bytes` to `name` and returns its path.
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(file(name), std::ios::binary) << bytes;
    return file(name);
  }

 private:
  std::filesystem::path path_;
};

enum class Layout { Ascii, BinaryLE, BinaryBE };
inline const char* layout_name(Layout l) {
  return l == Layout::Ascii ? "ascii" : l == Layout::BinaryLE ? "binary_little_endian" : "binary_big_endian";
}

/// One PLY property: a scalar of `type`, or a list with `count_type` counts.
struct PlyProp {
  std::string type;
  std::string name;
  std::string count_type;  ///< empty: scalar
};
/// One element; each row holds the values of every property in order, a list as its count then its items.
struct PlyElem {
  std::string name;
  std::vector<PlyProp> props;
  std::vector<std::vector<double>> rows;
};

inline std::size_t type_size(const std::string& t) {
  if (t == "char" || t == "int8" || t == "uchar" || t == "uint8") return 1;
  if (t == "short" || t == "int16" || t == "ushort" || t == "uint16") return 2;
  if (t == "double" || t == "float64") return 8;
  return 4;
}

template <class T>
void append_binary(std::string& out, T v, bool big) {
  std::array<char, sizeof(T)> b;
  std::memcpy(b.data(), &v, sizeof(T));
  if (big) std::reverse(b.begin(), b.end());
  out.append(b.data(), b.size());
}

/// The shortest text that reads back as `v` exactly.
inline std::string text_of(double v) {
  std::array<char, 40> text;
  return {text.data(), std::to_chars(text.data(), text.data() + text.size(), v).ptr};
}

inline void encode(std::string& out, const std::string& t, double v, Layout layout) {
  if (layout == Layout::Ascii) {
    out += text_of(v) + ' ';
    return;
  }
  const bool big = layout == Layout::BinaryBE;
  if (t == "char" || t == "int8") return append_binary(out, static_cast<std::int8_t>(v), big);
  if (t == "uchar" || t == "uint8") return append_binary(out, static_cast<std::uint8_t>(v), big);
  if (t == "short" || t == "int16") return append_binary(out, static_cast<std::int16_t>(v), big);
  if (t == "ushort" || t == "uint16") return append_binary(out, static_cast<std::uint16_t>(v), big);
  if (t == "int" || t == "int32") return append_binary(out, static_cast<std::int32_t>(v), big);
  if (t == "uint" || t == "uint32") return append_binary(out, static_cast<std::uint32_t>(v), big);
  if (t == "float" || t == "float32") return append_binary(out, static_cast<float>(v), big);
  append_binary(out, v, big);
}

/// A whole PLY file. `declared_counts` overrides the element counts written in the header (malformed files).
inline std::string make_ply(const std::vector<PlyElem>& elements, Layout layout,
                            const std::vector<std::uint64_t>& declared_counts = {}) {
  std::string out = std::string("ply\nformat ") + layout_name(layout) + " 1.0\ncomment made by io_test_util.h\n";
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const std::uint64_t count = e < declared_counts.size() ? declared_counts[e] : elements[e].rows.size();
    out += "element " + elements[e].name + " " + std::to_string(count) + "\n";
    for (const PlyProp& p : elements[e].props)
      out += p.count_type.empty() ? "property " + p.type + " " + p.name + "\n"
                                  : "property list " + p.count_type + " " + p.type + " " + p.name + "\n";
  }
  out += "obj_info generated\nend_header\n";
  for (const PlyElem& e : elements) {
    for (const std::vector<double>& row : e.rows) {
      std::size_t k = 0;
      for (const PlyProp& p : e.props) {
        if (p.count_type.empty()) {
          encode(out, p.type, row.at(k++), layout);
          continue;
        }
        const auto n = static_cast<std::size_t>(row.at(k));
        encode(out, p.count_type, row.at(k++), layout);
        for (std::size_t i = 0; i < n; ++i) encode(out, p.type, row.at(k++), layout);
      }
      if (layout == Layout::Ascii) out.back() = '\n';
    }
  }
  return out;
}

/// A point of a noisy sphere: unit direction (the normal) and radius about 1.
struct SpherePoint {
  Vec3d direction;
  double radius;
};

/// `n` points of a noisy unit sphere (Gaussian directions, radius 1 + 0.01 N(0, 1)), seeded: the same every run.
inline std::vector<SpherePoint> noisy_sphere(std::size_t n) {
  std::mt19937 mt(42);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<SpherePoint> out;
  for (std::size_t i = 0; i < n; ++i) {
    Vec3d d(g(mt), g(mt), g(mt));
    d.normalize();
    out.push_back({d, 1.0 + 0.01 * g(mt)});
  }
  return out;
}

/// Two clouds alike to the bit: origin, positions, normals, colours and every attribute (streamed against whole reads).
inline void expect_same_cloud(const PointCloud& a, const PointCloud& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.origin, b.origin);
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a.positions[i], b.positions[i]) << i;
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.colors, b.colors);
  ASSERT_EQ(a.attributes.size(), b.attributes.size());
  for (std::size_t k = 0; k < a.attributes.size(); ++k) {
    EXPECT_EQ(a.attributes[k].name, b.attributes[k].name);
    EXPECT_EQ(a.attributes[k].values, b.attributes[k].values) << a.attributes[k].name;
  }
}

/// The streamed read of `bytes` as `name` with `options` and a voxel of 0.1, for chunks of 1 to 65,536 points,
/// against the whole read followed by decimate() with the same cell: points, counts, format, layout, warnings.
inline void expect_as_whole_read(const std::string& bytes, const std::string& name, io::ReadOptions options) {
  options.decimate.voxel = 0.1;
  io::ReadOptions whole_options = options;
  whole_options.decimate = {};
  io::ReadResult whole = io::read_point_cloud_from_memory(bytes, name, whole_options);
  io::decimate(whole.cloud, {.voxel = 0.1});
  for (const std::size_t chunk : {std::size_t{1}, std::size_t{7}, std::size_t{1000}, std::size_t{1} << 16}) {
    SCOPED_TRACE(chunk);
    options.stream_chunk_points = chunk;
    const io::ReadResult streamed = io::read_point_cloud_from_memory(bytes, name, options);
    ASSERT_TRUE(streamed.decimation.has_value());
    EXPECT_TRUE(streamed.decimation->streamed);
    EXPECT_EQ(streamed.format, whole.format);
    EXPECT_EQ(streamed.columns, whole.columns);
    EXPECT_EQ(streamed.other_attributes, whole.other_attributes);
    EXPECT_EQ(streamed.warnings, whole.warnings);
    EXPECT_EQ(streamed.points_in_file, whole.points_in_file);
    EXPECT_EQ(streamed.dropped_non_finite, whole.dropped_non_finite);
    EXPECT_EQ(streamed.dropped_by_filter, whole.dropped_by_filter);
    expect_same_cloud(streamed.cloud, whole.cloud);
  }
}

/// The resolution rule on `bytes` (over 1000 points) read as `name`: within the default budget, read as before
/// (no thinning); over a budget of 1000, streamed, with the points of the whole read then decimate() by the same cell.
/// Returns the streamed read.
inline io::ReadResult expect_budget_rule(const std::string& bytes, const std::string& name) {
  io::ReadOptions options;
  options.decimate.resolution = io::OutputResolution{};  // 2,097,152 points: far above the test clouds
  const io::ReadResult within = io::read_point_cloud_from_memory(bytes, name, options);
  EXPECT_FALSE(within.decimation.has_value());
  io::ReadResult whole = io::read_point_cloud_from_memory(bytes, name);
  expect_same_cloud(within.cloud, whole.cloud);
  options.decimate.resolution = io::OutputResolution{.width = 40, .height = 40, .budget_points = 1000};
  io::ReadResult over = io::read_point_cloud_from_memory(bytes, name, options);
  EXPECT_TRUE(over.decimation.has_value() && over.decimation->streamed);
  if (over.decimation) io::decimate(whole.cloud, {.voxel = over.decimation->cell});
  expect_same_cloud(over.cloud, whole.cloud);
  return over;
}

/// Each of `inputs`, read as `name` by `read(bytes, name, thinned)`, fails with one message naming the file and a
/// place ("name (byte " or "name:"), the same whether `thinned` (the streamed read) or not (the whole read).
template <class Read>
void expect_same_errors(const std::vector<std::string>& inputs, const std::string& name, Read&& read) {
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    SCOPED_TRACE(i);
    const std::string whole = error_of([&] { read(inputs[i], name, false); });
    EXPECT_TRUE(whole.find(name + " (byte ") != std::string::npos || whole.find(name + ":") != std::string::npos)
        << whole;
    EXPECT_EQ(error_of([&] { read(inputs[i], name, true); }), whole);
  }
}

}  // namespace pcsketch::test
