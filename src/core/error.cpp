#include "pcsketch/core/error.h"

#include "pcsketch/core/assert.h"

namespace pcsketch {

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
