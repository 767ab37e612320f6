// The paper's Table 2 ("Model – time contrast") for our whole pipeline: ridge-valley points extraction, connection,
// contour points extraction, contour line connection, drawing, total, for the vertices of bunny, camel, fandisk and
// elephant (/work/shared/data/*.off) and for clouds sampled from bunny.off; next to the paper's published seconds and
// the per-point ratio, with the contour, ridge and valley precision/recall of each drawing against its mesh's ground
// truth (the visible occluding contours, and the visible convex and concave sharp edges at 40°,
// tests/support/mesh_ground_truth.h) so that speed and quality are read together.
//
//   bench_pipeline [N ...]   sample sizes (default 1000000 5000000); "0" skips the sampled clouds
//
// "total" is end to end without process start: read (of the vertices' OFF, or of the samples written beforehand as
// a binary PLY) + analysis + lines + view + thickness + shadows + writing an
// SVG and a PNG of 1024 × 1024 px. Each model runs in its own process (its own peak RSS).

#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "pcsketch/io/ply.h"
#include "pcsketch/io/read_cloud.h"
#include "pcsketch/pipeline.h"
#include "pcsketch/render/write.h"
#include "support/bench_support.h"
#include "support/mesh_ground_truth.h"

namespace pcsketch::bench {
namespace {

/// The paper's Table 2 (Intel Core 2 Duo, 4 GB): points and the six rows, seconds.
struct PaperRow {
  std::string model;
  std::size_t points;
  double rows[6];
};
const PaperRow kPaper[] = {{"bunny", 5326, {2.715, 0.338, 1.810, 0.367, 1.521, 7.151}},
                           {"camel", 6603, {3.247, 0.586, 1.925, 0.689, 1.875, 8.322}}};

struct Job {
  std::string name;   ///< table column
  std::string mesh;   ///< shared data file
  std::size_t samples = 0;  ///< 0: the mesh's vertices
  std::string paper;  ///< model name in kPaper, or empty
};

/// Mesh edges whose faces meet at more than this angle (degrees) are the ground truth of ridge and valley lines, as
/// in the features tests (fandisk).
constexpr float kSharpDegrees = 40.f;


/// Runs the whole pipeline on one cloud and scores its lines; returns JSON (crosses the process boundary).
std::string measure(const Job& job) {
  // A sampled cloud is written as a binary PLY first, untimed: its read row is a user's read of the file, not the
  // sampling of the mesh (which took twice as long at 1M points).
  std::string input = shared_data(job.mesh);
  if (job.samples > 0) {
    input = (std::filesystem::temp_directory_path() / "pcsketch_bench_pipeline.ply").string();
    io::write_ply(input, sampled_cloud(shared_data(job.mesh), job.samples, 2024));
  }
  Stopwatch clock;
  PointCloud cloud = io::read_point_cloud(input).cloud;
  Timings timings;
  timings.read = clock.restart();
  if (job.samples > 0) std::filesystem::remove(input);
  const DrawOptions options;
  const Prepared prepared = prepare(std::move(cloud), options);
  timings += prepared.timings;
  DrawResult result = draw_view(prepared, options.camera, options);
  clock.restart();
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  render::write_drawings(result.drawing, {dir / "pcsketch_bench_pipeline.svg", dir / "pcsketch_bench_pipeline.png"},
                         options.render);
  result.timings.drawing += clock.restart();
  timings += result.timings;
  const std::size_t peak = peak_rss_bytes();

  // Quality, same camera, 3 px at 1024 px: visible contour strokes against the mesh's visible occluding contours,
  // visible ridge strokes against its visible convex sharp edges and valley strokes against its concave ones.
  const Mesh mesh = io::read_mesh(shared_data(job.mesh));
  const view::Camera camera = view::make_camera(prepared.cloud.positions, prepared.cloud.origin, options.camera);
  const test::MeshSharpEdges sharp = test::mesh_sharp_edges(mesh, camera, kSharpDegrees);
  const auto score = [&](LineKind kind, const std::vector<Vec2f>& truth) {
    if (truth.empty()) return nlohmann::json();  // nothing to find: no score
    const test::LineMatch match = test::match_lines(test::sample_visible_strokes(result.drawing, kind), truth, 3.f);
    return nlohmann::json{match.precision, match.recall};
  };
  std::size_t strokes = 0;
  for (const Stroke& s : result.drawing.strokes) strokes += s.visible;

  nlohmann::json rows = nlohmann::json::array();
  for (const auto& [name, seconds] : timings.all_rows()) rows.push_back({name, seconds});
  return nlohmann::json{{"points", prepared.cloud.size()},
                        {"rows", rows},
                        {"contour", score(LineKind::Contour, test::mesh_contours(mesh, camera).visible)},
                        {"ridge", score(LineKind::Ridge, sharp.convex.visible)},
                        {"valley", score(LineKind::Valley, sharp.concave.visible)},
                        {"strokes", strokes},
                        {"peak", peak}}
      .dump();
}

int run(int argc, char** argv) {
  std::vector<std::size_t> sizes{1000000, 5000000};
  if (argc > 1) {
    sizes.clear();
    for (int a = 1; a < argc; ++a)
      if (const std::size_t n = std::stoul(argv[a]); n > 0) sizes.push_back(n);
  }
  std::vector<Job> jobs = {{"bunny", "bunny.off", 0, "bunny"},
                           {"camel", "camel.off", 0, "camel"},
                           {"fandisk", "fandisk.off", 0, ""},
                           {"elephant", "elephant.off", 0, ""}};
  for (std::size_t n : sizes) jobs.push_back({"bunny " + grouped(n), "bunny.off", n, ""});

  std::cout << "load average before: " << load_average() << "\n";
  std::vector<nlohmann::json> results;
  for (const Job& job : jobs) results.push_back(nlohmann::json::parse(run_isolated([&job] { return measure(job); })));

  // Table 2's six rows under their names, our other rows after them.
  const std::vector<std::string> paper_rows = {"ridge-valley points extraction", "ridge-valley points connection",
                                               "contour points extraction", "contour line connection", "drawing",
                                               "total"};
  std::vector<std::string> header{"row (seconds)"};
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    header.push_back(jobs[j].name);
    if (!jobs[j].paper.empty()) header.push_back("paper " + jobs[j].paper);
  }
  Table table(header);
  const auto seconds_of = [](const nlohmann::json& r, const std::string& row) {
    for (const auto& cell : r["rows"])
      if (cell[0] == row) return cell[1].get<double>();
    return 0.0;
  };
  const auto paper_of = [](const std::string& model) -> const PaperRow* {
    for (const PaperRow& p : kPaper)
      if (p.model == model) return &p;
    return nullptr;
  };
  std::vector<std::string> order = paper_rows;
  for (const auto& cell : results[0]["rows"])
    if (std::find(order.begin(), order.end(), cell[0].get<std::string>()) == order.end())
      order.push_back(cell[0].get<std::string>());
  for (const std::string& row : order) {
    const auto paper_index = std::find(paper_rows.begin(), paper_rows.end(), row) - paper_rows.begin();
    const bool in_paper = paper_index < static_cast<long>(paper_rows.size());
    std::vector<std::string> cells{in_paper ? row + " *" : "  " + row};
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      cells.push_back(fixed(seconds_of(results[j], row), 4));
      if (const PaperRow* p = paper_of(jobs[j].paper)) cells.push_back(in_paper ? fixed(p->rows[paper_index], 3) : "");
    }
    table.add_row(cells);
  }
  const auto add = [&](const std::string& label, auto ours, auto paper) {
    std::vector<std::string> cells{label};
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      cells.push_back(ours(results[j]));
      if (const PaperRow* p = paper_of(jobs[j].paper)) cells.push_back(paper(*p, results[j]));
    }
    table.add_row(cells);
  };
  const auto none = [](const PaperRow&, const nlohmann::json&) { return std::string(); };
  add("points", [](const nlohmann::json& r) { return grouped(r["points"].get<std::size_t>()); },
      [](const PaperRow& p, const nlohmann::json&) { return grouped(p.points); });
  add("µs per point (total)",
      [&](const nlohmann::json& r) { return fixed(1e6 * seconds_of(r, "total") / r["points"].get<double>(), 2); },
      [](const PaperRow& p, const nlohmann::json&) { return fixed(1e6 * p.rows[5] / static_cast<double>(p.points), 1); });
  add("paper/ours per point", [](const nlohmann::json&) { return std::string(); },
      [&](const PaperRow& p, const nlohmann::json& r) {
        const double ours = seconds_of(r, "total") / r["points"].get<double>();
        return fixed(p.rows[5] / static_cast<double>(p.points) / ours, 0) + "x";
      });
  // A score is a dash where the mesh shows no line of that kind (a smooth mesh has no sharp edge): nothing to find.
  const auto score_cell = [](const std::string& key, std::size_t index) {
    return [key, index](const nlohmann::json& r) {
      return r[key].is_null() ? std::string("—") : fixed(r[key][index].get<double>(), 3);
    };
  };
  const auto both_cell = [&](const std::string& key) {
    return [key, precision = score_cell(key, 0), recall = score_cell(key, 1)](const nlohmann::json& r) {
      return r[key].is_null() ? std::string("—") : precision(r) + " / " + recall(r);
    };
  };
  add("contour precision (3 px)", score_cell("contour", 0), none);
  add("contour recall (3 px)", score_cell("contour", 1), none);
  add("ridge precision / recall (3 px)", both_cell("ridge"), none);
  add("valley precision / recall (3 px)", both_cell("valley"), none);
  add("visible strokes", [](const nlohmann::json& r) { return grouped(r["strokes"].get<std::size_t>()); }, none);
  add("peak RSS", [](const nlohmann::json& r) { return mebibytes(r["peak"].get<std::size_t>()); }, none);
  std::cout << table.to_string() << "* = a row of the paper's Table 2. load average after: " << load_average() << "\n";
  return 0;
}

}  // namespace
}  // namespace pcsketch::bench

int main(int argc, char** argv) {
  return pcsketch::bench::bench_main("bench_pipeline", argc, argv, pcsketch::bench::run);
}
