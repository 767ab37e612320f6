// libFuzzer target: the PLY reader (ascii and both binary layouts), as a cloud and as a mesh.

#include "fuzz_read.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pcsketch::fuzz::read_both(data, size, "fuzz.ply");
  return 0;
}
