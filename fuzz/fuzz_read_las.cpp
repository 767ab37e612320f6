// libFuzzer target: the LAS reader (header, VLRs, counts against the file size, point formats 0-10).

#include "fuzz_read.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pcsketch::fuzz::read_both(data, size, "fuzz.las");
  return 0;
}
