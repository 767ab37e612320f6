#pragma once
// A LAS 1.0-1.4 writer for the reader's tests, written from the ASPRS specification apart from the reader (so that a
// reader bug and a writer bug cannot cancel out). Fields the reader does not keep are written as zeros.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::test {

struct LasPoint {
  Vec3d position;
  std::uint16_t intensity = 0;
  std::uint8_t return_number = 1;
  std::uint8_t number_of_returns = 1;
  std::uint8_t classification = 0;
  std::array<std::uint16_t, 3> rgb{};  ///< written by formats 2, 3, 5, 7, 8, 10
};

struct LasFile {
  unsigned minor = 2;           ///< version 1.minor
  unsigned format = 0;          ///< point data record format 0-10
  std::size_t extra_bytes = 0;  ///< per point, after the standard fields
  Vec3d scale = Vec3d::Constant(0.001);
  Vec3d offset = Vec3d::Zero();
  std::vector<LasPoint> points;
  std::vector<std::string> vlr_payloads;   ///< one VLR each, user id "pcsketch test"
  std::vector<std::string> evlr_payloads;  ///< 1.4 only: after the points
};

/// Smallest point record of each format, as the specification's tables give them.
std::size_t las_record_size(unsigned format);

/// Size of the public header of version 1.minor.
std::size_t las_header_size(unsigned minor);

/// The whole file. Positions are quantised as round((p - offset) / scale).
std::string write_las(const LasFile& file);

/// The position the reader must return for `p`: offset + scale * round((p - offset) / scale).
Vec3d las_quantised(const LasFile& file, const Vec3d& p);

/// Overwrites `n` little-endian bytes of `value` at `offset` of `bytes` (malformed headers).
void poke(std::string& bytes, std::size_t offset, std::uint64_t value, std::size_t n);

}  // namespace pcsketch::test
