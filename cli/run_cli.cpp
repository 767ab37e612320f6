// pcsketch: sketch drawings from raw point clouds. Thin layer: parse flags into option structs, call the library.

#include "run_cli.h"

#include <oneapi/tbb/global_control.h>

#include <iostream>
#include <optional>

#include "commands.h"
#include "pcsketch/core/error.h"
#include "pcsketch/validate.h"

namespace pcsketch::cli {

int run_cli(int argc, const char* const* argv) {
  CLI::App app{"pcsketch: pen-and-ink sketch drawings (contours, ridges, valleys, hatching) from raw point clouds"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "pcsketch 0.1.0");
  GlobalOptions global;
  app.add_flag("-q,--quiet", global.quiet, "No progress line and no warnings on stderr");
  app.add_option("--threads", global.threads, "Worker threads (0 = all cores); results do not depend on it")
      ->check(CLI::NonNegativeNumber);
  // Hidden (no group): lets the tests stop a command at the end of any stage without a signal.
  app.add_option("--cancel-at", global.cancel_at, "Act as if interrupted when this stage reports its end")->group("");

  add_info_command(app, global);
  add_sample_command(app, global);
  add_draw_command(app, global);
  add_features_command(app, global);
  add_parameters_command(app);

  std::optional<oneapi::tbb::global_control> thread_limit;
  app.parse_complete_callback([&] {
    if (global.threads > 0)
      thread_limit.emplace(oneapi::tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(global.threads));
  });
  // A bad command line is one line on stderr, as every other error.
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "pcsketch: error: " + one_line(e.what()) + " (see --help)\n";
  });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kOk : kUsage;
  } catch (const Cancelled&) {
    std::cerr << "pcsketch: cancelled\n";
    return kCancelled;
  } catch (const OptionError& e) {
    std::cerr << "pcsketch: error: " << e.what() << "\n";
    return kUsage;
  } catch (const Error& e) {
    std::cerr << "pcsketch: error: " << e.what() << "\n";
    return kBadInput;
  } catch (const std::bad_alloc&) {
    std::cerr << "pcsketch: error: out of memory\n";
    return kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "pcsketch: internal error: " << e.what() << "\n";
    return kInternal;
  }
  return kOk;
}

}  // namespace pcsketch::cli
