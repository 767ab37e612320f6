// Peak memory of large images on a tiny cloud (issue 10): the image-sized buffers (PNG raster, attached-shadow
// grid) dominate, and validate() estimates them before anything is allocated (kMaxImageBytes refuses the rest).
//
//   bench_image_memory [SIZE ...]   image sides in pixels (default 1024 8000 16000)
//
// Each size draws a 300-point sphere to a PNG and an SVG in its own process, so that each peak RSS is its own.

#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "pcsketch/pipeline.h"
#include "pcsketch/render/write.h"
#include "pcsketch/validate.h"
#include "support/bench_support.h"

namespace pcsketch::bench {
namespace {

PointCloud sphere(int n) {
  PointCloud cloud;
  for (int i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z), a = i * 2.399963229728653;
    cloud.positions.emplace_back(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)),
                                 static_cast<float>(z));
  }
  return cloud;
}

/// "estimated-bytes peak-rss-bytes seconds" of one drawing of side `size`.
std::string measure(int size) {
  DrawOptions options;
  options.camera.width = options.camera.height = size;
  Stopwatch clock;
  const DrawResult result = draw(sphere(300), options);
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  const std::string stem = "pcsketch_bench_image_" + std::to_string(size);
  render::write_drawings(result.drawing, {dir / (stem + ".png"), dir / (stem + ".svg")});
  const double seconds = clock.restart();
  std::filesystem::remove(dir / (stem + ".png"));
  std::filesystem::remove(dir / (stem + ".svg"));
  return std::to_string(image_bytes(options, options.camera)) + " " + std::to_string(peak_rss_bytes()) + " " +
         std::to_string(seconds);
}

int run(int argc, char** argv) {
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i) sizes.push_back(std::stoi(argv[i]));
  if (sizes.empty()) sizes = {1024, 8000, 16000};
  Table table({"image", "estimated MB", "peak RSS MB", "seconds"});
  for (const int size : sizes) {
    std::istringstream in(run_isolated([size] { return measure(size); }));
    double estimated = 0, peak = 0, seconds = 0;
    in >> estimated >> peak >> seconds;
    table.add_row({std::to_string(size) + "x" + std::to_string(size), fixed(estimated / 1e6, 0), fixed(peak / 1e6, 0),
                   fixed(seconds, 2)});
  }
  std::cout << table.to_string() << "load average: " << load_average() << "\n";
  return 0;
}

}  // namespace
}  // namespace pcsketch::bench

int main(int argc, char** argv) {
  return pcsketch::bench::bench_main("bench_image_memory", argc, argv, pcsketch::bench::run);
}
