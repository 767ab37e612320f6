// What scanners deliver: the shared meshes sampled at N points (default 200,000), clean, with Gaussian noise of
// 0.1% and 0.2% of the diagonal, and with 1% stray points (uniform, and in clumps of 20), each drawn from several
// views and scored against the mesh's exact visible occluding contours and sharp edges (3 px at 1024 px,
// tests/support/mesh_ground_truth.h). Speed and quality read together: seconds of prepare() and of a view, peak RSS.
//
//   bench_scans [-n N] [--models a,b] [--conditions clean,0.1%,...] [--views K] [--boundary on|off]
//               [--fusion on|off] [--smooth on|off] [--min-stroke-length PX] [--score all|drawn]
//               [--config OPTIONS.json]
//
// --config reads options as `pcsketch draw --print-config` writes them (any subset), in its place among the flags.
// --score drawn leaves out the strokes fused into another line (not painted); by default every visible stroke is
// scored as the kind it was traced as.
//
// Each (model, condition) runs in its own process. "total" = prepare + the first view (no reading, no writing).

#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "pcsketch/io/read_cloud.h"
#include "pcsketch/io/sample_mesh.h"
#include "pcsketch/options_table.h"
#include "pcsketch/pipeline.h"
#include "support/bench_support.h"
#include "support/mesh_ground_truth.h"

