// Plotter paths (plotter/plot_order.h) on the gallery's views: pen-down and pen-up travel and stroke count of the
// drawing as written without ordering, against the merged and sorted one, on a 200 mm page at the gallery's 512 px.
//
//   bench_plotter [PAGE_MM]   page width in millimetres (default 200)
//
// Models: the bundled sample (data/bunny.ply, --azimuth -35 --elevation 15), and from ../shared/data fandisk.off
// (--view 1,1,1, and the paper's +z view, where paper-mode hatch lines of several ridges fall on one line) and
// building.ply (--up 0,0,1 --view 1,0.7,-0.6), the views of scripts/gallery.sh. A model that is
// not there is skipped.

#include <filesystem>
#include <iostream>
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
    const double mm_per_px = render::mm_per_pixel(drawn.drawing.width, options.render);
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
  return 0;
}

}  // namespace
}  // namespace pcsketch::bench

int main(int argc, char** argv) {
  return pcsketch::bench::bench_main("bench_plotter", argc, argv, pcsketch::bench::run);
}
