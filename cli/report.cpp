#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <string>

#include "commands.h"
#include "pcsketch/core/error.h"

namespace pcsketch::cli {

namespace {

volatile std::sig_atomic_t interrupted = 0;

extern "C" void on_interrupt(int signal) {
  if (interrupted) {
    // A second signal: the user will not wait for the next progress report.
    std::signal(signal, SIG_DFL);
    std::raise(signal);
    return;
  }
  interrupted = 1;
}

}  // namespace

void install_interrupt_handlers() {
  for (const int signal : {SIGINT, SIGTERM}) {
    struct sigaction old {};
    // A signal ignored at start (a background job of a non-interactive shell) stays ignored.
    if (::sigaction(signal, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    struct sigaction action {};
    action.sa_handler = on_interrupt;
    sigemptyset(&action.sa_mask);
    ::sigaction(signal, &action, nullptr);
  }
}

ProgressFn make_progress(const GlobalOptions& global) {
  struct State {
    std::string stage;
    std::chrono::steady_clock::time_point start;
    bool shown = false;
  };
  auto state = std::make_shared<State>();
  const bool line = !global.quiet && isatty(STDERR_FILENO);
  return [state, line, cancel_at = global.cancel_at](std::string_view stage, double fraction) {
    if (interrupted || (stage == cancel_at && fraction >= 1.0)) {
      if (state->shown) std::fputs("\r\033[K", stderr);
      return false;
    }
    if (!line) return true;
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
