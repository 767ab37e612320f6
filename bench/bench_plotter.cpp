// Plotter paths (plotter/plot_order.h) on the gallery's views: pen-down and pen-up travel and stroke count of the
// drawing as written without ordering, against the merged and sorted one, on a 200 mm page at the gallery's 512 px.
//
//   bench_plotter [PAGE_MM [N ...]]   page width in millimetres (default 200); each N also times plot_order on N
//                                     random short strokes in five layers on a 4000 px image (near-linear check)
//
// Models: the bundled sample (data/bunny.ply, --azimuth -35 --elevation 15), and from ../shared/data fandisk.off
// (--view 1,1,1, and the paper's +z view, where paper-mode hatch lines of several ridges fall on one line) and
// building.ply (--up 0,0,1 --view 1,0.7,-0.6), the views of scripts/gallery.sh. A model that is
// not there is skipped.

#include <filesystem>
#include <iostream>
#include <random>
#include <string>

#include "pcsketch/io/read_cloud.h"
#include "pcsketch/pipeline.h"
#include "pcsketch/plotter/plot_order.h"
#include "support/bench_support.h"

namespace pcsketch::bench {
namespace {

struct Model {
  std::string name, path;
  view::CameraOptions camera;
};

/// `n` strokes 0–7 px long, uniformly over a 4000 px square, spread over the five line kinds: pieces that rarely
/// meet, so merging finds few joins and sorting does the work.
Drawing random_strokes(std::size_t n) {
  std::mt19937 rng(12111);
  std::uniform_real_distribution<float> coord(0.f, 4000.f), step(-5.f, 5.f);
  Drawing d;
  d.width = d.height = 4000;
  for (std::size_t i = 0; i < n; ++i) {
    Stroke s;
    s.kind = static_cast<LineKind>(i % 5);
    const Vec2f a(coord(rng), coord(rng));
    s.image_points = {a, a + Vec2f(step(rng), step(rng))};
    d.strokes.push_back(std::move(s));
  }
  return d;
}

void time_random(const std::vector<std::size_t>& counts) {
  Table table({"random strokes", "seconds", "pen-up mm", "pen-up mm --plotter", "strokes --plotter"});
  for (const std::size_t n : counts) {
    const Drawing d = random_strokes(n);
    Stopwatch clock;
    const plotter::PlotterResult r = plotter::plot_order(d, 0.05, {.min_stroke_mm = 0});
    table.add_row({grouped(n), fixed(clock.seconds(), 3), fixed(r.before.pen_up_mm, 0), fixed(r.after.pen_up_mm, 0),
                   grouped(r.after.strokes)});
  }
  std::cout << table.to_string();
}

int run(int argc, char** argv) {
  const double page_mm = argc > 1 ? std::stod(argv[1]) : 200.0;
  std::cout << "load average before: " << load_average() << "\n";
  const std::vector<Model> models = {
      {"sample (data/bunny.ply)", PCSKETCH_DATA "/bunny.ply", {.azimuth_deg = -35.0, .elevation_deg = 15.0}},
      {"fandisk", shared_data("fandisk.off"), {.direction = Vec3d(1, 1, 1)}},
      {"fandisk, +z (paper's view)", shared_data("fandisk.off"), {}},
      {"building", shared_data("building.ply"), {.direction = Vec3d(1, 0.7, -0.6), .up = Vec3d(0, 0, 1)}}};
  Table table({"model", "strokes", "pen-down mm", "pen-up mm", "strokes", "pen-down mm", "pen-up mm", "pen-up ratio",
               "joins", "dropped", "hatching once mm", "ms"});
  for (Model m : models) {
    if (!std::filesystem::exists(m.path)) {
      std::cout << "skipping " << m.name << " (" << m.path << " not found)\n";
      continue;
    }
    DrawOptions options;
    m.camera.width = m.camera.height = 512;
    options.render.page_width_mm = page_mm;
    const DrawResult drawn = draw_view(prepare(io::read_point_cloud(m.path).cloud, options), m.camera, options);
    const double mm_per_px = render::mm_per_pixel(drawn.drawing, options.render);
    Stopwatch clock;
    const plotter::PlotterResult r = plotter::plot_order(drawn.drawing, mm_per_px, options.plotter);
    const double ms = 1e3 * clock.seconds();
    table.add_row({m.name, grouped(r.before.strokes), fixed(r.before.pen_down_mm, 0), fixed(r.before.pen_up_mm, 0),
                   grouped(r.after.strokes), fixed(r.after.pen_down_mm, 0), fixed(r.after.pen_up_mm, 0),
                   fixed(r.before.pen_up_mm / std::max(r.after.pen_up_mm, 1e-9), 2), grouped(r.joins),
                   grouped(r.short_strokes_dropped), fixed(r.duplicate_hatching_mm, 0), fixed(ms, 1)});
  }
  std::cout << "page " << fixed(page_mm, 0) << " mm wide, 512 px; columns 2-4 unsorted (as drawn), 5-7 --plotter\n"
            << table.to_string();
  std::vector<std::size_t> counts;
  for (int i = 2; i < argc; ++i) counts.push_back(std::stoul(argv[i]));
  if (!counts.empty()) time_random(counts);
  return 0;
}

}  // namespace
}  // namespace pcsketch::bench

int main(int argc, char** argv) {
  return pcsketch::bench::bench_main("bench_plotter", argc, argv, pcsketch::bench::run);
}
