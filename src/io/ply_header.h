#pragma once
// A PLY header: its elements and their properties, checked against the body's size before any entry is read.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ply_types.h"
#include "raw_cloud.h"

namespace pcsketch::io::detail {

enum class Encoding : std::uint8_t { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Property {
  std::string name;
  PlyScalar type = PlyScalar::F32;      ///< the value type (items, for a list)
  std::optional<PlyScalar> count_type;  ///< set for a list property
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::uint64_t line = 0;  ///< header line declaring it
  std::vector<Property> properties;
};

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;
  std::uint64_t body_line = 0;  ///< line number of the first body line (ascii)
};

/// Parses the header of `src` (a PLY file: its first line is "ply").
Header parse_header(const Source& src);

/// Fails unless every element's smallest possible entries fit in the bytes after the header: a count is never
/// trusted before it is checked against the file size.
void check_counts(const Source& src, const Header& h);

}  // namespace pcsketch::io::detail
