#include "pcsketch/differential/surface.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "pcsketch/core/error.h"
#include "pcsketch/neighbourhood/spacing.h"
#include "pcsketch/neighbourhood/spatial_order.h"

namespace pcsketch::differential {

namespace {

/// Seconds spent in `step()`, added to `seconds`.
template <class Step>
auto timed(double& seconds, Step&& step) {
  const auto start = std::chrono::steady_clock::now();
  struct Stop {
    double& seconds;
    std::chrono::steady_clock::time_point start;
    ~Stop() { seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); }
  } stop{seconds, start};
  return step();
}

/// True if the cloud has at least 3 distinct positions (a linear scan that stops at the third).
bool has_three_distinct(const std::vector<Vec3f>& points) {
  if (points.empty()) return false;
  const Vec3f& a = points[0];
  const Vec3f* b = nullptr;
  for (const Vec3f& p : points) {
    if (p == a || (b && p == *b)) continue;
    if (b) return true;
    b = &p;
  }
  return false;
}

/// Normalises file normals; false if any is zero or not finite.
bool normalise(std::vector<Vec3f>& normals) {
  for (Vec3f& n : normals) {
    const float length = n.norm();
    if (!std::isfinite(length) || length < 1e-12f) return false;
    n /= length;
  }
  return true;
}

template <class Options>
Options with_progress(Options options, const ProgressFn& progress) {
  if (!options.progress) options.progress = progress;
  return options;
}

void append(Warnings& to, const Warnings& from) { to.insert(to.end(), from.begin(), from.end()); }

}  // namespace

Surface analyse_surface(PointCloud& cloud, const SurfaceOptions& options) {
  if (!has_three_distinct(cloud.positions))
    throw Error("surface analysis: the cloud has " + std::to_string(cloud.size()) +
                " points but fewer than 3 distinct positions; nothing to analyse");
  Surface surface;
  SurfaceTimings& t = surface.timings;
  if (options.reorder) timed(t.reorder, [&] { neighbourhood::reorder_spatially(cloud); });

  const neighbourhood::KdTree tree = timed(t.kd_tree, [&] { return neighbourhood::KdTree(cloud.positions); });
  surface.neighbourhoods = timed(t.neighbourhoods, [&] {
    return neighbourhood::compute_neighbourhoods(tree, cloud.positions,
                                                 with_progress(options.neighbourhood, options.progress));
  });
  surface.spacing = neighbourhood::mean_spacing(surface.neighbourhoods);

  bool estimate = options.recompute_normals || !cloud.has_normals();
  if (!estimate && !normalise(cloud.normals)) {
    surface.warnings.push_back("surface analysis: the file has zero or non-finite normals; all normals recomputed");
    estimate = true;
  }
  if (estimate) {
    NormalResult normals = timed(t.normals, [&] {
      return estimate_normals(cloud.positions, surface.neighbourhoods, with_progress(options.normals, options.progress));
    });
    cloud.normals = std::move(normals.normals);
    append(surface.warnings, normals.warnings);
    surface.normals_estimated = true;
  }
  bool orient = estimate || options.orient_file_normals;
  if (!orient) {
    const double disagreement = timed(t.orientation, [&] {
      return sign_disagreement(cloud.positions, cloud.normals, surface.neighbourhoods, options.orientation.criterion);
    });
    if (disagreement > options.file_normal_disagreement) {
      char percent[16];
      std::snprintf(percent, sizeof percent, "%.1f%%", 100.0 * disagreement);
      surface.warnings.push_back(std::string("surface analysis: the file's normals are not consistently oriented (") +
                                 percent + " of neighbour pairs disagree in sign); their signs were re-oriented");
      orient = true;
    }
  }
  if (orient) {
    const OrientResult orientation = timed(t.orientation, [&] {
      return orient_normals(cloud.positions, cloud.normals, surface.neighbourhoods,
                            with_progress(options.orientation, options.progress));
    });
    surface.components = orientation.components;
    append(surface.warnings, orientation.warnings);
  }

  surface.curvature = timed(t.curvature, [&] {
    return estimate_curvature(cloud.positions, cloud.normals, surface.neighbourhoods, tree,
                              with_progress(options.curvature, options.progress));
  });
  append(surface.warnings, surface.curvature.warnings);
  return surface;
}

}  // namespace pcsketch::differential
