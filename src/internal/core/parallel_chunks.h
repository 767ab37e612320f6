#pragma once
// A parallel per-index loop that reports progress as its pieces finish (ProgressReporter is not thread-safe).

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <mutex>

#include "pcsketch/core/report.h"

namespace pcsketch::detail {

/// Calls body(begin, end) over [0, n) in one parallel loop. With a `progress` callback, the worker that finishes a
/// piece reports the fraction done when no other report is running (a try-lock: reports never overlap and never make
/// a worker wait), at most about 50 times; a callback returning false throws Cancelled out of that worker, which
/// cancels the loop and rethrows in the caller. One loop, not rounds: a barrier per round left a core idle while the
/// slowest piece of each round finished (uneven work such as a noisy cloud's widened fits). The body must write only
/// to slots of its own range, which keeps results identical for any thread count. `grain`: fewest indices a task
/// gets (1 where one index is a whole line of work).
template <class Body>
void parallel_chunks(std::size_t n, const ProgressFn& progress, std::string_view stage, const Body& body,
                     std::size_t grain = 256) {
  const ProgressReporter report(progress, stage);
  report(0.0);
  if (n == 0) {
    report(1.0);
    return;
  }
  if (!progress) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain),
                      [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
    return;
  }
  // Pieces of at most n/50 so that reports come often enough; the loop's own splitting keeps them balanced.
  const std::size_t piece = std::max<std::size_t>(grain, n / 50 + 1);
  std::atomic<std::size_t> done{0};
  std::size_t reported = 0;  // guarded by `reporting`
  std::mutex reporting;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, piece), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t begin = r.begin(); begin < r.end(); begin += grain) {
      const std::size_t end = std::min(r.end(), begin + grain);
      body(begin, end);
      const std::size_t now = done.fetch_add(end - begin) + (end - begin);
      if (now - reported < piece && now != n) continue;
      const std::unique_lock lock(reporting, std::try_to_lock);
      if (!lock.owns_lock() || now <= reported) continue;
      reported = now;
      report(static_cast<double>(now) / static_cast<double>(n));
    }
  });
}

}  // namespace pcsketch::detail
