// Large clouds (issue 14): time and peak RSS of reading and drawing big binary PLYs at 1024 px, thinned to the
// output's resolution while streamed, and the contour precision/recall of that drawing against the drawing of
// every point (both at 1024 px, default options, visible contours sampled every 0.5 px, matched within 2 px).
//
//   bench_stream [--full] [--cell-pixels C] FILE ...   (PLY made by `pcsketch sample MESH -n N -o FILE.ply`; any
//   streamed format works: ascii PLY, LAS, ascii or binary PCD, XYZ)
//
// --cell-pixels: the thinning's cell in pixels instead of the default 0.5 (to see what a coarser one costs).
// --full also draws each file from all its points (the reference for precision/recall; needs ~330 bytes a point).
// Each configuration runs in its own process, so that its peak RSS is its own. No assertions: it prints a table.

#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "pcsketch/io/read_cloud.h"
#include "pcsketch/pipeline.h"
#include "support/bench_support.h"
#include "support/mesh_ground_truth.h"

namespace pcsketch::bench {
namespace {

using Clock = std::chrono::steady_clock;

// One drawing: seconds (read, total), points kept, peak RSS and the visible contour samples.
std::string measure(const std::string& path, bool full, double cell_pixels) {
  const auto start = Clock::now();
  io::ReadOptions read;
  if (!full) read.decimate.resolution = io::OutputResolution{.cell_pixels = cell_pixels};  // draw's at 1024 px
  io::ReadResult r = io::read_point_cloud(path, read);
  const double read_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const std::size_t kept = r.cloud.size();
  DrawOptions options;
  const DrawResult drawn = draw(std::move(r.cloud), options);
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  nlohmann::json samples = nlohmann::json::array();
  for (const Vec2f& s : test::sample_visible_strokes(drawn.drawing, LineKind::Contour))
    samples.push_back({s.x(), s.y()});
  return nlohmann::json{{"read", read_seconds},
                        {"seconds", seconds},
                        {"kept", kept},
                        {"in_file", r.points_in_file},
                        {"cell", r.decimation ? r.decimation->cell : 0.0},
                        {"rss", peak_rss_bytes()},
                        {"contours", std::move(samples)}}
      .dump();
}

std::vector<Vec2f> points_of(const nlohmann::json& samples) {
  std::vector<Vec2f> out;
  for (const auto& s : samples) out.emplace_back(s[0].get<float>(), s[1].get<float>());
  return out;
}

int run(int argc, char** argv) {
  bool full = false;
  double cell_pixels = io::OutputResolution{}.cell_pixels;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--full") {
      full = true;
    } else if (arg == "--cell-pixels" && i + 1 < argc) {
      cell_pixels = std::stod(argv[++i]);
    } else {
      files.push_back(arg);
    }
  }
  if (files.empty()) throw std::runtime_error("usage: bench_stream [--full] FILE.ply ...");
  std::cout << "load average before: " << load_average() << "; cell " << cell_pixels << " px\n";
  Table table({"file", "points", "kept", "cell", "read s", "total s", "peak RSS", "full s", "full RSS",
               "contour P", "contour R"});
  for (const std::string& file : files) {
    const nlohmann::json thin = nlohmann::json::parse(run_isolated([&] { return measure(file, false, cell_pixels); }));
    std::vector<std::string> row{file,
                                 grouped(thin["in_file"].get<std::size_t>()),
                                 grouped(thin["kept"].get<std::size_t>()),
                                 fixed(thin["cell"].get<double>() * 1e6, 1) + "e-6",
                                 fixed(thin["read"].get<double>(), 2),
                                 fixed(thin["seconds"].get<double>(), 2),
                                 mebibytes(thin["rss"].get<std::size_t>())};
    if (full) {
      const nlohmann::json all = nlohmann::json::parse(run_isolated([&] { return measure(file, true, cell_pixels); }));
      const test::LineMatch m =
          test::match_lines(points_of(thin["contours"]), points_of(all["contours"]), /*tolerance_px=*/2.f);
      row.insert(row.end(), {fixed(all["seconds"].get<double>(), 2), mebibytes(all["rss"].get<std::size_t>()),
                             fixed(m.precision, 4), fixed(m.recall, 4)});
    } else {
      row.insert(row.end(), {"-", "-", "-", "-"});
    }
    table.add_row(row);
    std::cout << table.to_string() << std::flush;
  }
  std::cout << "load average after: " << load_average() << "\n";
  return 0;
}

}  // namespace
}  // namespace pcsketch::bench

int main(int argc, char** argv) { return pcsketch::bench::bench_main("bench_stream", argc, argv, pcsketch::bench::run); }
