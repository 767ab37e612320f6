// The C++ example of docs/output.md ("Library"), compiled and run here so that it keeps working. Keep the two in step.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "pcsketch/pcsketch.h"

namespace {

// --- docs/output.md example, body of main() with the input path and output folder as parameters ---
void example(const std::string& input, const std::filesystem::path& out) {
  pcsketch::io::ReadResult read = pcsketch::io::read_point_cloud(input);

  pcsketch::DrawOptions options;
  options.features.detection.ridge_threshold_alpha = 0.15f;  // paper's alpha: smaller gives more ridge/valley lines
  options.thickness.rho_max = 4.f;                            // paper's rho_max: thickest stroke, pixels
  options.camera.width = options.camera.height = 512;

  // View-independent work once (normals, curvature, ridge/valley lines, ray-casting scene) ...
  const pcsketch::Prepared prepared = pcsketch::prepare(std::move(read.cloud), options);
  // ... then any number of views.
  for (const double azimuth : {0.0, -35.0}) {
    pcsketch::view::CameraOptions camera = options.camera;
    camera.azimuth_deg = azimuth;
    camera.elevation_deg = 15.0;
    const pcsketch::DrawResult result = pcsketch::draw_view(prepared, camera, options);
    const std::string stem = "bunny_" + std::to_string(static_cast<int>(azimuth));
    pcsketch::render::write_drawing(result.drawing, out / (stem + ".svg"), options.render);
    pcsketch::render::write_drawing(result.drawing, out / (stem + ".json"));
  }
}
// --- end of the example ---

TEST(LibraryExample, DrawsTwoViewsOfTheBundledBunny) {
  const std::filesystem::path out = std::filesystem::path(::testing::TempDir()) / "pcsketch_library_example";
  std::filesystem::create_directories(out);
  example(PCSKETCH_DATA "/bunny.ply", out);
  for (const char* name : {"bunny_0.svg", "bunny_0.json", "bunny_-35.svg", "bunny_-35.json"}) {
    ASSERT_TRUE(std::filesystem::exists(out / name)) << name;
    EXPECT_GT(std::filesystem::file_size(out / name), 1000u) << name;
  }
  std::filesystem::remove_all(out);
}

}  // namespace
