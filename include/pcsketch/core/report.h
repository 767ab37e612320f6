#pragma once
// Progress, cancellation and warnings travel through options, never globals: the library is silent by default.

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace pcsketch {

/// Called as a long stage progresses: stage name and fraction done in [0, 1].
/// Return false to ask the stage to stop; it then throws pcsketch::Cancelled.
using ProgressFn = std::function<bool(std::string_view stage, double fraction)>;

/// Thrown when a ProgressFn asked to stop.
struct Cancelled : std::exception {
  const char* what() const noexcept override { return "cancelled"; }
};

/// Reports progress at most every `step` fraction so callbacks stay cheap in parallel loops.
/// Not thread-safe: call from one thread (e.g. between parallel chunks).
class ProgressReporter {
 public:
  ProgressReporter(const ProgressFn& fn, std::string_view stage) : fn_(fn), stage_(stage) {}
  /// Reports `fraction`; throws Cancelled if the callback says stop.
  void operator()(double fraction) const;

 private:
  const ProgressFn& fn_;
  std::string_view stage_;
};

/// Non-fatal problems a stage noticed (dropped points, degenerate input); the CLI prints them as warnings.
using Warnings = std::vector<std::string>;

}  // namespace pcsketch
