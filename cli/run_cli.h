#pragma once
// The whole command line in-process: main() and the CLI fuzz target (fuzz/fuzz_cli.cpp) call the same function.

namespace pcsketch::cli {

/// Parses `argv` (argv[0] the program name) and runs the subcommand. Every failure is one line on stderr.
/// @return the exit status (ExitCode in commands.h): 0 success, 1 bad command line, 2 bad input, 3 internal error.
int run_cli(int argc, const char* const* argv);

}  // namespace pcsketch::cli
