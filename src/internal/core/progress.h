#pragma once
// Progress helpers shared by the stages: one callback handed down to the steps, sequential loops reported sparsely.

#include <algorithm>
#include <cstddef>
#include <string_view>

#include "pcsketch/core/report.h"

namespace pcsketch::detail {

/// `options` with its progress set to `progress` unless it has its own.
template <class Options>
Options with_progress(Options options, const ProgressFn& progress) {
  if (!options.progress) options.progress = progress;
  return options;
}

/// A sequential loop's progress, reported about 20 times whatever its length (the callback may write to a terminal):
/// 0 on construction, then done/total each time `done` passes the next twentieth of `total`, 1 on finish(). Each
/// report may throw pcsketch::Cancelled. Call from one thread.
class ProgressSteps {
 public:
  ProgressSteps(const ProgressFn& progress, std::string_view stage, std::size_t total)
      : report_(progress, stage), total_(total), step_(std::max<std::size_t>(total / 20, 1)), next_(step_) {
    report_(0.0);
  }
  void at(std::size_t done) {
    if (done < next_ || done >= total_) return;
    report_(static_cast<double>(done) / static_cast<double>(total_));
    next_ = done + step_;
  }
  void finish() const { report_(1.0); }

 private:
  ProgressReporter report_;
  std::size_t total_, step_, next_;
};

}  // namespace pcsketch::detail
