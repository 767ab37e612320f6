#pragma once
// The allocator setting for a process that draws one large cloud (the CLI, the benches). Each stage allocates fresh
// per-point buffers of tens of MiB and frees them; by default glibc maps each one, the kernel zero-fills it page by
// page on first touch and it is unmapped again on free, so a 1M-point draw spent ~0.7 s of system time faulting
// pages (docs/geometry.md, "Keeping freed memory").

namespace pcsketch {

/// Makes glibc's malloc serve blocks up to 1 GiB from its heap and keep freed memory for the next stage instead of
/// returning it to the kernel. Process-wide and for the process's life, so the library never calls it itself: a
/// program whose job is drawing calls it once at start. Peak memory grows by a few percent. A no-op without glibc.
void keep_freed_memory();

}  // namespace pcsketch
