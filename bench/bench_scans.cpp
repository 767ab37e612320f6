// What scanners deliver: the shared meshes sampled at N points (default 200,000), clean, with Gaussian noise of
// 0.1% and 0.2% of the diagonal, and with 1% stray points (uniform, and in clumps of 20), each drawn from several
// views and scored against the mesh's exact visible occluding contours and sharp edges (3 px at 1024 px,
// tests/support/mesh_ground_truth.h); boundary strokes are scored with the contours, as the truth holds the mesh's
// border edges. "vertices" draws the mesh's own vertices (a sparse, often uneven cloud). A model is a shared mesh's
// name or a path to any mesh (held-out models: scripts/heldout_meshes.sh). Speed and quality read together: seconds
// of prepare() and of a view, peak RSS. "outline R" is the part of the mesh's filled silhouette's edge within the
// tolerance of a drawn contour or border: whether the outline closes, scored against truth that does not depend on
// how finely the mesh is faceted (a coarse mesh's contour edges zig-zag across its grazing faces).
//
//   bench_scans [-n N] [--models a,b|path.off,...] [--conditions clean,0.1%,...] [--views K] [--boundary on|off]
//               [--fusion on|off] [--smooth on|off] [--min-stroke-length PX] [--score all|drawn]
//               [--config OPTIONS.json] [--overlay DIR]
//
// --config reads options as `pcsketch draw --print-config` writes them (any subset), in its place among the flags.
// --score drawn leaves out the strokes fused into another line (not painted); by default every visible stroke is
// scored as the kind it was traced as. --overlay writes an SVG per model, condition and view into DIR: the contour
// truth green where drawn and red where missed, the drawn contour blue where true and orange where not.
//
// Each (model, condition) runs in its own process. "total" = prepare + the first view (no reading, no writing).

#include <array>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numeric>
#include <random>
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
  /// outline and the rims of that view. Scored from that view only, against the faces sampled (kept_faces).
  bool one_side = false;
  /// The mesh's own vertices instead of samples (n unused): a sparse cloud whose points lie on the true contours.
  bool vertices = false;
  /// This many scan lines over the model's height (y), n points along them (scan_line_samples): about 20:1 denser
  /// along the lines than across at 200k points.
  std::size_t scan_lines = 0;
};
const Condition kConditions[] = {{"clean", 0, 0, 1},
                                 {"0.1%", 0.001, 0, 1},
                                 {"0.2%", 0.002, 0, 1},
                                 {"1% outliers", 0, 0.01, 1},
                                 {"2% clumps", 0, 0.02, 20},
                                 {"0.1% + 1% outl.", 0.001, 0.01, 1},
                                 {"one side", 0, 0, 1, true},
                                 {"one side 0.1%", 0.001, 0, 1, true},
                                 {"one side + 1% outl.", 0, 0.01, 1, true},
                                 {"vertices", 0, 0, 1, false, true},
                                 {"scan lines", 0, 0, 1, false, false, 60},
                                 {"scan lines 0.1%", 0.001, 0, 1, false, false, 60}};

/// Directions of sight: the paper's +z and four oblique ones, none parallel to the default up (+y).
const Vec3d kViews[] = {{0, 0, 1}, {1, 0.15, 0.6}, {1, 1, 1}, {-1, 0.3, -0.5}, {0.3, -0.6, 1}};

constexpr float kSharpDegrees = 40.f;
constexpr float kTolerancePx = 3.f;


/// Samples of the visible strokes of `kind`; with `drawn_only`, the copies fused into another line (not painted) are
/// left out, so a ridge drawn as the contour along it counts for the contour only; `with_border` adds the boundary
/// strokes.
std::vector<Vec2f> drawn_samples(Drawing drawing, LineKind kind, bool drawn_only, bool with_border) {
  if (drawn_only) std::erase_if(drawing.strokes, [](const Stroke& s) { return s.fused_into.has_value(); });
  std::vector<Vec2f> drawn = test::sample_visible_strokes(drawing, kind);
  if (with_border) {  // a scan's border is where its outline and rims are
    const std::vector<Vec2f> border = test::sample_visible_strokes(drawing, LineKind::Boundary);
    drawn.insert(drawn.end(), border.begin(), border.end());
  }
  return drawn;
}

/// Precision and recall of drawn samples against the truth's, or null where there is no truth.
nlohmann::json score(const std::vector<Vec2f>& drawn, const std::vector<Vec2f>& truth) {
  if (truth.empty()) return nullptr;
  const test::LineMatch m = test::match_lines(drawn, truth, kTolerancePx);
  return {m.precision, m.recall};
}

