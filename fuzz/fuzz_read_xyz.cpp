// libFuzzer target: the XYZ/PTS/CSV text reader (PTS count line, header line, column layouts).

#include "fuzz_read.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The first byte picks the extension, so both column conventions (xyz and pts) are explored.
  if (size == 0) return 0;
  pcsketch::fuzz::read_both(data + 1, size - 1, data[0] & 1 ? "fuzz.pts" : "fuzz.xyz");
  return 0;
}
