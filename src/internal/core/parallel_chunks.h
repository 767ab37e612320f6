#pragma once
// A parallel per-index loop that reports progress between chunks (ProgressReporter is not thread-safe).

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>

#include "pcsketch/core/report.h"

namespace pcsketch::detail {

/// Calls body(begin, end) over [0, n) in parallel, in about 20 sequential rounds when there is a `progress` callback
/// (called, and may cancel, between rounds), else in one round (each round ends in a barrier, costly when the cores
/// are shared). The body must write only to slots of its own range, which keeps results identical for any thread
/// count. `grain`: fewest indices a task gets (1 where one index is a whole line of work).
template <class Body>
void parallel_chunks(std::size_t n, const ProgressFn& progress, std::string_view stage, const Body& body,
                     std::size_t grain = 256) {
  const ProgressReporter report(progress, stage);
  const std::size_t round = progress ? std::max<std::size_t>(n / 20 + 1, 16 * grain) : std::max<std::size_t>(n, 1);
  report(0.0);
  for (std::size_t begin = 0; begin < n; begin += round) {
    const std::size_t end = std::min(n, begin + round);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, grain),
                      [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
    report(static_cast<double>(end) / static_cast<double>(n));
  }
  if (n == 0) report(1.0);
}

}  // namespace pcsketch::detail
