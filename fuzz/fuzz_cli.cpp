// libFuzzer target: the whole command line in-process (cli/run_cli.h: the function main() calls), with flags and
// their values drawn from the input, on tiny built-in clouds, whole small draws included. Any input must end in exit
// status 0, 1 or 2 (or 130 for the hidden --cancel-at); status 3 (an unexpected exception), a crash, a hang or a
// sanitizer report is a finding.
//
// Every run happens in a fresh directory inside a private temporary one (the working directory while the CLI runs),
// and no token made from the input holds a '/': whatever path a token names (as an -o, --json, --stages or --lines
// value) lies inside the private directory. A reproducer is written at the -artifact_prefix, which must therefore be
// an absolute path (scripts/fuzz-smoke.sh gives one). One run
// stays fast: the clouds have at most 96 points, and draw always gets one --size of at most 64x64 px from the harness
// (a second --size from the input is a usage error: CLI11 refuses a single-value flag given twice).

#include <fcntl.h>
#include <fuzzer/FuzzedDataProvider.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "run_cli.h"

namespace {

namespace fs = std::filesystem;

// Flags of draw, features and info that take a value (a flag the subcommand lacks is a usage error, also worth
// running), then switches.
constexpr std::array kValueFlags = {
    "-o", "--json", "--stages", "--lines", "--columns", "--classes", "--drop-classes", "--crop", "--voxel",
    "--max-points", "--max-memory", "--view", "--up", "--azimuth", "--elevation", "--eye", "--target", "--fov",
    "--margin", "--neighbours", "--file-normals", "--outlier-density", "--outlier-min-cluster", "--denoise-trigger",
    "--denoise-iterations", "--denoise-passes", "--denoise-cutoff", "--orientation", "--outward", "--alpha",
    "--detection", "--extreme", "--extreme-percentile", "--saliency-floor", "--median-factor", "--suppression-cone",
    "--radius", "--radius-abs", "--corridor", "--max-turn", "--join-distance", "--beta", "--min-length",
    "--min-length-abs", "--smooth", "--smooth-weight", "--z-max", "--contour-radius", "--contour-connection",
    "--contour-persistence", "--self-offset", "--hidden-lines", "--thickness", "--rho-min", "--rho-max", "--cofi",
    "--shadow", "--light", "--light-elevation", "--light-azimuth", "--shadow-d", "--shadow-k", "--hatch-spacing",
    "--pen-width", "--pen-width-px", "--page-width-mm", "--scale", "--units", "--sheet", "--k", "--threads"};
constexpr std::array kSwitches = {
    "--timings", "--perspective", "--recompute-normals", "--keep-outliers", "--no-denoise", "--no-suppression",
    "--no-interior-contours", "--no-uneven-spacing", "--no-local-offset", "--no-visibility-lift", "--no-brush",
    "--light-fixed", "--no-shade-blocks", "--shadow-over-background", "--no-contours", "--no-ridges", "--no-valleys",
    "--no-hatching", "--plotter", "--scale-bar", "--north-arrow", "--ascii", "--no-recentre", "--help", "--version"};
// Values worth trying: edges of the ranges, non-finite numbers, vectors, enum names, output names.
constexpr std::array kValues = {
    "nan", "inf", "-inf", "-1", "0", "1", "2", "3", "0.5", "0.999", "1e308", "1e-30", "1e309", "16", "256", "257",
    "1,0,0", "0,0,0", "nan,1,1", "1e308,1e308,1e308", "0,0,1", "-1,-1,-1,1,1,1", "0,0,0,0,0,0", "x,y,z",
    "x,y,z,nx,ny,nz", "skip,x,y,z", "x,y,z,r,g,b", "x,x,y", "2,6", "none", "paper", "both", "attached", "reflect",
    "parallel", "auto", "trust", "orient", "volume", "farthest", "dashed", "constant", "depth", "angle", "combined",
    "outermost", "direction-guided", "minmax", "o.svg", "o.png", "o.pdf", "o.json", "o.gif", "O.SVG", "st", ".",
    "l.json", "o.ply"};

struct Workspace {
  fs::path run;                     ///< the directory of one run, emptied before each
  std::vector<std::string> inputs;  ///< absolute paths of the built-in clouds
};

/// The private directory and its clouds: a 60-point sphere (XYZ), a 96-point cube with normals (ascii PLY) and
/// 2 points (too few to analyse).
Workspace make_workspace() {
  static char pattern[] = "/tmp/pcsketch_fuzz_cli_XXXXXX";
  if (!::mkdtemp(pattern)) std::abort();
  std::atexit([] {
    std::error_code ec;
    fs::remove_all(pattern, ec);
  });
  const fs::path root = pattern;
  Workspace w{root / "run",
              {(root / "sphere.xyz").string(), (root / "cube.ply").string(), (root / "two.xyz").string()}};
  std::ofstream sphere(w.inputs[0]);
  for (int i = 0; i < 60; ++i) {
    const double z = 1 - 2 * (i + 0.5) / 60, r = std::sqrt(1 - z * z), a = i * 2.399963229728653;
    sphere << r * std::cos(a) << " " << r * std::sin(a) << " " << z << "\n";
  }
  std::ofstream cube(w.inputs[1]);
  cube << "ply\nformat ascii 1.0\nelement vertex 96\nproperty float x\nproperty float y\nproperty float z\n"
          "property float nx\nproperty float ny\nproperty float nz\nend_header\n";
  for (int axis = 0; axis < 3; ++axis)
    for (const int side : {-1, 1})
      for (int i = 0; i < 16; ++i) {
        std::array<double, 3> p{}, n{};
        p[axis] = side;
        n[axis] = side;
        p[(axis + 1) % 3] = (i % 4 - 1.5) / 2;
        p[(axis + 2) % 3] = (i / 4 - 1.5) / 2;
        cube << p[0] << " " << p[1] << " " << p[2] << " " << n[0] << " " << n[1] << " " << n[2] << "\n";
      }
  std::ofstream(w.inputs[2]) << "0 0 0\n1 1 1\n";
  return w;
}

/// A value for a flag: one of kValues, a number, or raw bytes without '/'.
std::string value(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange(0, 3)) {
    case 0:
    case 1:
      return kValues[in.ConsumeIntegralInRange<std::size_t>(0, kValues.size() - 1)];
    case 2:
      return std::to_string(in.ConsumeFloatingPoint<double>());
    default: {
      std::string raw = in.ConsumeRandomLengthString(24);
      for (char& c : raw)
        if (c == '/') c = '_';
      return raw;
    }
  }
}

