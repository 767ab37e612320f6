#pragma once
// The allocator settings for a process that draws one large cloud (the CLI, the benches). Each stage allocates fresh
// per-point buffers of tens of MiB and frees them; by default glibc maps each one, the kernel zero-fills it page by
// page on first touch and it is unmapped again on free, so a 1M-point draw spent ~0.7 s of system time faulting
// pages (docs/geometry.md, "Keeping freed memory" and "Huge pages").

#include <string>

namespace pcsketch {

/// Makes glibc's malloc serve blocks up to 1 GiB from its heap and keep freed memory for the next stage instead of
/// returning it to the kernel. Process-wide and for the process's life, so the library never calls it itself: a
/// program whose job is drawing calls it once at start. Peak memory grows by a few percent. A no-op without glibc.
void keep_freed_memory();

/// Restarts the program (execv of /proc/self/exe with the same arguments, so the same process) with glibc's malloc
/// asked to back its memory with transparent huge pages (GLIBC_TUNABLES=glibc.malloc.hugetlb=1, which glibc reads
/// only at start): a 2 MiB page faults in at once and one TLB entry maps it (a 1M-point draw: 2.43 → 2.06 s).
/// Returns without restarting where it cannot help: the tunable already set (by an earlier call or the user, who
/// opts out with glibc.malloc.hugetlb=0), the kernel's mode not "madvise" ("always" gives every heap huge pages
/// already, "never" none), no glibc, a sanitizer's allocator, or LD_PRELOAD set (valgrind and heap profilers).
/// Call it first thing in main(), before any thread starts; a host program (Python) sets the variable itself.
void restart_with_huge_pages(char** argv);

namespace detail {
/// GLIBC_TUNABLES with the huge page tunable added to `current` (null: unset); empty if it names that tunable.
std::string huge_page_tunables(const char* current);
}  // namespace detail

}  // namespace pcsketch
