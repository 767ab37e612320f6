// Times the ridge/valley step (paper Table 2 rows "ridge-valley points extraction" = detection and "ridge-valley
// points connection" = tracing + joining) once the curvatures are known, on the bunny's vertices, fandisk's vertices
// and a cloud sampled from bunny.off.
//
//   bench_features [N]   size of the sampled cloud (default 1000000); "0" skips it
//
// Each stage runs 3 times on the same analysed cloud and the fastest run is reported (the machine is shared; the
// load average is printed with the table).

#include <algorithm>
#include <iostream>
#include <string>

#include "pcsketch/differential/surface.h"
#include "pcsketch/features/ridge_valley_lines.h"
#include "pcsketch/io/read_cloud.h"
#include "support/bench_support.h"

namespace pcsketch::bench {
namespace {

struct Measured {
  std::size_t points = 0, ridge_points = 0, valley_points = 0, lines = 0;
  double analysis = 0;
  features::RidgeValleyTimings best{1e30, 1e30, 1e30};
};

Measured measure(PointCloud cloud) {
  Measured m;
  cloud.normals.clear();
  Stopwatch clock;
  const differential::Surface surface = differential::analyse_surface(cloud);
  m.analysis = clock.seconds();
  m.points = cloud.size();
  for (int run = 0; run < 3; ++run) {
    const features::RidgeValleyLines r = features::extract_ridge_valley_lines(cloud, surface);
    m.best.detection = std::min(m.best.detection, r.timings.detection);
    m.best.tracing = std::min(m.best.tracing, r.timings.tracing);
    m.best.joining = std::min(m.best.joining, r.timings.joining);
    m.ridge_points = r.detection.ridge_points;
    m.valley_points = r.detection.valley_points;
    m.lines = r.lines.size();
  }
  return m;
}

int run(int argc, char** argv) {
  const std::size_t n = argc > 1 ? std::stoul(argv[1]) : 1000000;
  std::cout << "load average before: " << load_average() << "\n";
  std::vector<std::string> names{"bunny.off vertices", "fandisk.off vertices"};
  std::vector<Measured> results{measure(io::read_point_cloud(shared_data("bunny.off")).cloud),
                                measure(io::read_point_cloud(shared_data("fandisk.off")).cloud)};
  if (n > 0) {
    names.push_back(grouped(n) + " bunny samples");
    results.push_back(measure(sampled_cloud(shared_data("bunny.off"), n, 2024)));
  }
  Table table = per_point_table("stage", names);
  const auto row = [&](const std::string& stage, auto seconds_of) {
    add_per_point_row(table, stage, results, seconds_of, 4);
  };
  row("ridge-valley points extraction (detection)", [](const Measured& m) { return m.best.detection; });
  row("tracing", [](const Measured& m) { return m.best.tracing; });
  row("joining", [](const Measured& m) { return m.best.joining; });
  row("ridge-valley points connection (trace+join)",
      [](const Measured& m) { return m.best.tracing + m.best.joining; });
  row("ridge/valley total", [](const Measured& m) { return m.best.detection + m.best.tracing + m.best.joining; });
  row("(surface analysis, for scale)", [](const Measured& m) { return m.analysis; });
  const auto count_row = [&](const std::string& label, auto count_of) {
    std::vector<std::string> cells{label};
    for (const Measured& m : results) cells.insert(cells.end(), {grouped(count_of(m)), ""});
    table.add_row(cells);
  };
  count_row("points", [](const Measured& m) { return m.points; });
  count_row("ridge points", [](const Measured& m) { return m.ridge_points; });
  count_row("valley points", [](const Measured& m) { return m.valley_points; });
  count_row("lines", [](const Measured& m) { return m.lines; });
  std::cout << table.to_string() << "load average after: " << load_average() << "\n";
  return 0;
}

}  // namespace
}  // namespace pcsketch::bench

int main(int argc, char** argv) {
  return pcsketch::bench::bench_main("bench_features", argc, argv, pcsketch::bench::run);
}
