#include "support/las_writer.h"

#include <cmath>
#include <cstring>

namespace pcsketch::test {
namespace {

void put(std::string& out, std::uint64_t value, std::size_t n) {
  // Fields wider than 8 bytes (GUID, counts by return) are written as zeros past the value's 8 bytes.
  for (std::size_t i = 0; i < n; ++i) out += static_cast<char>(i < 8 ? (value >> (8 * i)) & 0xFFu : 0u);
}
void put_double(std::string& out, double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, 8);
  put(out, bits, 8);
}
void put_text(std::string& out, const std::string& text, std::size_t n) {
  std::string field = text.substr(0, n);
  field.resize(n, '\0');
  out += field;
}

// A VLR (`length_bytes` 2) or EVLR (8) header: reserved, user id, record id, length after the header, description.
void put_record_header(std::string& out, std::uint16_t record_id, std::size_t length, std::size_t length_bytes) {
  put(out, 0, 2);
  put_text(out, "pcsketch test", 16);
  put(out, record_id, 2);
  put(out, length, length_bytes);
  put_text(out, "a test record", 32);
}

std::string record(const LasFile& f, const LasPoint& p) {
  std::string r;
  const Vec3d q = ((p.position - f.offset).array() / f.scale.array()).round();
  for (int a = 0; a < 3; ++a) put(r, static_cast<std::uint32_t>(static_cast<std::int32_t>(q[a])), 4);
  put(r, p.intensity, 2);
  if (f.format < 6) {
    put(r, (p.return_number & 7u) | ((p.number_of_returns & 7u) << 3), 1);
    put(r, p.classification & 31u, 1);
    put(r, 0, 4);                                                // scan angle rank, user data, point source id
    if (f.format != 0 && f.format != 2) put_double(r, 12345.5);  // GPS time
    if (f.format == 2 || f.format == 3 || f.format == 5)
      for (const std::uint16_t c : p.rgb) put(r, c, 2);
    if (f.format == 4 || f.format == 5) put(r, 0, 29);  // wave packet
  } else {
    put(r, (p.return_number & 15u) | ((p.number_of_returns & 15u) << 4), 1);
    put(r, 0, 1);  // classification flags, scanner channel, scan direction, edge
    put(r, p.classification, 1);
    put(r, 0, 5);  // user data, scan angle, point source id
    put_double(r, 12345.5);
    if (f.format == 7 || f.format == 8 || f.format == 10)
      for (const std::uint16_t c : p.rgb) put(r, c, 2);
    if (f.format == 8 || f.format == 10) put(r, 0, 2);  // NIR
    if (f.format == 9 || f.format == 10) put(r, 0, 29);
  }
  r.append(f.extra_bytes, '\x5A');
  return r;
}

}  // namespace

std::size_t las_record_size(unsigned format) {
  static constexpr std::size_t kSize[] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
  return kSize[format];
}

std::size_t las_header_size(unsigned minor) { return minor >= 4 ? 375 : minor == 3 ? 235 : 227; }

Vec3d las_quantised(const LasFile& f, const Vec3d& p) {
  const Vec3d q = ((p - f.offset).array() / f.scale.array()).round();
  return f.offset + Vec3d(f.scale.array() * q.array());
}

std::string write_las(const LasFile& f) {
  std::string vlrs;
  for (const std::string& payload : f.vlr_payloads) {
    put_record_header(vlrs, 1, payload.size(), 2);
    vlrs += payload;
  }
  const std::size_t header_size = las_header_size(f.minor);
  const std::size_t record_length = las_record_size(f.format) + f.extra_bytes;
  const std::uint64_t count = f.points.size();
  const std::uint64_t points_end = header_size + vlrs.size() + count * record_length;

  std::string h;
  h += "LASF";
  put(h, 0, 2);   // file source id
  put(h, 0, 2);   // global encoding
  put(h, 0, 16);  // GUID
  put(h, 1, 1);
  put(h, f.minor, 1);
  put_text(h, "pcsketch", 32);
  put_text(h, "las_writer.cpp", 32);
  put(h, 1, 2);
  put(h, 2026, 2);
  put(h, header_size, 2);
  put(h, header_size + vlrs.size(), 4);
  put(h, f.vlr_payloads.size(), 4);
  put(h, f.format, 1);
  put(h, record_length, 2);
  // Formats 6-10 leave the legacy counts 0 (spec 1.4); older ones fill them.
  put(h, f.format >= 6 ? 0 : count, 4);
  put(h, f.format >= 6 ? 0 : count, 4);
  put(h, 0, 16);
  for (int a = 0; a < 3; ++a) put_double(h, f.scale[a]);
  for (int a = 0; a < 3; ++a) put_double(h, f.offset[a]);
  Vec3d lo = Vec3d::Zero(), hi = Vec3d::Zero();
  for (std::size_t i = 0; i < f.points.size(); ++i) {
    lo = i == 0 ? f.points[i].position : lo.cwiseMin(f.points[i].position);
    hi = i == 0 ? f.points[i].position : hi.cwiseMax(f.points[i].position);
  }
  for (int a = 0; a < 3; ++a) {
    put_double(h, hi[a]);
    put_double(h, lo[a]);
  }
  if (f.minor >= 3) put(h, 0, 8);  // start of waveform data
  if (f.minor >= 4) {
    put(h, f.evlr_payloads.empty() ? 0 : points_end, 8);
    put(h, f.evlr_payloads.size(), 4);
    put(h, count, 8);
    put(h, count, 8);
    put(h, 0, 14 * 8);
  }
  std::string out = h + vlrs;
  for (const LasPoint& p : f.points) out += record(f, p);
  for (const std::string& payload : f.evlr_payloads) {
    put_record_header(out, 2, payload.size(), 8);
    out += payload;
  }
  return out;
}

void poke(std::string& bytes, std::size_t offset, std::uint64_t value, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) bytes[offset + i] = static_cast<char>((value >> (8 * i)) & 0xFFu);
}

}  // namespace pcsketch::test
