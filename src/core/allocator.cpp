#include "pcsketch/core/allocator.h"

#include <cstdlib>  // defines __GLIBC__ where it applies
#include <fstream>
#include <string>

#if defined(__GLIBC__)
#include <malloc.h>
#include <unistd.h>
#endif

// GCC names AddressSanitizer with a macro, clang only through __has_feature. The restart is off under it (and the
// helpers it alone uses go with it), since ASan's own allocator ignores glibc's tunables.
#if defined(__SANITIZE_ADDRESS__)
#define PCSKETCH_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PCSKETCH_UNDER_ASAN 1
#endif
#endif
#if defined(__GLIBC__) && !defined(PCSKETCH_UNDER_ASAN)
#define PCSKETCH_HUGE_PAGE_RESTART 1
#endif

namespace pcsketch {

namespace {

constexpr const char* kHugePageTunable = "glibc.malloc.hugetlb=1";

#if defined(PCSKETCH_HUGE_PAGE_RESTART)
/// The kernel's transparent huge page mode reads "always [madvise] never" with the chosen one in brackets.
bool huge_pages_on_request() {
  std::ifstream mode("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  return std::getline(mode, line) && line.find("[madvise]") != std::string::npos;
}
#endif

}  // namespace

void keep_freed_memory() {
#if defined(__GLIBC__)
  // Both are needed: a high mmap threshold alone returns the heap's freed top at every free (the trim threshold
  // is 128 KiB), and a high trim threshold alone fixes the mmap threshold at 128 KiB (both measured slower).
  constexpr int kOneGiB = 1 << 30;
  mallopt(M_MMAP_THRESHOLD, kOneGiB);
  mallopt(M_TRIM_THRESHOLD, kOneGiB);
#endif
}

std::string detail::huge_page_tunables(const char* current) {
  const std::string tunables = current ? current : "";
  if (tunables.find("glibc.malloc.hugetlb") != std::string::npos) return {};  // set already, by us or the user
  return tunables.empty() ? kHugePageTunable : tunables + ":" + kHugePageTunable;
}

void restart_with_huge_pages(char** argv) {
#if defined(PCSKETCH_HUGE_PAGE_RESTART)
  const std::string tunables = detail::huge_page_tunables(std::getenv("GLIBC_TUNABLES"));
  // A preloaded library (valgrind's tools, heaptrack, another malloc) may own malloc, and the restarted program would
  // run outside the tool that watches it. Under "always" every heap already gets huge pages; under "never" none can.
  const char* preload = std::getenv("LD_PRELOAD");
  if (tunables.empty() || !argv || (preload && *preload) || !huge_pages_on_request()) return;
  if (setenv("GLIBC_TUNABLES", tunables.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);  // returns only on failure: go on as we are, the variable marks the attempt
#else
  (void)argv;
#endif
}

}  // namespace pcsketch
