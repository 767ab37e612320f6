#pragma once
// Errors: one exception type for everything the library rejects.

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

namespace pcsketch {

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
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
  Error(const FileLoc& where, const std::string& message) : std::runtime_error(where.to_string() + ": " + message) {}
};

}  // namespace pcsketch
