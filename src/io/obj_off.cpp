// OFF and OBJ readers: the vertices are the cloud; faces are read (and fan-triangulated) only for meshes.

#include <algorithm>
#include <array>

#include "raw_cloud.h"
#include "text_scan.h"

namespace pcsketch::io::detail {
namespace {

std::string_view strip_comment(std::string_view line) { return line.substr(0, line.find('#')); }

/// The next line with something on it besides a '#' comment; false at the end.
bool next_content_line(LineReader& lines, std::string_view& line) {
  while (lines.next(line)) {
    line = strip_comment(line);
    if (line.find_first_not_of(" \t\r\v\f") != std::string_view::npos) return true;
  }
  return false;
}

double number(const Source& src, const LineReader& lines, std::string_view token, const char* format) {
  double v = 0;
  if (!parse_double(token, v)) src.fail_at_line(lines.line(), std::string(format) + ": " + bad_number(token));
  return v;
}

}  // namespace

RawCloud parse_off(const Source& src, Want want) {
  LineReader lines(src.bytes, 1, src.path);
  std::string_view line;
  next_content_line(lines, line);
  Tokens header(line, false);
  std::string_view magic;
  header.next(magic);
  // Variants: [C][N]OFF (colours, normals per vertex). 4OFF, nOFF and STOFF change the vertex layout.
  const std::string_view prefix = magic.substr(0, magic.size() - 3);
  if (prefix != "" && prefix != "C" && prefix != "N" && prefix != "CN" && prefix != "NC")
    src.fail_at_line(lines.line(), "OFF: unsupported variant " + quote(magic));
  const bool has_normals = prefix.find('N') != std::string_view::npos;

  // The counts may follow the magic on the same line.
  std::array<std::uint64_t, 2> counts{};
  std::string_view token;
  Tokens count_tokens = header;
  if (header.done()) {
    if (!next_content_line(lines, line)) src.fail_at_line(lines.line(), "OFF: no vertex/face count line");
    count_tokens = Tokens(line, false);
  }
  for (std::uint64_t& c : counts)
    if (!count_tokens.next(token) || !parse_uint(token, c))
      src.fail_at_line(lines.line(), "OFF: the count line must start with the vertex and face counts");
  // Each vertex line takes at least 6 bytes ("0 0 0\n"), each face line at least 2: check before allocating.
  const std::uint64_t left = lines.rest().size();
  if (counts[0] > left / 6 + 1 || counts[1] > left / 2 + 1 || counts[0] > 0xffffffffull)
    src.fail_at_line(lines.line(), "OFF: header claims " + std::to_string(counts[0]) + " vertices and " +
                                       std::to_string(counts[1]) + " faces, but only " + std::to_string(left) +
                                       " bytes follow (truncated file?)");

  RawCloud raw;
  raw.format = std::string("off") + (has_normals ? " (normals)" : "");
  if (prefix.find('C') != std::string_view::npos) raw.other_attributes.push_back("colour");
  raw.positions.resize(counts[0]);
  if (has_normals) raw.normals.resize(counts[0]);
  const std::size_t per_vertex = has_normals ? 6 : 3;
  std::array<double, 6> v{};
  for (std::uint64_t i = 0; i < counts[0]; ++i) {
    if (!next_content_line(lines, line))
      src.fail_at_line(lines.line() + 1,
                       "OFF: file ends after " + std::to_string(i) + " of " + std::to_string(counts[0]) + " vertices");
    Tokens tokens(line, false);
    for (std::size_t k = 0; k < per_vertex; ++k) {
      if (!tokens.next(token))
        src.fail_at_line(lines.line(),
                         "OFF: too few values on a vertex line (need " + std::to_string(per_vertex) + ")");
      v[k] = number(src, lines, token, "OFF");
    }
    raw.positions[i] = Vec3d(v[0], v[1], v[2]);
    if (has_normals) raw.normals[i] = Vec3f(float(v[3]), float(v[4]), float(v[5]));
  }
  if (want == Want::Points) return raw;

  std::vector<std::uint32_t> polygon;
  for (std::uint64_t f = 0; f < counts[1]; ++f) {
    if (!next_content_line(lines, line))
      src.fail_at_line(lines.line() + 1,
                       "OFF: file ends after " + std::to_string(f) + " of " + std::to_string(counts[1]) + " faces");
    Tokens tokens(line, false);
    std::uint64_t n = 0, index = 0;
    if (!tokens.next(token) || !parse_uint(token, n))
      src.fail_at_line(lines.line(), "OFF: a face line must start with its vertex count");
    polygon.clear();
    for (std::uint64_t k = 0; k < n; ++k) {
      if (!tokens.next(token) || !parse_uint(token, index) || index >= counts[0])
        src.fail_at_line(lines.line(), "OFF: face " + std::to_string(f) + " needs " + std::to_string(n) +
                                           " vertex indices below " + std::to_string(counts[0]));
      polygon.push_back(static_cast<std::uint32_t>(index));
    }
    add_fan(polygon, raw.faces);
  }
  return raw;
}

RawCloud parse_obj(const Source& src, Want want) {
  RawCloud raw;
  raw.format = "obj";
  LineReader lines(src.bytes, 1, src.path);
  std::string_view line, keyword, token;
  std::vector<std::uint32_t> polygon;
  bool has_vn = false;
  while (next_content_line(lines, line)) {
    Tokens tokens(line, false);
    tokens.next(keyword);
    if (keyword == "v") {
      std::array<double, 3> v{};
      for (double& x : v) {
        if (!tokens.next(token)) src.fail_at_line(lines.line(), "OBJ: a vertex needs x y z");
        x = number(src, lines, token, "OBJ");
      }
      raw.positions.emplace_back(v[0], v[1], v[2]);
    } else if (keyword == "vn") {
      has_vn = true;
    } else if (keyword == "f" && want == Want::Mesh) {
      // Corners are v, v/vt, v//vn or v/vt/vn; 1-based, negative counts back from the last vertex.
      polygon.clear();
      while (tokens.next(token)) {
        const std::string_view v = token.substr(0, token.find('/'));
        const bool negative = v.starts_with("-");
        std::uint64_t k = 0;
        const std::uint64_t count = raw.positions.size();
        if (!parse_uint(negative ? v.substr(1) : v, k) || k == 0 || k > count)
          src.fail_at_line(lines.line(), "OBJ: face corner \"" + std::string(token.substr(0, 32)) +
                                             "\" is not a vertex index in 1.." + std::to_string(count));
        polygon.push_back(static_cast<std::uint32_t>(negative ? count - k : k - 1));
      }
      add_fan(polygon, raw.faces);
    }
  }
  // OBJ normals belong to face corners, not to vertices: not kept.
  if (has_vn) raw.other_attributes.push_back("vn (per face corner)");
  return raw;
}

}  // namespace pcsketch::io::detail
