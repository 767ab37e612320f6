#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "commands.h"
#include "pcsketch/core/error.h"

namespace pcsketch::cli {

ProgressFn make_progress(const GlobalOptions& global) {
  if (global.quiet || !isatty(STDERR_FILENO)) return {};
  struct State {
    std::string stage;
    std::chrono::steady_clock::time_point start;
    bool shown = false;
  };
  auto state = std::make_shared<State>();
  return [state](std::string_view stage, double fraction) {
    const auto now = std::chrono::steady_clock::now();
    if (stage != state->stage) {
      if (state->shown) std::fputs("\r\033[K", stderr);
      state->stage = stage;
      state->start = now;
      state->shown = false;
    }
    // Silent for stages that finish within a second: the line would only flicker.
    if (now - state->start < std::chrono::seconds(1)) return true;
    std::fprintf(stderr, "\r\033[K%s %3.0f%%", state->stage.c_str(), 100.0 * fraction);
    if (fraction >= 1.0) std::fputs("\r\033[K", stderr);
    state->shown = fraction < 1.0;
    return true;
  };
}

void print_warnings(const GlobalOptions& global, const Warnings& warnings) {
  if (global.quiet) return;
  for (const std::string& w : warnings) std::fprintf(stderr, "pcsketch: warning: %s\n", one_line(w).c_str());
}

}  // namespace pcsketch::cli
