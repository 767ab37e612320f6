// pcsketch features IN -o OUT.ply [--lines OUT.json]: ridge/valley points and lines of a cloud (paper §IV.A), for
// inspection in CloudCompare/MeshLab (per-point scalar fields) and for other tools (polylines as JSON).

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.h"
#include "options.h"
#include "pcsketch/core/atomic_file.h"
#include "pcsketch/core/error.h"
#include "pcsketch/differential/surface.h"
#include "pcsketch/features/boundary_lines.h"
#include "pcsketch/features/ridge_valley_lines.h"
#include "pcsketch/io/ply.h"
#include "pcsketch/io/read_cloud.h"
#include "pcsketch/pipeline.h"
#include "pcsketch/validate.h"

namespace pcsketch::cli {
namespace {

/// `label` of the points left out as outliers, of the points on a drawn border and of the points thinned away on scan
/// lines (0–2 are features::PointLabel).
constexpr std::uint8_t kOutlierLabel = 3, kBorderLabel = 4, kThinnedLabel = 5;

struct FeaturesArgs {
  std::string in_path;
  std::string out_path;
  std::string lines_path;
  io::ReadOptions read;
  DrawOptions options;  ///< only surface, features, boundary and max_memory_gb are used (the flags shared with draw)
  bool ascii = false;
};

// The per-point arrays in file order (analyse_surface reorders the cloud; source_index maps back).
template <typename T>
std::vector<T> in_file_order(const std::vector<T>& values, const std::vector<std::uint32_t>& source_index) {
  if (source_index.empty()) return values;
  std::vector<T> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) out[source_index[i]] = values[i];
  return out;
}

/// `cloud` followed by points analyse_surface left out (normals zero where they have none): with the outliers and the
/// points thinned on scan lines, every point of the file, so that `label` can mark them instead of dropping them.
PointCloud with_left_out(const PointCloud& cloud, const PointCloud& left_out) {
  PointCloud all = cloud;
  if (left_out.empty()) return all;
  all.positions.insert(all.positions.end(), left_out.positions.begin(), left_out.positions.end());
  if (all.has_normals() || cloud.has_normals()) {
    if (left_out.has_normals())
      all.normals.insert(all.normals.end(), left_out.normals.begin(), left_out.normals.end());
    else
      all.normals.resize(all.positions.size(), Vec3f::Zero());
  }
  if (cloud.has_colors() && left_out.has_colors())
    all.colors.insert(all.colors.end(), left_out.colors.begin(), left_out.colors.end());
  else
    all.colors.clear();
  all.source_index.insert(all.source_index.end(), left_out.source_index.begin(), left_out.source_index.end());
  return all;
}

void write_lines_json(const std::string& path, const PointCloud& cloud, const differential::Surface& surface,
                      const features::RidgeValleyLines& result, const features::Boundary& boundary,
                      const FeaturesArgs& args) {
  nlohmann::json lines = nlohmann::json::array();
  std::vector<const Polyline*> all;
  for (const Polyline& line : result.lines) all.push_back(&line);
  for (const Polyline& line : boundary.lines) all.push_back(&line);
  for (const Polyline* each : all) {
    const Polyline& line = *each;
    nlohmann::json points = nlohmann::json::array();
    for (const Vec3f& p : line.points) {
      const Vec3d w = cloud.origin + p.cast<double>();
      points.push_back({w.x(), w.y(), w.z()});
    }
    nlohmann::json indices = nlohmann::json::array();
    for (std::uint32_t i : line.point_index) indices.push_back(cloud.source_index.empty() ? i : cloud.source_index[i]);
    lines.push_back({{"kind", to_string(line.kind)},
                     {"closed", line.closed},
                     {"points", std::move(points)},
                     {"curvature", line.curvature},
                     {"point_index", std::move(indices)}});
  }
  const features::DetectionResult& d = result.detection;
  const nlohmann::json doc = {{"input", args.in_path},
                              {"points", cloud.size()},
                              {"spacing_h", surface.spacing},
                              {"tracing_radius_r", result.radius},
                              {"convex_extreme", d.convex_extreme},
                              {"concave_extreme", d.concave_extreme},
                              {"ridge_threshold", d.ridge_threshold},
                              {"valley_threshold", d.valley_threshold},
                              {"ridge_points", d.ridge_points},
                              {"valley_points", d.valley_points},
                              {"border_points", boundary.border_points},
                              {"parameters", options::to_json(args.options)["features"]},
                              {"boundary_parameters", options::to_json(args.options)["boundary"]},
                              {"timings_s",
                               {{"detection", result.timings.detection},
                                {"tracing", result.timings.tracing},
                                {"joining", result.timings.joining}}},
                              {"lines", std::move(lines)}};
  TempFile temp(path);
  std::ofstream out(temp.path());
  out << doc.dump(1) << "\n";
  out.close();
  if (!out) throw Error(FileLoc{path, {}, {}}, "cannot write the lines JSON file");
  temp.commit();
}

/// -o and --lines checked before the input is read: writable, and two different files.
void check_outputs(const FeaturesArgs& args) {
  check_output_path("--output", args.out_path);
  if (args.lines_path.empty()) return;
  check_output_path("--lines", args.lines_path);
  if (same_file_key(args.lines_path) == same_file_key(args.out_path))
    throw OptionError("--lines", quote(args.lines_path) + " is also the --output file");
}

void run_features(const FeaturesArgs& args, const GlobalOptions& global) {
  // The flags shared with draw get draw's checks, before the input is read.
  validate(args.options);
  check_outputs(args);
  const ProgressFn progress = make_progress(global);
  io::ReadOptions read_options = args.read;
  read_options.progress = progress;
  check_full_resolution(read_options, args.in_path, point_bytes(args.options.surface, 1));
  io::ReadResult read = io::read_point_cloud(args.in_path, read_options);
  io::check_scale(read.cloud, args.in_path);
  validate_memory(point_bytes(args.options.surface, read.cloud.size()), args.options.max_memory_gb,
                  args.in_path + ": " + std::to_string(read.cloud.size()) + " points (--neighbours " +
                      std::to_string(args.options.surface.neighbourhood.k) + ")");
  // Per-point output of fewer points than the file holds must never pass unnoticed.
  if (read.decimation && !read.decimation->reason.starts_with("--"))
    read.warnings.push_back(std::to_string(read.points_in_file) + " points in the file, " +
                            std::to_string(read.cloud.size()) + " written: " + describe_reduction(read) +
                            "; --full-resolution keeps every point");
  print_warnings(global, read.warnings);
  PointCloud& cloud = read.cloud;
  differential::SurfaceOptions surface_options = args.options.surface;
  surface_options.progress = progress;
  const differential::Surface surface = differential::analyse_surface(cloud, surface_options);
  print_warnings(global, surface.warnings);
  features::RidgeValleyOptions features_options = args.options.features;
  features_options.progress = progress;
  const features::RidgeValleyLines result = features::extract_ridge_valley_lines(cloud, surface, features_options);
  print_warnings(global, result.warnings);
  features::BoundaryOptions boundary_options = args.options.boundary;
  boundary_options.progress = progress;
  const features::Boundary boundary = features::find_boundaries(cloud.positions, cloud.normals,
                                                                surface.neighbourhoods, surface.spacing,
                                                                boundary_options);

  // Written in the file's point order, so the scalar fields line up with the input cloud; outliers get label 3, the
  // points of a drawn border 4 (a ridge at a scan's edge is the edge), the points thinned on scan lines 5.
  PointCloud out = with_left_out(with_left_out(cloud, surface.outliers), surface.thinned);
  const std::size_t removed = surface.outliers.size();
  std::vector<float> k1 = surface.curvature.k1, k2 = surface.curvature.k2, ki = result.detection.feature_curvature;
  std::vector<std::uint8_t> labels(cloud.size());
  for (std::size_t i = 0; i < labels.size(); ++i)
    labels[i] = !boundary.border.empty() && boundary.border[i] == features::Boundary::kDrawnRim
                    ? kBorderLabel
                    : static_cast<std::uint8_t>(result.detection.labels[i]);
  for (std::vector<float>* values : {&k1, &k2, &ki}) values->resize(out.size(), 0.f);
  labels.resize(cloud.size() + removed, kOutlierLabel);
  labels.resize(out.size(), kThinnedLabel);
  k1 = in_file_order(k1, out.source_index);
  k2 = in_file_order(k2, out.source_index);
  ki = in_file_order(ki, out.source_index);
  labels = in_file_order(labels, out.source_index);
  if (!out.source_index.empty()) {
    std::vector<std::uint32_t> order(out.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
    permute(out, in_file_order(order, out.source_index));
  }
  io::PlyWriteOptions write{.format = args.ascii ? io::PlyFormat::Ascii : io::PlyFormat::BinaryLittleEndian};
  write.comments.push_back("pcsketch features " + args.in_path + ": k1 >= k2 principal curvatures (convex > 0), "
                           "k_feature = the one of larger magnitude, label 0 none 1 ridge 2 valley 3 outlier "
                           "(left out of the analysis) 4 border of an open scan 5 thinned on scan lines");
  io::write_ply(args.out_path, out,
                {{"k1", std::span<const float>(k1)},
                 {"k2", std::span<const float>(k2)},
                 {"k_feature", std::span<const float>(ki)},
                 {"label", std::span<const std::uint8_t>(labels)}},
                write);
  if (!args.lines_path.empty()) write_lines_json(args.lines_path, cloud, surface, result, boundary, args);

  std::size_t ridges = 0;
  for (const Polyline& l : result.lines) ridges += l.kind == LineKind::Ridge;
  std::printf("%zu points (%zu outliers left out, %zu thinned on scan lines), h = %g: %zu ridge points, %zu valley "
              "points; %zu ridge lines, %zu valley lines (%zu joins, %zu short lines dropped); %zu border points, %zu "
              "boundary lines\n",
              cloud.size(), removed, surface.thinned.size(), static_cast<double>(surface.spacing),
              result.detection.ridge_points,
              result.detection.valley_points, ridges, result.lines.size() - ridges, result.joins, result.dropped,
              boundary.border_points, boundary.lines.size());
  std::printf("detection %.3f s, tracing %.3f s, joining %.3f s\n", result.timings.detection, result.timings.tracing,
              result.timings.joining);
}

}  // namespace

void add_features_command(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<FeaturesArgs>();
  CLI::App* cmd = app.add_subcommand(
      "features", "Ridge/valley points and lines (paper IV.A): per-point k1, k2, label as PLY scalar fields, lines as JSON");
  cmd->add_option("IN", args->in_path, "Point cloud: PLY, LAS, XYZ/PTS/TXT/CSV, PCD, OFF or OBJ")->required();
  add_read_options(cmd, args->read);
  add_memory_option(cmd, args->options.max_memory_gb);
  cmd->add_option("-o,--output", args->out_path,
                  "Output PLY: x y z, nx ny nz, k1 k2 k_feature (float, 1/model units), label (uchar: 0 none, "
                  "1 ridge, 2 valley, 3 outlier left out of the analysis, 4 border of an open scan, 5 thinned on "
                  "scan lines); every point of the input, in its order")
      ->required();
  cmd->add_option("--lines", args->lines_path,
                  "Also write the ridge/valley and boundary polylines (world coordinates) as JSON");
  cmd->add_flag("--ascii", args->ascii, "Write ascii PLY instead of binary little-endian");

  add_analysis_flags(cmd, args->options);
  cmd->callback([args, &global] { run_features(*args, global); });
}

}  // namespace pcsketch::cli
