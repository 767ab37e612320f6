#pragma once
// Shared helpers of the bench/ programs: wall-clock timing, peak memory, process isolation, tables, test clouds.

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::bench {

/// Wall-clock stopwatch, started on construction.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  /// Seconds since construction or the last restart().
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  /// Returns seconds() and starts again.
  double restart() {
    const double s = seconds();
    start_ = std::chrono::steady_clock::now();
    return s;
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

/// User + system CPU seconds of this process so far, all threads (getrusage). On a machine shared with other work,
/// CPU time divided by the core count estimates the wall time on an idle machine better than the wall time does.
double cpu_seconds();

/// Peak resident set size of this process so far, bytes (getrusage; monotonic over the process's life, so measure
/// each configuration in its own process: see run_isolated).
std::size_t peak_rss_bytes();
/// Current resident set size, bytes (/proc/self/statm); 0 where unavailable.
std::size_t current_rss_bytes();
/// The 1-, 5- and 15-minute load averages as "0.42 0.51 0.60" (/proc/loadavg), to print next to timings on a
/// shared machine; "unknown" where unavailable.
std::string load_average();

/// Runs `job` in a forked child process and returns what it returned, so that its peak RSS (and any crash) stays
/// its own. Call before the parent starts any thread pool (fork copies only the calling thread).
/// @throws std::runtime_error if the child fails or dies.
std::string run_isolated(const std::function<std::string()>& job);

/// A bench program's main: runs `run(argc, argv)` and turns an exception into one line on stderr and status 1.
int bench_main(const char* name, int argc, char** argv, int (*run)(int, char**));

/// A plain-text table with right-aligned columns (the first column left-aligned).
class Table {
 public:
  explicit Table(std::vector<std::string> header) : header_(std::move(header)) {}
  void add_row(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  /// The table as text, a rule under the header, one line per row.
  std::string to_string() const;

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

/// A table whose first column is `first` and which has, for each configuration in `names`, a "NAME s" and a
/// "µs/point" column.
Table per_point_table(const std::string& first, const std::vector<std::string>& names);

/// `value` with `digits` digits after the point.
std::string fixed(double value, int digits);

/// Adds to a per_point_table the row `label`: for each result, `seconds_of(result)` with `digits` digits and the
/// time per point (`Result::points`) in µs.
template <class Result, class SecondsOf>
void add_per_point_row(Table& table, const std::string& label, const std::vector<Result>& results,
                       SecondsOf seconds_of, int digits = 3) {
  std::vector<std::string> cells{label};
  for (const Result& r : results) {
    const double s = seconds_of(r);
    cells.push_back(fixed(s, digits));
    cells.push_back(fixed(1e6 * s / static_cast<double>(r.points), 3));
  }
  table.add_row(std::move(cells));
}
/// A count with thousands separators: 1,000,000.
std::string grouped(std::size_t count);
/// Bytes as MiB with one decimal.
std::string mebibytes(std::size_t bytes);

/// Path of a file in the shared data folder (the PCSKETCH_SHARED_DATA macro bench/CMakeLists.txt defines).
std::string shared_data(const std::string& name);

/// Shuffles every per-point array of `cloud` together, deterministically for `seed` (scans arrive in random order;
/// a sampler's output is spatially coherent and would flatter cache-sensitive stages). source_index follows.
void shuffle(PointCloud& cloud, std::uint64_t seed);

/// `n` area-uniform samples of the mesh at `path` (io::read_mesh + io::sample_mesh), without normals, shuffled,
/// source_index cleared (file order = sample order).
PointCloud sampled_cloud(const std::string& path, std::size_t n, std::uint64_t seed);

}  // namespace pcsketch::bench
