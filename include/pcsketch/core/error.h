#pragma once
// Errors: one exception type for everything the library rejects.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace pcsketch {

/// Input text for a message: in double quotes, at most `max_bytes` of it (then "..."), every byte outside printable
/// ASCII as \xNN. A message quotes input through this, so a 10 MB token or an escape sequence never reaches a terminal.
std::string quote(std::string_view text, std::size_t max_bytes = 80);

/// `message` as one printable line: control bytes (a newline or NUL in a path, an ESC) as \xNN, cut after
/// kMaxMessageBytes at a character boundary.
inline constexpr std::size_t kMaxMessageBytes = 600;
std::string one_line(std::string_view message);

/// A number for a message in its shortest exact form ("0.2", "1e+308", "nan"), never 309 digits.
std::string number(double value);

/// Where in an input file something went wrong (pbrt's FileLoc): a line for text, a byte offset for binary.
struct FileLoc {
  std::string path;
  std::optional<std::uint64_t> line;         ///< 1-based line number (text formats)
  std::optional<std::uint64_t> byte_offset;  ///< 0-based byte offset (binary formats)

  /// "path:12" or "path (byte 1234)" or "path".
  std::string to_string() const;
};

/// Thrown by every stage for bad input or a violated precondition. The message is one line meant for the user:
/// it names the file and place (if any) and the subsystem, e.g. "scan.ply (byte 812): PLY: body truncated, …".
/// The message is stored through one_line(), so it stays one line whatever the input held.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(one_line(message)) {}
  Error(const FileLoc& where, const std::string& message) : Error(where.to_string() + ": " + message) {}
};

}  // namespace pcsketch