/// An SVG of the contour score: truth samples green where drawn near them, red where missed; drawn samples blue
/// where true, orange where not; the cloud's points grey.
void write_overlay(const std::string& file, const view::Camera& camera, const PointCloud& cloud,
                   const std::vector<Vec2f>& drawn, const std::vector<Vec2f>& truth) {
  std::ofstream out(file);
  out << "<svg xmlns='http://www.w3.org/2000/svg' width='" << camera.width << "' height='" << camera.height
      << "'><rect width='100%' height='100%' fill='white'/>\n";
  const auto dots = [&](const std::vector<Vec2f>& points, const std::vector<bool>& good, const char* yes,
                        const char* no, float r) {
    for (std::size_t i = 0; i < points.size(); ++i)
      out << "<circle cx='" << points[i].x() << "' cy='" << points[i].y() << "' r='" << r << "' fill='"
          << (good.empty() || good[i] ? yes : no) << "'/>\n";
  };
  std::vector<Vec2f> projected;
  for (const Vec3f& p : cloud.positions) projected.push_back(camera.project(p).head<2>());
  dots(projected, {}, "#bbb", "#bbb", 0.8f);
  dots(truth, test::matched_samples(truth, drawn, kTolerancePx), "#2a2", "#e22", 1.2f);
  dots(drawn, test::matched_samples(drawn, truth, kTolerancePx), "#22c", "#f80", 0.6f);
  out << "</svg>\n";
}

