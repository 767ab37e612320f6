#pragma once
// PLY scalar types, shared by the reader and the writer.

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string_view>

namespace pcsketch::io::detail {

enum class PlyScalar : std::uint8_t { I8, U8, I16, U16, I32, U32, F32, F64 };

/// Both spellings of every type ("uchar" and "uint8", …); nullopt for an unknown name.
inline std::optional<PlyScalar> ply_scalar_from_name(std::string_view name) {
  static constexpr std::array<std::pair<std::string_view, PlyScalar>, 16> kNames{{
      {"char", PlyScalar::I8},
      {"int8", PlyScalar::I8},
      {"uchar", PlyScalar::U8},
      {"uint8", PlyScalar::U8},
      {"short", PlyScalar::I16},
      {"int16", PlyScalar::I16},
      {"ushort", PlyScalar::U16},
      {"uint16", PlyScalar::U16},
      {"int", PlyScalar::I32},
      {"int32", PlyScalar::I32},
      {"uint", PlyScalar::U32},
      {"uint32", PlyScalar::U32},
      {"float", PlyScalar::F32},
      {"float32", PlyScalar::F32},
      {"double", PlyScalar::F64},
      {"float64", PlyScalar::F64},
  }};
  for (const auto& [n, t] : kNames)
    if (n == name) return t;
  return std::nullopt;
}

inline std::size_t ply_scalar_size(PlyScalar t) {
  switch (t) {
    case PlyScalar::I8:
    case PlyScalar::U8:
      return 1;
    case PlyScalar::I16:
    case PlyScalar::U16:
      return 2;
    case PlyScalar::I32:
    case PlyScalar::U32:
    case PlyScalar::F32:
      return 4;
    case PlyScalar::F64:
      return 8;
  }
  return 0;
}

template <class T>
T load_swapped(const char* p, bool swap) {
  std::array<char, sizeof(T)> b;
  std::memcpy(b.data(), p, sizeof(T));
  if (swap) std::reverse(b.begin(), b.end());
  T v;
  std::memcpy(&v, b.data(), sizeof(T));
  return v;
}

/// One binary value at `p` (byte-swapped when `swap`), as double.
inline double load_ply_scalar(PlyScalar t, const char* p, bool swap) {
  switch (t) {
    case PlyScalar::I8:
      return load_swapped<std::int8_t>(p, swap);
    case PlyScalar::U8:
      return load_swapped<std::uint8_t>(p, swap);
    case PlyScalar::I16:
      return load_swapped<std::int16_t>(p, swap);
    case PlyScalar::U16:
      return load_swapped<std::uint16_t>(p, swap);
    case PlyScalar::I32:
      return load_swapped<std::int32_t>(p, swap);
    case PlyScalar::U32:
      return load_swapped<std::uint32_t>(p, swap);
    case PlyScalar::F32:
      return load_swapped<float>(p, swap);
    case PlyScalar::F64:
      return load_swapped<double>(p, swap);
  }
  return 0;
}

}  // namespace pcsketch::io::detail
