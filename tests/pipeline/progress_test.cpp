// Progress and cancellation (issue 14): every long stage reports under its own name, a stage's fraction never starts
// again, and a callback returning false stops the pipeline in any stage with pcsketch::Cancelled and no file.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "pcsketch/io/ply.h"
#include "pcsketch/io/read_cloud.h"
#include "pcsketch/pipeline.h"
#include "pcsketch/render/write.h"
#include "support/analytic_shapes.h"

namespace pcsketch {
namespace {

namespace fs = std::filesystem;

/// Every stage a draw of the open box reports, in pipeline order.
const std::vector<std::string> kStages = {
    "read", "reorder", "neighbourhoods", "outliers", "normals", "orientation", "curvature",
    "ridge/valley detection", "ridge/valley tracing", "ridge/valley joining", "boundaries", "scene",
    "contour points", "contour connection", "visibility", "shadows", "writing"};

using Reports = std::vector<std::pair<std::string, double>>;

/// A cube without its top face, as a raw scan (no normals): ridges, a border, shading. Written once as PLY.
class Progress : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("pcsketch_progress_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    const PointCloud cube = test::cube(1.f, {.n = 8000, .noise_sigma = 0.002f});
    PointCloud open;
    for (const Vec3f& p : cube.positions)
      if (p.z() < 0.999f) open.positions.push_back(p);
    io::write_ply((dir_ / "open_box.ply").string(), open);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  /// Reads, prepares, draws and writes the open box with `progress`, into a directory of its own.
  static void draw_and_write(const ProgressFn& progress, const fs::path& out) {
    DrawOptions options;
    options.camera = {.direction = Vec3d(-1, -0.8, -0.6), .width = 160, .height = 160};
    options.shadow.mode = stylize::ShadowMode::Both;
    options.progress = progress;
    io::ReadOptions read;
    read.progress = progress;
    const Prepared prepared = prepare(io::read_point_cloud((dir_ / "open_box.ply").string(), read).cloud, options);
    const DrawResult result = draw_view(prepared, options.camera, options);
    fs::create_directories(out);
    render::write_drawings(result.drawing, {out / "d.svg", out / "d.png"}, options.render, progress);
  }

  static inline fs::path dir_;
};

TEST_F(Progress, EveryStageReportsUnderItsNameAndNeverStartsAgain) {
  Reports reports;
  draw_and_write(
      [&](std::string_view stage, double fraction) {
        reports.emplace_back(stage, fraction);
        return true;
      },
      dir_ / "all");
  for (const std::string& stage : kStages)
    EXPECT_TRUE(std::any_of(reports.begin(), reports.end(), [&](const auto& r) { return r.first == stage; }))
        << stage << " never reported";
  std::size_t run = 0;
  for (std::size_t i = 0; i < reports.size(); ++i) {
    const auto& [stage, fraction] = reports[i];
    EXPECT_FALSE(stage.empty());
    EXPECT_GE(fraction, 0.0);
    EXPECT_LE(fraction, 1.0);
    const bool same = i > 0 && reports[i - 1].first == stage;
    // Consecutive reports of one stage go forward: a terminal line never jumps back to 0% under the same name.
    if (same) {
      EXPECT_GE(fraction, reports[i - 1].second) << stage << " went back at report " << i;
    }
    run = same ? run + 1 : 1;
    EXPECT_LE(run, 45u) << stage << ": too many reports for a progress line";
  }
}

TEST_F(Progress, ReturningFalseInAnyStageThrowsCancelledAndWritesNothing) {
  for (const std::string& target : kStages) {
    bool reached = false;
    const fs::path out = dir_ / "cancel";
    fs::remove_all(out);
    EXPECT_THROW(draw_and_write(
                     [&](std::string_view stage, double) {
                       reached = reached || stage == target;
                       return stage != target;
                     },
                     out),
                 Cancelled)
        << target;
    EXPECT_TRUE(reached) << target << " never reported";
    // Neither output nor temporary file: writing stops before any file replaces its target.
    if (fs::exists(out)) {
      EXPECT_TRUE(fs::is_empty(out)) << target;
    }
  }
}

TEST_F(Progress, CancellingAtTheEndOfWritingLeavesNoFile) {
  const fs::path out = dir_ / "late";
  const ProgressFn stop_when_written = [](std::string_view stage, double fraction) {
    return stage != "writing" || fraction < 1;
  };
  EXPECT_THROW(draw_and_write(stop_when_written, out), Cancelled);
  EXPECT_TRUE(fs::is_empty(out));
}

}  // namespace
}  // namespace pcsketch