/// A profile scanner's points: the mesh cut by `lines` planes y = const evenly spread over its height, the cuts
/// sampled at one spacing along them so that about `n` points are made (each segment from a random phase), with
/// Gaussian noise of `noise` × the diagonal on each coordinate.
PointCloud scan_line_samples(const Mesh& mesh, std::size_t lines, std::size_t n, double noise) {
  float low = mesh.vertices.front().y(), high = low;
  for (const Vec3f& v : mesh.vertices) low = std::min(low, v.y()), high = std::max(high, v.y());
  const float gap = (high - low) / static_cast<float>(lines);
  std::vector<std::pair<Vec3f, Vec3f>> cuts;
  double length = 0;
  for (const auto& f : mesh.faces) {
    float bottom = mesh.vertices[f[0]].y(), top = bottom;
    for (const std::uint32_t v : f) {
      bottom = std::min(bottom, mesh.vertices[v].y());
      top = std::max(top, mesh.vertices[v].y());
    }
    // Only the planes within the face's span can cut it (one below and above, for rounding).
    const auto first = static_cast<std::size_t>(std::max(0.f, (bottom - low) / gap - 1.5f));
    const std::size_t last = std::min(lines, static_cast<std::size_t>(std::max(0.f, (top - low) / gap + 1.5f)));
    for (std::size_t l = first; l < last; ++l) {
      const float y = low + (static_cast<float>(l) + 0.5f) * gap;
      std::array<Vec3f, 3> ends;
      std::size_t count = 0;
      for (int e = 0; e < 3; ++e) {
        const Vec3f& a = mesh.vertices[f[static_cast<std::size_t>(e)]];
        const Vec3f& b = mesh.vertices[f[static_cast<std::size_t>((e + 1) % 3)]];
        if ((a.y() < y) != (b.y() < y)) ends[count++] = a + (b - a) * ((y - a.y()) / (b.y() - a.y()));
      }
      if (count != 2) continue;
      cuts.emplace_back(ends[0], ends[1]);
      length += static_cast<double>((ends[1] - ends[0]).norm());
    }
  }
  const double step = length / static_cast<double>(n);
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> phase(0, 1);
  Vec3f lo = mesh.vertices.front(), hi = lo;
  for (const Vec3f& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  std::normal_distribution<float> offset(0.f, static_cast<float>(noise) * (hi - lo).norm());
  PointCloud cloud;
  cloud.origin = mesh.origin;
  for (const auto& cut : cuts) {
    const double l = static_cast<double>((cut.second - cut.first).norm());
    for (double t = phase(rng) * step; t < l; t += step) {
      const Vec3f jitter = noise > 0 ? Vec3f(offset(rng), offset(rng), offset(rng)) : Vec3f::Zero();
      cloud.positions.push_back(cut.first + (cut.second - cut.first) * static_cast<float>(t / l) + jitter);
    }
  }
  cloud.source_index.resize(cloud.size());
  std::iota(cloud.source_index.begin(), cloud.source_index.end(), 0u);
  return cloud;
}

/// Which faces of `mesh` look towards `direction` (their normal against it): what a scan from that side records.
std::vector<char> facing_faces(const Mesh& mesh, const Vec3d& direction) {
  std::vector<char> facing(mesh.faces.size());
  for (std::size_t f = 0; f < facing.size(); ++f) {
    const Vec3d a = mesh.vertices[mesh.faces[f][0]].cast<double>();
    const Vec3d b = mesh.vertices[mesh.faces[f][1]].cast<double>(), c = mesh.vertices[mesh.faces[f][2]].cast<double>();
    facing[f] = (b - a).cross(c - a).dot(direction) < 0;
  }
  return facing;
}

/// `mesh` with only the faces `keep` marks. The truth of a one-side scan is its facing faces, whose border they give:
/// the whole mesh's truth held walls seen edge-on and the inside of open shells seen through their rims, which no
/// point of such a scan lies on (a mushroom's stem drawn as a square round its cap, 0.42 / 0.46).
Mesh kept_faces(const Mesh& mesh, const std::vector<char>& keep) {
  Mesh kept = mesh;
  kept.faces.clear();
  for (std::size_t f = 0; f < keep.size(); ++f)
    if (keep[f]) kept.faces.push_back(mesh.faces[f]);
  return kept;
}

/// `overlay_dir`: where --overlay writes its SVGs, empty: none.
std::string measure(const std::string& model, const Condition& c, std::size_t n, std::size_t views,
                    const DrawOptions& options, bool drawn_only, const std::string& overlay_dir) {
  // A name is a shared mesh; a path (held-out meshes) is read as given.
  const std::string path = model.find('/') == std::string::npos ? shared_data(model + ".off") : model;
  const Mesh whole = io::read_mesh(path);
  // A one-side scan keeps the samples of the faces that look at the first view, and is scored against those faces.
  const std::vector<char> facing = c.one_side ? facing_faces(whole, kViews[0]) : std::vector<char>{};
  const Mesh mesh = c.one_side ? kept_faces(whole, facing) : whole;
  PointCloud cloud = c.vertices     ? io::read_point_cloud(path).cloud
                     : c.scan_lines ? scan_line_samples(whole, c.scan_lines, n, c.noise)
                                    : io::sample_mesh(whole, {.n = n,
                                                              .noise_sigma_factor = c.noise,
                                                              .seed = 2024,
                                                              .outlier_fraction = c.outliers,
                                                              .outlier_clump = c.clump});
  if (c.one_side) {
    std::vector<std::uint32_t> seen;
    for (std::uint32_t i = 0; i < cloud.size(); ++i)
      if (cloud.source_index[i] == io::kOutlier || facing[cloud.source_index[i]]) seen.push_back(i);
    keep_points(cloud, seen);
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
    // The truth holds the mesh's border edges with its contours: boundary strokes are scored with the contours (a
    // border drawn on a closed surface counts against precision).
    const std::vector<Vec2f> drawn_contours = drawn_samples(d, LineKind::Contour, drawn_only, true);
    const auto lines = [&](LineKind kind) { return drawn_samples(d, kind, drawn_only, false); };
    per_view.push_back({{"contour", score(drawn_contours, contours)},
                        {"outline", score(drawn_contours, test::mesh_outline(mesh, cam))},
                        {"ridge", score(lines(LineKind::Ridge), sharp.convex.visible)},
                        {"valley", score(lines(LineKind::Valley), sharp.concave.visible)}});
    if (!overlay_dir.empty()) {
      const std::string stem =
          overlay_dir + "/" + std::filesystem::path(model).stem().string() + "_" + c.name + "_" + std::to_string(v);
      write_overlay(stem + ".svg", cam, prepared.cloud, drawn_contours, contours);
      if (!sharp.convex.visible.empty())
        write_overlay(stem + "_ridges.svg", cam, prepared.cloud, lines(LineKind::Ridge), sharp.convex.visible);
      if (!sharp.concave.visible.empty())
        write_overlay(stem + "_valleys.svg", cam, prepared.cloud, lines(LineKind::Valley), sharp.concave.visible);
    }
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
  std::string overlay_dir;
  for (int a = 1; a + 1 < argc; a += 2) {
    const std::string flag = argv[a], value = argv[a + 1];
    if (flag == "-n") n = std::stoul(value);
    else if (flag == "--views") views = std::min<std::size_t>(std::stoul(value), std::size(kViews));
    else if (flag == "--models") models = split(value);
    else if (flag == "--boundary") options.boundary.enabled = value != "off";
    else if (flag == "--fusion") options.fusion.enabled = value != "off";
    else if (flag == "--score") drawn_only = value == "drawn";
    else if (flag == "--overlay") overlay_dir = value;
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
               "contour R", "outline R", "ridge P / R", "valley P / R", "peak RSS"});
  for (const std::string& model : models)
    for (const Condition& c : conditions) {
      const nlohmann::json r =
          nlohmann::json::parse(run_isolated([&] {
            return measure(model, c, n, views, options, drawn_only, overlay_dir);
          }));
      const double total = r["prepare"].get<double>() + r["view"].get<double>();
      const auto& v = r["views"];
      table.add_row({std::filesystem::path(model).stem().string(), c.name, grouped(r["kept"].get<std::size_t>()),
                     grouped(r["kept_outliers"].get<std::size_t>()) + "/" + grouped(r["outliers"].get<std::size_t>()),
                     fixed(r["prepare"].get<double>(), 3), fixed(r["view"].get<double>(), 3), fixed(total, 3),
                     range_cell(v, "contour", 0), range_cell(v, "contour", 1), range_cell(v, "outline", 1),
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
