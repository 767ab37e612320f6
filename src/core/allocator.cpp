#include "pcsketch/core/allocator.h"

#include <cstdlib>  // defines __GLIBC__ where it applies

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace pcsketch {

void keep_freed_memory() {
#if defined(__GLIBC__)
  // Both are needed: a high mmap threshold alone returns the heap's freed top at every free (the trim threshold
  // is 128 KiB), and a high trim threshold alone fixes the mmap threshold at 128 KiB (both measured slower).
  constexpr int kOneGiB = 1 << 30;
  mallopt(M_MMAP_THRESHOLD, kOneGiB);
  mallopt(M_TRIM_THRESHOLD, kOneGiB);
#endif
}

}  // namespace pcsketch
