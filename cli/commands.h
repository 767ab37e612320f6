#pragma once
// Each subcommand lives in its own cmd_<name>.cpp and registers itself on the app here.

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "pcsketch/core/report.h"

namespace pcsketch::cli {

/// Exit statuses of the tool.
enum ExitCode : int {
  kOk = 0,
  kUsage = 1,      ///< bad command line (CLI11 prints the reason)
  kBadInput = 2,   ///< malformed, truncated or hostile input, or an impossible request: one line on stderr
  kInternal = 3,   ///< a bug: an unexpected exception
  kCancelled = 130,  ///< stopped by SIGINT or SIGTERM (as a shell reports an interrupted command): no output written
};

/// Options every subcommand shares.
struct GlobalOptions {
  bool quiet = false;   ///< no progress, no warnings
  int threads = 0;      ///< 0 = all cores
  std::string cancel_at;  ///< hidden, for tests: act as if interrupted when this stage reports its end
};

/// The command's progress callback: it stops the command (pcsketch::Cancelled) once SIGINT or SIGTERM came (see
/// install_interrupt_handlers) and draws a progress line on stderr when stderr is a terminal, not quiet, and a stage
/// has run for over a second.
ProgressFn make_progress(const GlobalOptions& global);
/// Prints each warning as "pcsketch: warning: …" unless quiet.
void print_warnings(const GlobalOptions& global, const Warnings& warnings);

void add_info_command(CLI::App& app, const GlobalOptions& global);
void add_sample_command(CLI::App& app, const GlobalOptions& global);
void add_draw_command(CLI::App& app, const GlobalOptions& global);
void add_features_command(CLI::App&, const GlobalOptions&);
void add_parameters_command(CLI::App& app);

}  // namespace pcsketch::cli
