#include "pcsketch/core/error.h"

#include <charconv>

#include "pcsketch/core/assert.h"

namespace pcsketch {

namespace {
void append_hex(std::string& out, unsigned char c) {
  static constexpr char kHex[] = "0123456789abcdef";
  out += "\\x";
  out += kHex[c >> 4];
  out += kHex[c & 15];
}
}  // namespace

std::string quote(std::string_view text, std::size_t max_bytes) {
  std::string out = "\"";
  for (const char c : text.substr(0, max_bytes)) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f && c != '"' && c != '\\')
      out += c;
    else if (c == '"' || c == '\\')
      out += std::string("\\") + c;
    else
      append_hex(out, u);
  }
  if (text.size() > max_bytes) out += "...";
  return out + "\"";
}

std::string number(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string one_line(std::string_view message) {
  std::string out;
  for (const char c : message.substr(0, kMaxMessageBytes)) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f)
      append_hex(out, u);
    else
      out += c;
  }
  if (message.size() > kMaxMessageBytes) {
    // Cut at a character boundary (UTF-8 continuation bytes are 10xxxxxx).
    while (!out.empty() && (static_cast<unsigned char>(out.back()) & 0xc0) == 0x80) out.pop_back();
    if (!out.empty() && static_cast<unsigned char>(out.back()) >= 0xc0) out.pop_back();
    out += "...";
  }
  return out;
}

std::string FileLoc::to_string() const {
  std::string s = path;
  if (line) s += ":" + std::to_string(*line);
  if (byte_offset) s += " (byte " + std::to_string(*byte_offset) + ")";
  return s;
}

namespace detail {
void assert_failed(const char* condition, const char* file, int line, const std::string& message) {
  throw Error(std::string("internal check failed at ") + file + ":" + std::to_string(line) + ": " + condition + ": " +
              message);
}
}  // namespace detail

}  // namespace pcsketch
