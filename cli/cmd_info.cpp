// pcsketch info FILE: what a cloud holds, where it lies, its mean spacing h, and how long reading took.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <string>

#include "commands.h"
#include "options.h"
#include "pcsketch/core/error.h"
#include "pcsketch/io/read_cloud.h"
#include "pcsketch/neighbourhood/kd_tree.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"
#include "pcsketch/neighbourhood/spacing.h"
#include "pcsketch/neighbourhood/spatial_order.h"

namespace pcsketch::cli {
namespace {

struct InfoArgs {
  std::string path;
  io::ReadOptions read;
  /// h needs only each point's nearest distinct neighbour: 6 neighbours skip up to 5 duplicates of a point at a
  /// third of the cost of the pipeline's 16.
  neighbourhood::NeighbourhoodOptions neighbourhoods{.k = 6};
};

// Smallest and largest of `values`.
std::string range_of(const std::vector<float>& values) {
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  char text[64];
  std::snprintf(text, sizeof text, "%g .. %g", static_cast<double>(*lo), static_cast<double>(*hi));
  return text;
}

// "2: 1200 (60%), 6: 800 (40%)": how many points of each class, to choose --classes and --drop-classes.
std::string histogram_of(const std::vector<float>& values) {
  std::map<float, std::size_t> counts;
  for (const float v : values) ++counts[v];
  std::string out;
  for (const auto& [value, count] : counts) {
    char text[64];
    std::snprintf(text, sizeof text, "%s%g: %zu (%.1f%%)", out.empty() ? "" : ", ", static_cast<double>(value), count,
                  100.0 * static_cast<double>(count) / static_cast<double>(values.size()));
    out += text;
  }
  return out;
}

// One line per per-point array besides the positions, with its range.
void print_attributes(const io::ReadResult& r) {
  const PointCloud& cloud = r.cloud;
  if (cloud.has_normals()) std::printf("  normals         unit vectors\n");
  if (cloud.has_colors()) {
    static constexpr const char* kChannel[] = {"red", "green", "blue"};
    for (std::size_t c = 0; c < 3; ++c) {
      std::vector<float> channel(cloud.size());
      for (std::size_t i = 0; i < cloud.size(); ++i) channel[i] = cloud.colors[i][c];
      std::printf("  %-15s %s\n", kChannel[c], range_of(channel).c_str());
    }
  }
  for (const PointAttribute& a : cloud.attributes) {
    const std::string text = a.name == "classification" ? histogram_of(a.values) : range_of(a.values);
    std::printf("  %-15s %s\n", a.name.c_str(), text.c_str());
  }
}

void run_info(const InfoArgs& args, const GlobalOptions& global) {
  // The neighbour lists of the spacing estimate: an index and a distance per neighbour.
  check_full_resolution(args.read, args.path, 8.0 * static_cast<double>(args.neighbourhoods.k));
  const auto start = std::chrono::steady_clock::now();
  io::ReadResult r = io::read_point_cloud(args.path, args.read);
  const double read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  print_warnings(global, r.warnings);
  PointCloud& cloud = r.cloud;

  std::string attributes = "x y z";
  if (cloud.has_normals()) attributes += ", normals";
  if (cloud.has_colors()) attributes += ", colours";
  for (const PointAttribute& a : cloud.attributes) attributes += ", " + a.name;
  std::string not_kept;
  for (const std::string& a : r.other_attributes) not_kept += (not_kept.empty() ? "" : ", ") + a;
  const Box3f box = bounding_box(cloud.positions);
  const Vec3d lo = cloud.origin + box.min.cast<double>(), hi = cloud.origin + box.max.cast<double>();

  neighbourhood::NeighbourhoodOptions nb = args.neighbourhoods;
  nb.progress = make_progress(global);
  // Spatial order first: neighbours close in memory make the queries cache-friendly.
  neighbourhood::reorder_spatially(cloud);
  const neighbourhood::KdTree tree(cloud.positions);
  const float h = neighbourhood::mean_spacing(neighbourhood::compute_neighbourhoods(tree, cloud.positions, nb));

  std::printf("file        %s\n", one_line(args.path).c_str());
  std::printf("format      %s\n", r.format.c_str());
  std::printf("points      %zu (%zu in the file, %zu dropped as non-finite, %zu exact duplicates)\n", cloud.size(),
              r.points_in_file, r.dropped_non_finite, r.duplicates);
  if (!r.columns.empty()) std::printf("columns     %s\n", r.columns.c_str());
  std::printf("attributes  %s\n", attributes.c_str());
  print_attributes(r);
  if (!not_kept.empty()) std::printf("not kept    %s\n", not_kept.c_str());
  const std::string reduction = describe_reduction(r);
  if (!reduction.empty()) std::printf("reduced     %s\n", reduction.c_str());
  std::printf("origin      %.6f %.6f %.6f\n", cloud.origin.x(), cloud.origin.y(), cloud.origin.z());
  std::printf("bbox min    %.6f %.6f %.6f\n", lo.x(), lo.y(), lo.z());
  std::printf("bbox max    %.6f %.6f %.6f\n", hi.x(), hi.y(), hi.z());
  std::printf("bbox diag   %.6g\n", static_cast<double>(box.diagonal()));
  if (h > 0.f) {
    std::printf("spacing h   %.6g (mean nearest-neighbour distance)\n", static_cast<double>(h));
  } else {
    std::printf("spacing h   undefined (fewer than 2 distinct points)\n");
  }
  std::printf("read time   %.3f s\n", read_seconds);
}

}  // namespace

void add_info_command(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* cmd = app.add_subcommand(
      "info", "Point count, attributes and their ranges, bounding box, mean spacing h, format, read time");
  cmd->add_option("FILE", args->path, "Point cloud: PLY, LAS, XYZ/PTS/TXT/CSV/ASC, PCD, OFF or OBJ")->required();
  add_read_options(cmd, args->read);
  cmd->add_flag("!--no-recentre", args->read.recentre,
                "Keep world coordinates as float positions instead of recentring far-away clouds on a double origin");
  cmd->add_option("--k", args->neighbourhoods.k, "Neighbours per point for the spacing estimate")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{1}, neighbourhood::kMaxNeighbours));
  cmd->callback([args, &global] { run_info(*args, global); });
}

}  // namespace pcsketch::cli
