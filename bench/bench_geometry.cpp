// Times the view-independent geometry (issue 2's benchmark): read, spatial reorder, kd-tree + k-NN neighbourhoods,
// PCA normals, orientation and curvature, on the bunny's vertices and on clouds sampled from bunny.off, with peak RSS.
//
//   bench_geometry [N ...]   sample sizes (default 1000000 5000000); "0" skips the sampled clouds
//
// Each configuration runs in its own process so that its peak RSS is its own. Timings are wall-clock on a shared
// machine: the load average is printed with them, and the CPU time of the whole analysis (reorder to curvature,
// all threads), which divided by the core count estimates the wall time on an idle machine.

#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>

#include "pcsketch/differential/surface.h"
#include "pcsketch/io/ply.h"
#include "pcsketch/io/read_cloud.h"
#include "support/bench_support.h"

namespace pcsketch::bench {
namespace {

struct Measured {
  std::size_t points = 0, fit_neighbours = 0;
  double read = 0;
  double analysis_cpu = 0;  ///< CPU seconds of analyse_surface, all threads
  differential::SurfaceTimings t;
  std::size_t peak = 0;
};

/// Reads `path` and analyses it with default options; in the calling (child) process.
Measured measure(const std::string& path) {
  Measured m;
  Stopwatch clock;
  PointCloud cloud = io::read_point_cloud(path).cloud;
  m.read = clock.seconds();
  cloud.normals.clear();  // time the normal estimation too (bunny.off has none anyway)
  const double cpu_before = cpu_seconds();
  const differential::Surface surface = differential::analyse_surface(cloud);
  m.analysis_cpu = cpu_seconds() - cpu_before;
  m.points = cloud.size();
  m.fit_neighbours = surface.curvature.fit_neighbours;
  m.t = surface.timings;
  m.peak = peak_rss_bytes();
  return m;
}

std::string serialise(const Measured& m) {
  std::ostringstream out;
  out.precision(17);
  out << m.points << ' ' << m.fit_neighbours << ' ' << m.read << ' ' << m.t.reorder << ' '
      << m.t.neighbourhoods << ' ' << m.t.normals << ' ' << m.t.orientation << ' ' << m.t.curvature << ' ' << m.analysis_cpu << ' '
      << m.peak;
  return out.str();
}

Measured parse(const std::string& text) {
  std::istringstream in(text);
  Measured m;
  in >> m.points >> m.fit_neighbours >> m.read >> m.t.reorder >> m.t.neighbourhoods >> m.t.normals >>
      m.t.orientation >> m.t.curvature >> m.analysis_cpu >> m.peak;
  return m;
}

/// Samples bunny.off, writes the shuffled samples as binary PLY, and measures reading that file back.
Measured measure_sampled(std::size_t n) {
  const std::string path = "/tmp/pcsketch_bench_geometry_" + std::to_string(getpid()) + ".ply";
  io::write_ply(path, sampled_cloud(shared_data("bunny.off"), n, 2024));
  Measured m;
  try {
    m = measure(path);
  } catch (...) {
    std::remove(path.c_str());
    throw;
  }
  std::remove(path.c_str());
  return m;
}

int run(int argc, char** argv) {
  std::vector<std::size_t> sizes{1000000, 5000000};
  if (argc > 1) {
    sizes.clear();
    for (int a = 1; a < argc; ++a)
      if (const std::size_t n = std::stoul(argv[a]); n > 0) sizes.push_back(n);
  }
  std::cout << "load average before: " << load_average() << "\n";
  std::vector<std::string> names{"bunny.off vertices"};
  std::vector<Measured> results{parse(run_isolated([] { return serialise(measure(shared_data("bunny.off"))); }))};
  for (std::size_t n : sizes) {
    names.push_back(grouped(n) + " samples");
    results.push_back(parse(run_isolated([n] { return serialise(measure_sampled(n)); })));
  }

  Table table = per_point_table("stage", names);
  const auto row = [&](const std::string& stage, auto seconds_of) {
    add_per_point_row(table, stage, results, seconds_of);
  };
  const auto geometry = [](const Measured& m) {
    return m.t.neighbourhoods + m.t.normals + m.t.orientation + m.t.curvature;
  };
  row("read", [](const Measured& m) { return m.read; });
  row("spatial reorder", [](const Measured& m) { return m.t.reorder; });
  row("k-NN neighbourhoods (tree built beside)", [](const Measured& m) { return m.t.neighbourhoods; });
  row("normals (PCA)", [](const Measured& m) { return m.t.normals; });
  row("orientation", [](const Measured& m) { return m.t.orientation; });
  row("curvature", [](const Measured& m) { return m.t.curvature; });
  row("geometry (kd+nbhd+norm+orient+curv)", geometry);
  row("total (with read, reorder)", [&](const Measured& m) { return m.read + m.t.reorder + geometry(m); });
  row("CPU time of the analysis (all threads)", [](const Measured& m) { return m.analysis_cpu; });
  std::vector<std::string> points{"points"}, fit{"neighbours per curvature fit"}, peak{"peak RSS"};
  for (const Measured& m : results) {
    points.insert(points.end(), {grouped(m.points), ""});
    fit.insert(fit.end(), {std::to_string(m.fit_neighbours), ""});
    peak.insert(peak.end(), {mebibytes(m.peak), ""});
  }
  table.add_row(points);
  table.add_row(fit);
  table.add_row(peak);
  std::cout << table.to_string() << "load average after: " << load_average() << "\n";
  return 0;
}

}  // namespace
}  // namespace pcsketch::bench

int main(int argc, char** argv) {
  return pcsketch::bench::bench_main("bench_geometry", argc, argv, pcsketch::bench::run);
}