/// argv: pcsketch -q SUBCOMMAND INPUT [--size WxH] [-o OUTPUT], then up to 12 flags, switches or raw tokens.
std::vector<std::string> command_line(FuzzedDataProvider& in, const Workspace& w) {
  static constexpr std::array kCommands = {"draw", "draw", "features", "info"};
  const std::string command = kCommands[in.ConsumeIntegralInRange<std::size_t>(0, kCommands.size() - 1)];
  std::vector<std::string> args = {"pcsketch", "-q", command,
                                   w.inputs[in.ConsumeIntegralInRange<std::size_t>(0, w.inputs.size() - 1)]};
  // The outputs a run needs (without one, draw and features stop at the usage check).
  static constexpr std::array kDrawOutputs = {"o.svg", "o.png", "o.pdf", "o.json"};
  if (command == "draw")
    args.insert(args.end(), {"--size",
                             std::to_string(in.ConsumeIntegralInRange(1, 64)) + "x" +
                                 std::to_string(in.ConsumeIntegralInRange(1, 64)),
                             "-o", kDrawOutputs[in.ConsumeIntegralInRange<std::size_t>(0, kDrawOutputs.size() - 1)]});
  if (command == "features") args.insert(args.end(), {"-o", "f.ply"});
  for (int n = in.ConsumeIntegralInRange(0, 12); n > 0 && in.remaining_bytes() > 0; --n) {
    switch (in.ConsumeIntegralInRange(0, 5)) {
      case 0:
        args.push_back(kSwitches[in.ConsumeIntegralInRange<std::size_t>(0, kSwitches.size() - 1)]);
        break;
      case 1:
        args.push_back(value(in));  // a stray token: a positional, a flag spelled by the input, "--x=y"
        break;
      default:
        args.push_back(kValueFlags[in.ConsumeIntegralInRange<std::size_t>(0, kValueFlags.size() - 1)]);
        args.push_back(value(in));
    }
  }
  return args;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // The CLI's output is noise here: stdout (results, --help) goes to /dev/null, std::cerr (its one-line errors)
  // nowhere. libFuzzer and the sanitizers write to stderr's descriptor, which stays.
  if (!std::freopen("/dev/null", "w", stdout)) std::abort();
  std::cerr.rdbuf(nullptr);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const Workspace workspace = make_workspace();
  FuzzedDataProvider in(data, size);
  const std::vector<std::string> args = command_line(in, workspace);
  std::error_code ec;
  fs::remove_all(workspace.run, ec);
  fs::create_directory(workspace.run);
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  // In the run directory only while the CLI runs: libFuzzer reads its corpus by relative paths between runs.
  static const int home = ::open(".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (home < 0 || ::chdir(workspace.run.c_str()) != 0) std::abort();
  const int status = pcsketch::cli::run_cli(static_cast<int>(argv.size()), argv.data());
  if (::fchdir(home) != 0) std::abort();
  // 3: an exception that is no pcsketch::Error. 130 is a stop asked for (the hidden --cancel-at, spelled by the input).
  if (status < 0 || (status > 2 && status != 130)) __builtin_trap();
  return 0;
}
