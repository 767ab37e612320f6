// libFuzzer target: the PCD (with LZF), OFF and OBJ readers.

#include "fuzz_read.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const kNames[] = {"fuzz.pcd", "fuzz.off", "fuzz.obj"};
  pcsketch::fuzz::read_both(data + 1, size - 1, kNames[data[0] % 3]);
  return 0;
}
