#pragma once
// The whole command line in-process: main() and the CLI fuzz target (fuzz/fuzz_cli.cpp) call the same function.

namespace pcsketch::cli {

/// Parses `argv` (argv[0] the program name) and runs the subcommand. Every failure is one line on stderr.
/// @return the exit status (ExitCode in commands.h): 0 success, 1 bad command line, 2 bad input, 3 internal error,
///         130 stopped by SIGINT or SIGTERM.
int run_cli(int argc, const char* const* argv);

/// SIGINT and SIGTERM stop the running command at its next progress report: no output file is written or left
/// half-written, and run_cli returns 130. A second signal ends the process at once. main() installs them; the fuzz
/// target does not (libFuzzer has its own).
void install_interrupt_handlers();

}  // namespace pcsketch::cli
