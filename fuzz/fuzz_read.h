#pragma once
// Shared body of the reader fuzz targets: any input must give a cloud or a pcsketch::Error, nothing else.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "pcsketch/core/error.h"
#include "pcsketch/io/read_cloud.h"

namespace pcsketch::fuzz {

/// Reads `data` as a cloud and as a mesh under the name `name_hint` (whose extension picks the reader when no magic
/// matches). Only pcsketch::Error may escape the readers; anything else (or a sanitizer report) is a finding.
inline void read_both(const std::uint8_t* data, std::size_t size, const std::string& name_hint) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const io::ReadResult r = io::read_point_cloud_from_memory(bytes, name_hint);
    if (r.cloud.empty()) __builtin_trap();  // an empty cloud must be an error
  } catch (const Error&) {
  }
  try {
    const Mesh m = io::read_mesh_from_memory(bytes, name_hint);
    for (const auto& f : m.faces)
      for (const std::uint32_t v : f)
        if (v >= m.vertices.size()) __builtin_trap();  // face indices were validated
  } catch (const Error&) {
  }
}

}  // namespace pcsketch::fuzz
