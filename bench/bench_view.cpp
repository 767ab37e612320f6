// Times one view and a second view (issue 4's benchmark, the paper's Table 2 rows): contour points extraction,
// contour connection, visibility of every line (contours, ridges, valleys), on the bunny's vertices and on clouds
// sampled from bunny.off. The view-independent work (analyse_surface, ridge/valley lines, the SurfaceScene) runs
// once and is reported separately: the second view reuses it.
//
//   bench_view [N ...]   sample sizes (default 1000000); "0" skips the sampled clouds
//
// Each configuration runs in its own process (peak RSS of its own). Wall-clock timings on a shared machine: the
// load average is printed with them.

#include <ctime>
#include <iostream>
#include <sstream>
#include <string>

#include "pcsketch/differential/surface.h"
#include "pcsketch/features/ridge_valley_lines.h"
#include "pcsketch/io/read_cloud.h"
#include "pcsketch/view/view.h"
#include "support/bench_support.h"

namespace pcsketch::bench {
namespace {

constexpr int kViews = 2;

/// CPU seconds of this process (all threads): on a loaded machine wall time overstates the cost, CPU time over the
/// number of cores estimates the wall time on an idle one.
double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Measured {
  std::size_t points = 0, ridge_lines = 0;
  double analyse = 0, ridges = 0, scene = 0;
  view::ViewTimings t[kViews];
  double cpu[kViews] = {};
  std::size_t boundary[kViews] = {}, contours[kViews] = {}, vertices[kViews] = {};
  std::size_t peak = 0;
};

/// Analyses `cloud` once, then computes two views (the paper's +z view and one from the side and above).
Measured measure(PointCloud cloud) {
  Measured m;
  m.points = cloud.size();
  Stopwatch clock;
  const differential::Surface surface = differential::analyse_surface(cloud);
  m.analyse = clock.restart();
  const features::RidgeValleyLines lines = features::extract_ridge_valley_lines(cloud, surface);
  m.ridges = clock.restart();
  m.ridge_lines = lines.lines.size();
  const view::SurfaceScene scene = view::build_surface_scene(cloud, surface);
  m.scene = clock.restart();
  const view::CameraOptions cameras[kViews] = {{}, {.azimuth_deg = 60.0, .elevation_deg = 20.0}};
  for (int v = 0; v < kViews; ++v) {
    const view::Camera camera = view::make_camera(cloud.positions, cloud.origin, cameras[v]);
    const double cpu_start = cpu_seconds();
    const view::ViewResult result = view::compute_view(cloud, surface, scene, lines.lines, camera);
    m.cpu[v] = cpu_seconds() - cpu_start;
    m.t[v] = result.timings;
    m.boundary[v] = result.contour_points.boundary.size();
    m.contours[v] = result.contour_count;
    for (const view::ViewLine& line : result.lines) m.vertices[v] += line.line.size();
  }
  m.peak = peak_rss_bytes();
  return m;
}

std::string serialise(const Measured& m) {
  std::ostringstream out;
  out.precision(17);
  out << m.points << ' ' << m.ridge_lines << ' ' << m.analyse << ' ' << m.ridges << ' ' << m.scene << ' ' << m.peak;
  for (int v = 0; v < kViews; ++v)
    out << ' ' << m.t[v].contour_points << ' ' << m.t[v].contour_connection << ' ' << m.t[v].visibility << ' '
        << m.boundary[v] << ' ' << m.contours[v] << ' ' << m.vertices[v] << ' ' << m.cpu[v];
  return out.str();
}

Measured parse(const std::string& text) {
  std::istringstream in(text);
  Measured m;
  in >> m.points >> m.ridge_lines >> m.analyse >> m.ridges >> m.scene >> m.peak;
  for (int v = 0; v < kViews; ++v)
    in >> m.t[v].contour_points >> m.t[v].contour_connection >> m.t[v].visibility >> m.boundary[v] >> m.contours[v] >>
        m.vertices[v] >> m.cpu[v];
  return m;
}

int run(int argc, char** argv) {
  std::vector<std::size_t> sizes{1000000};
  if (argc > 1) {
    sizes.clear();
    for (int a = 1; a < argc; ++a)
      if (const std::size_t n = std::stoul(argv[a]); n > 0) sizes.push_back(n);
  }
  std::cout << "load average before: " << load_average() << "\n";
  std::vector<std::string> names{"bunny.off vertices"};
  std::vector<Measured> results{parse(run_isolated([] {
    PointCloud cloud = io::read_point_cloud(shared_data("bunny.off")).cloud;
    return serialise(measure(std::move(cloud)));
  }))};
  for (const std::size_t n : sizes) {
    names.push_back(grouped(n) + " samples");
    results.push_back(
        parse(run_isolated([n] { return serialise(measure(sampled_cloud(shared_data("bunny.off"), n, 2024))); })));
  }

  Table table = per_point_table("step", names);
  const auto row = [&](const std::string& step, auto seconds_of) {
    add_per_point_row(table, step, results, seconds_of);
  };
  const auto count_row = [&](const std::string& what, auto count_of) {
    std::vector<std::string> cells{what};
    for (const Measured& m : results) cells.insert(cells.end(), {grouped(count_of(m)), ""});
    table.add_row(cells);
  };
  row("once: analyse_surface", [](const Measured& m) { return m.analyse; });
  row("once: ridge/valley lines", [](const Measured& m) { return m.ridges; });
  row("once: surface scene (Embree)", [](const Measured& m) { return m.scene; });
  for (int v = 0; v < kViews; ++v) {
    const std::string label = v == 0 ? "view 1: " : "view 2: ";
    row(label + "contour points extraction", [v](const Measured& m) { return m.t[v].contour_points; });
    row(label + "contour connection", [v](const Measured& m) { return m.t[v].contour_connection; });
    row(label + "visibility", [v](const Measured& m) { return m.t[v].visibility; });
    row(label + "total", [v](const Measured& m) {
      return m.t[v].contour_points + m.t[v].contour_connection + m.t[v].visibility;
    });
    row(label + "CPU time, all threads", [v](const Measured& m) { return m.cpu[v]; });
  }
  count_row("points", [](const Measured& m) { return m.points; });
  count_row("ridge/valley lines", [](const Measured& m) { return m.ridge_lines; });
  for (int v = 0; v < kViews; ++v) {
    const std::string label = v == 0 ? "view 1: " : "view 2: ";
    count_row(label + "boundary points", [v](const Measured& m) { return m.boundary[v]; });
    count_row(label + "contour lines", [v](const Measured& m) { return m.contours[v]; });
    count_row(label + "line vertices ray-cast", [v](const Measured& m) { return m.vertices[v]; });
  }
  std::vector<std::string> peak{"peak RSS"};
  for (const Measured& m : results) peak.insert(peak.end(), {mebibytes(m.peak), ""});
  table.add_row(peak);
  std::cout << table.to_string() << "load average after: " << load_average() << "\n";
  return 0;
}

}  // namespace
}  // namespace pcsketch::bench

int main(int argc, char** argv) {
  return pcsketch::bench::bench_main("bench_view", argc, argv, pcsketch::bench::run);
}
