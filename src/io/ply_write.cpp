#include <array>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>

#include "ply_types.h"
#include "pcsketch/core/atomic_file.h"
#include "pcsketch/core/error.h"
#include "pcsketch/io/ply.h"

namespace pcsketch::io {
namespace {

/// Appends values in the chosen layout: binary in the file's byte order, or ascii with the shortest text that reads
/// back to the same value.
class BodyWriter {
 public:
  explicit BodyWriter(PlyFormat format) : format_(format) {
    swap_ = format != PlyFormat::Ascii &&
            (format == PlyFormat::BinaryBigEndian) != (std::endian::native == std::endian::big);
  }

  template <class T>
  void put(T value) {
    if (format_ == PlyFormat::Ascii) {
      std::array<char, 32> text;
      // uchar is a number in ascii PLY, not a character.
      const auto [end, ec] = std::to_chars(text.data(), text.data() + text.size(), +value);
      out_.insert(out_.end(), text.data(), end);
      out_.push_back(' ');
      return;
    }
    std::array<char, sizeof(T)> b;
    std::memcpy(b.data(), &value, sizeof(T));
    if (swap_) std::reverse(b.begin(), b.end());
    out_.insert(out_.end(), b.begin(), b.end());
  }
  void end_entry() {
    if (format_ == PlyFormat::Ascii) out_.back() = '\n';
  }
  const std::vector<char>& bytes() const { return out_; }
  void reserve(std::size_t n) { out_.reserve(n); }

 private:
  PlyFormat format_;
  bool swap_ = false;
  std::vector<char> out_;
};

std::size_t attribute_size(const PlyAttribute& a) {
  return std::visit([](const auto& span) { return span.size(); }, a.values);
}

}  // namespace

void write_ply(const std::string& path, const PointCloud& cloud, const std::vector<PlyAttribute>& attributes,
               const PlyWriteOptions& options) {
  const FileLoc where{path, {}, {}};
  for (const PlyAttribute& a : attributes) {
    if (a.name.empty() || a.name.find_first_of(" \t\r\n") != std::string::npos)
      throw Error(where, "PLY writer: attribute name \"" + a.name + "\" is empty or has blanks");
    if (attribute_size(a) != cloud.size())
      throw Error(where, "PLY writer: attribute \"" + a.name + "\" has " + std::to_string(attribute_size(a)) +
                             " values for " + std::to_string(cloud.size()) + " points");
  }
  for (const std::string& c : options.comments)
    if (c.find('\n') != std::string::npos) throw Error(where, "PLY writer: a comment contains a newline");

  // World coordinates: double keeps a large origin's precision; float is exact when there is no origin.
  const bool doubles = !cloud.origin.isZero();
  std::string header = "ply\nformat ";
  header += options.format == PlyFormat::Ascii                ? "ascii 1.0\n"
            : options.format == PlyFormat::BinaryLittleEndian ? "binary_little_endian 1.0\n"
                                                              : "binary_big_endian 1.0\n";
  for (const std::string& c : options.comments) header += "comment " + c + "\n";
  header += "element vertex " + std::to_string(cloud.size()) + "\n";
  for (const char* axis : {"x", "y", "z"})
    header += std::string("property ") + (doubles ? "double " : "float ") + axis + "\n";
  if (cloud.has_normals()) header += "property float nx\nproperty float ny\nproperty float nz\n";
  if (cloud.has_colors()) header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  for (const PlyAttribute& a : attributes) {
    const char* type = std::holds_alternative<std::span<const float>>(a.values)          ? "float"
                       : std::holds_alternative<std::span<const std::int32_t>>(a.values) ? "int"
                                                                                         : "uchar";
    header += std::string("property ") + type + " " + a.name + "\n";
  }
  header += "end_header\n";

  BodyWriter body(options.format);
  body.reserve(cloud.size() * (doubles ? 24 : 12) * (options.format == PlyFormat::Ascii ? 2 : 1));
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (doubles) {
      const Vec3d w = cloud.world(i);
      for (int k = 0; k < 3; ++k) body.put(w[k]);
    } else {
      for (int k = 0; k < 3; ++k) body.put(cloud.positions[i][k]);
    }
    if (cloud.has_normals())
      for (int k = 0; k < 3; ++k) body.put(cloud.normals[i][k]);
    if (cloud.has_colors())
      for (const std::uint8_t c : cloud.colors[i]) body.put(c);
    for (const PlyAttribute& a : attributes) std::visit([&](const auto& span) { body.put(span[i]); }, a.values);
    body.end_entry();
  }

  // Into a temporary file renamed over `path` when complete: a failure leaves an existing file as it was.
  TempFile temp(path);
  std::FILE* file = std::fopen(temp.path().c_str(), "wb");
  if (!file) throw Error(where, "PLY writer: cannot open for writing: " + std::string(std::strerror(errno)));
  const std::vector<char>& bytes = body.bytes();
  const bool written = std::fwrite(header.data(), 1, header.size(), file) == header.size() &&
                       std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size() && std::fflush(file) == 0;
  const int write_error = errno;
  const bool closed = std::fclose(file) == 0;
  if (!written || !closed)
    throw Error(where, "PLY writer: write failed: " + std::string(std::strerror(written ? errno : write_error)));
  temp.commit();
}

}  // namespace pcsketch::io
