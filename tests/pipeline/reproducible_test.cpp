// Same input and options, same bytes: every output format of two separate drawings of one cloud is identical
// (the PDF's dates are fixed, render/pdf.h).

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include "pcsketch/pipeline.h"
#include "pcsketch/render/write.h"
#include "support/analytic_shapes.h"

namespace pcsketch {
namespace {

namespace fs = std::filesystem;

std::string bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(Reproducible, TwoDrawingsGiveTheSameBytesInEveryFormat) {
  // Its own directory per process: two suites run at once (release and a sanitizer build) must not share files.
  const fs::path dir = fs::path(::testing::TempDir()) / ("pcsketch_reproducible_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  DrawOptions options;
  options.camera.width = options.camera.height = 200;
  options.camera.azimuth_deg = 30.0;  // shadow hatching and ridges on the torus as well as contours
  options.camera.elevation_deg = 20.0;
  for (const char* run : {"a", "b"}) {
    // Over a second apart: cairo would otherwise date the PDF with the clock (to the second).
    if (std::string(run) == "b") std::this_thread::sleep_for(std::chrono::milliseconds(1100));
    const DrawResult result = draw(test::torus(1.f, 0.4f, {.n = 6000}), options);
    ASSERT_FALSE(result.drawing.strokes.empty());
    for (const char* ext : {".svg", ".png", ".pdf", ".json"})
      render::write_drawing(result.drawing, dir / (std::string(run) + ext), options.render);
  }
  for (const char* ext : {".svg", ".png", ".pdf", ".json"}) {
    const std::string a = bytes_of(dir / (std::string("a") + ext));
    EXPECT_FALSE(a.empty()) << ext;
    EXPECT_TRUE(a == bytes_of(dir / (std::string("b") + ext))) << ext << " differs between the two drawings";
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pcsketch
