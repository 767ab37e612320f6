// pcsketch info FILE: what a cloud holds, where it lies, its mean spacing h, and how long reading took.

#include <chrono>
#include <cstdio>
#include <string>

#include "commands.h"
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

void run_info(const InfoArgs& args, const GlobalOptions& global) {
  const auto start = std::chrono::steady_clock::now();
  io::ReadResult r = io::read_point_cloud(args.path, args.read);
  const double read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  print_warnings(global, r.warnings);
  PointCloud& cloud = r.cloud;

  std::string attributes = "x y z";
  if (cloud.has_normals()) attributes += ", normals";
  if (cloud.has_colors()) attributes += ", colours";
  if (!r.other_attributes.empty()) {
    attributes += "; not kept:";
    for (const std::string& a : r.other_attributes) attributes += " " + a;
  }
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
  std::printf("attributes  %s\n", attributes.c_str());
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
  CLI::App* cmd =
      app.add_subcommand("info", "Point count, attributes, bounding box, mean spacing h, format, read time");
  cmd->add_option("FILE", args->path, "Point cloud: PLY, XYZ/PTS/TXT/CSV/ASC, PCD, OFF or OBJ")->required();
  cmd->add_flag("!--no-recentre", args->read.recentre,
                "Keep world coordinates as float positions instead of recentring far-away clouds on a double origin");
  cmd->add_option("--k", args->neighbourhoods.k, "Neighbours per point for the spacing estimate")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{1}, neighbourhood::kMaxNeighbours));
  cmd->callback([args, &global] { run_info(*args, global); });
}

}  // namespace pcsketch::cli