namespace pcsketch::bench {
namespace {

struct Condition {
  std::string name;
  double noise = 0;      ///< σ, fraction of the diagonal
  double outliers = 0;   ///< fraction of n
  std::size_t clump = 1;
  /// Only the samples whose face looks towards the first view's camera: a scan from one side, whose border is the
  /// outline and the rims of that view. Scored from that view only, contours and borders together.
  bool one_side = false;
};
const Condition kConditions[] = {{"clean", 0, 0, 1},
                                 {"0.1%", 0.001, 0, 1},
                                 {"0.2%", 0.002, 0, 1},
                                 {"1% outliers", 0, 0.01, 1},
                                 {"2% clumps", 0, 0.02, 20},
                                 {"0.1% + 1% outl.", 0.001, 0.01, 1},
                                 {"one side", 0, 0, 1, true},
                                 {"one side 0.1%", 0.001, 0, 1, true},
                                 {"one side + 1% outl.", 0, 0.01, 1, true}};

/// Directions of sight: the paper's +z and four oblique ones, none parallel to the default up (+y).
const Vec3d kViews[] = {{0, 0, 1}, {1, 0.15, 0.6}, {1, 1, 1}, {-1, 0.3, -0.5}, {0.3, -0.6, 1}};

constexpr float kSharpDegrees = 40.f;
constexpr float kTolerancePx = 3.f;


/// Scores the visible strokes of `kind`; with `drawn_only`, the copies fused into another line (not painted) are left
/// out, so a ridge drawn as the contour along it counts for the contour only; `with_border` scores the boundary
/// strokes with them.
nlohmann::json score(Drawing drawing, LineKind kind, const std::vector<Vec2f>& truth, bool drawn_only,
                     bool with_border = false) {
  if (truth.empty()) return nullptr;
  if (drawn_only) std::erase_if(drawing.strokes, [](const Stroke& s) { return s.fused_into.has_value(); });
  std::vector<Vec2f> drawn = test::sample_visible_strokes(drawing, kind);
  if (with_border) {  // an open scan's border is where its outline and rims are
    const std::vector<Vec2f> border = test::sample_visible_strokes(drawing, LineKind::Boundary);
    drawn.insert(drawn.end(), border.begin(), border.end());
  }
  const test::LineMatch m = test::match_lines(drawn, truth, kTolerancePx);
  return {m.precision, m.recall};
}

std::string measure(const std::string& model, const Condition& c, std::size_t n, std::size_t views,
                    const DrawOptions& options, bool drawn_only) {
  const Mesh mesh = io::read_mesh(shared_data(model + ".off"));
  PointCloud cloud = io::sample_mesh(mesh, {.n = n,
                                            .noise_sigma_factor = c.noise,
                                            .seed = 2024,
                                            .keep_normals = c.one_side,
                                            .outlier_fraction = c.outliers,
                                            .outlier_clump = c.clump});
  if (c.one_side) {
    std::vector<std::uint32_t> facing;
    for (std::uint32_t i = 0; i < cloud.size(); ++i)
      if (cloud.source_index[i] == io::kOutlier || cloud.normals[i].cast<double>().dot(kViews[0]) < 0)
        facing.push_back(i);
    keep_points(cloud, facing);
    cloud.normals.clear();  // a raw scan's
    views = 1;
  }
  shuffle(cloud, 2024);
  std::size_t outliers = 0;
  for (const std::uint32_t s : cloud.source_index) outliers += s == io::kOutlier;
  Stopwatch clock;
  const Prepared prepared = prepare(std::move(cloud), options);
  const double prepare_seconds = clock.restart();
  nlohmann::json per_view = nlohmann::json::array();
  double view_seconds = 0;
  for (std::size_t v = 0; v < views; ++v) {
    view::CameraOptions camera = options.camera;
    camera.direction = kViews[v];
    clock.restart();
    const DrawResult result = draw_view(prepared, camera, options);
    if (v == 0) view_seconds = clock.seconds();
    const view::Camera cam = view::make_camera(prepared.cloud.positions, prepared.cloud.origin, camera);
    const test::MeshSharpEdges sharp = test::mesh_sharp_edges(mesh, cam, kSharpDegrees);
    const Drawing& d = result.drawing;
    const std::vector<Vec2f> contours = test::mesh_contours(mesh, cam).visible;
    per_view.push_back({{"contour", score(d, LineKind::Contour, contours, drawn_only, c.one_side)},
                        {"ridge", score(d, LineKind::Ridge, sharp.convex.visible, drawn_only)},
                        {"valley", score(d, LineKind::Valley, sharp.concave.visible, drawn_only)}});
  }
  // Outliers left in the analysed cloud, and surface points removed with them.
  std::size_t kept_outliers = 0;
  for (const std::uint32_t s : prepared.cloud.source_index) kept_outliers += s == io::kOutlier;
  return nlohmann::json{{"prepare", prepare_seconds},
                        {"view", view_seconds},
                        {"kept", prepared.cloud.size()},
                        {"outliers", outliers},
                        {"kept_outliers", kept_outliers},
                        {"views", per_view},
                        {"peak", peak_rss_bytes()}}
      .dump();
}

/// "min–mean" of one score component over the views where it exists, or "—".
std::string range_cell(const nlohmann::json& views, const std::string& key, std::size_t index) {
  double lo = 1, sum = 0;
  std::size_t count = 0;
  for (const auto& v : views) {
    if (v[key].is_null()) continue;
    const double x = v[key][index].get<double>();
    lo = std::min(lo, x), sum += x, ++count;
  }
  if (count == 0) return "—";
  return fixed(lo, 2) + "–" + fixed(sum / static_cast<double>(count), 2);
}

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

int run(int argc, char** argv) {
  std::size_t n = 200000, views = std::size(kViews);
  std::vector<std::string> models = {"bunny", "camel", "fandisk", "elephant"};
  std::vector<Condition> conditions(std::begin(kConditions), std::end(kConditions));
  DrawOptions options;
  bool drawn_only = false;
  for (int a = 1; a + 1 < argc; a += 2) {
    const std::string flag = argv[a], value = argv[a + 1];
    if (flag == "-n") n = std::stoul(value);
    else if (flag == "--views") views = std::min<std::size_t>(std::stoul(value), std::size(kViews));
    else if (flag == "--models") models = split(value);
    else if (flag == "--boundary") options.boundary.enabled = value != "off";
    else if (flag == "--fusion") options.fusion.enabled = value != "off";
    else if (flag == "--score") drawn_only = value == "drawn";
    else if (flag == "--smooth") options.finish.smooth = value != "off";
    else if (flag == "--min-stroke-length") options.finish.min_length_px = std::stof(value);
    else if (flag == "--config") {
      std::ifstream in(value);
      if (!in) throw std::runtime_error("cannot open " + value);
      options::from_json(nlohmann::json::parse(in), options);
    }
    else if (flag == "--conditions") {
      conditions.clear();
      for (const std::string& name : split(value))
        for (const Condition& c : kConditions)
          if (c.name == name) conditions.push_back(c);
    } else throw std::runtime_error("unknown flag " + flag);
  }
  std::cout << "load average before: " << load_average() << "; " << grouped(n) << " samples, " << views
            << " views, scores min–mean over views at " << kTolerancePx << " px\n";
  Table table({"model", "condition", "kept", "outliers left", "prepare s", "view s", "total s", "contour P",
               "contour R", "ridge P / R", "valley P / R", "peak RSS"});
  for (const std::string& model : models)
    for (const Condition& c : conditions) {
      const nlohmann::json r =
          nlohmann::json::parse(run_isolated([&] { return measure(model, c, n, views, options, drawn_only); }));
      const double total = r["prepare"].get<double>() + r["view"].get<double>();
      const auto& v = r["views"];
      table.add_row({model, c.name, grouped(r["kept"].get<std::size_t>()),
                     grouped(r["kept_outliers"].get<std::size_t>()) + "/" + grouped(r["outliers"].get<std::size_t>()),
                     fixed(r["prepare"].get<double>(), 3), fixed(r["view"].get<double>(), 3), fixed(total, 3),
                     range_cell(v, "contour", 0), range_cell(v, "contour", 1),
                     range_cell(v, "ridge", 0) + " / " + range_cell(v, "ridge", 1),
                     range_cell(v, "valley", 0) + " / " + range_cell(v, "valley", 1),
                     mebibytes(r["peak"].get<std::size_t>())});
      std::cout << model << " " << c.name << " done\n" << std::flush;
    }
  std::cout << table.to_string() << "load average after: " << load_average() << "\n";
  return 0;
}

}  // namespace
}  // namespace pcsketch::bench

int main(int argc, char** argv) { return pcsketch::bench::bench_main("bench_scans", argc, argv, pcsketch::bench::run); }
