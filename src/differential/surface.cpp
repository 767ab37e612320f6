#include "pcsketch/differential/surface.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "core/progress.h"
#include "faces.h"
#include "pcsketch/core/error.h"
#include "pcsketch/io/decimate.h"
#include "pcsketch/neighbourhood/spacing.h"
#include "pcsketch/neighbourhood/spatial_order.h"

namespace pcsketch::differential {

namespace {

using pcsketch::detail::with_progress;

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

/// The tree of `points` and their neighbourhoods (the tree builds itself only when a query needs it).
neighbourhood::Neighbourhoods index_neighbourhoods(const std::vector<Vec3f>& points,
                                                   std::optional<neighbourhood::KdTree>& tree, SurfaceTimings& t,
                                                   const SurfaceOptions& options) {
  return timed(t.neighbourhoods, [&] {
    return neighbourhood::index_neighbourhoods(points, tree, with_progress(options.neighbourhood, options.progress));
  });
}

void append(Warnings& to, const Warnings& from) { to.insert(to.end(), from.begin(), from.end()); }

/// Moves the points flagged in `out` from `cloud` to the returned cloud (both keep their order).
PointCloud split_off(PointCloud& cloud, const std::vector<std::uint8_t>& out) {
  std::vector<std::uint32_t> kept, removed;
  for (std::uint32_t i = 0; i < cloud.size(); ++i) (out[i] ? removed : kept).push_back(i);
  PointCloud split = cloud;
  select(split, removed);
  select(cloud, kept);
  return split;
}

/// Thins a cloud that lies on scan lines (clean::find_scan_lines) to one point per cube of a fraction of the lines'
/// spacing, the points left out moved to surface.thinned, and recomputes the tree and neighbourhoods of what is left.
void thin_scan_lines(PointCloud& cloud, Surface& surface, std::optional<neighbourhood::KdTree>& tree,
                     const SurfaceOptions& options) {
  SurfaceTimings& t = surface.timings;
  surface.scan_lines = timed(t.scan_lines, [&] {
    return clean::find_scan_lines(cloud.positions, surface.neighbourhoods, *tree, options.scan_lines);
  });
  if (!surface.scan_lines.found()) return;
  const std::size_t before = cloud.size();
  const double cell = options.scan_lines.cell_factor * surface.scan_lines.spacing;
  timed(t.scan_lines, [&] {
    std::vector<std::uint8_t> out(cloud.size(), 1);
    for (const std::uint32_t i : io::voxel_representatives(cloud, cell)) out[i] = 0;
    surface.thinned = split_off(cloud, out);
  });
  char message[320];
  std::snprintf(message, sizeof message,
                "surface analysis: the points lie on scan lines %g apart, %.0f times their spacing along them (%.0f%% "
                "of the neighbourhoods): thinned to one point per cube of edge %g, %zu of %zu points kept "
                "(--keep-scan-lines keeps them all)",
                surface.scan_lines.spacing, surface.scan_lines.anisotropy, 100.0 * surface.scan_lines.line_fraction,
                cell, cloud.size(), before);
  surface.warnings.emplace_back(message);
  surface.neighbourhoods = index_neighbourhoods(cloud.positions, tree, surface.timings, options);
}

/// Moves the outliers of `cloud` to surface.outliers and updates the tree and neighbourhoods for what is left (only
/// when there are outliers: a clean cloud keeps the ones it has).
void remove_outliers(PointCloud& cloud, Surface& surface, std::optional<neighbourhood::KdTree>& tree,
                     const SurfaceOptions& options) {
  SurfaceTimings& t = surface.timings;
  const clean::OutlierResult found =
      timed(t.outliers, [&] {
        return clean::find_outliers(cloud.positions, surface.neighbourhoods,
                                    with_progress(options.outliers, options.progress));
      });
  if (found.removed() == 0) return;
  timed(t.outliers, [&] { surface.outliers = split_off(cloud, found.outlier); });
  surface.isolated_outliers = found.isolated;
  surface.clustered_outliers = found.clustered;
  surface.neighbourhoods = timed(t.neighbourhoods, [&] {
    return neighbourhood::neighbourhoods_after_removal(surface.neighbourhoods, found.outlier, cloud.positions, tree,
                                                       with_progress(options.neighbourhood, options.progress));
  });
}

/// The part of the normals' angular spread (normal_noise) that noise can explain. A sparse cloud's neighbours spread
/// unevenly around a point, so their normals differ by the surface's bending, which normal_noise then reads as noise
/// (0.10–0.18 rad on 2k-point samples and coarse mesh vertices, against under 0.01 on dense clean samples); the
/// contours' persistence rule would then drop real rims. Noise σ tilts a PCA normal over k ≈ 16 neighbours within
/// R ≈ 2.3 h by about 2σ / (R √k) ≈ 0.22 σ/h, and σ̂ (estimate_noise) separates noise from shape misfit.
float noise_tilt(float measured, const Surface& surface, const DenoiseResult& denoised) {
  constexpr float kTiltPerNoise = 0.25f;           // radians per σ̂/h
  if (!denoised.noise_estimated) return measured;  // nothing separates noise from bending then
  return std::min(measured, kTiltPerNoise * denoised.noise_before / surface.spacing);
}

}  // namespace

Surface analyse_surface(PointCloud& cloud, const SurfaceOptions& options,
                        std::optional<neighbourhood::KdTree>* tree_out) {
  if (!has_three_distinct(cloud.positions))
    throw Error("surface analysis: the cloud has " + std::to_string(cloud.size()) +
                " points but fewer than 3 distinct positions; nothing to analyse");
  Surface surface;
  SurfaceTimings& t = surface.timings;
  if (options.reorder) {
    const ProgressReporter report(options.progress, "reorder");
    report(0.0);
    timed(t.reorder, [&] { neighbourhood::reorder_spatially(cloud); });
    report(1.0);
  }

  std::optional<neighbourhood::KdTree> tree;
  ProgressReporter(options.progress, "neighbourhoods")(0.0);  // the grid's build is part of the stage
  surface.neighbourhoods = index_neighbourhoods(cloud.positions, tree, t, options);
  thin_scan_lines(cloud, surface, tree, options);
  remove_outliers(cloud, surface, tree, options);
  bool estimate = options.recompute_normals || !cloud.has_normals();
  if (!estimate && !normalise(cloud.normals)) {
    surface.warnings.push_back("surface analysis: the file has zero or non-finite normals; all normals recomputed");
    estimate = true;
  }
  std::optional<NormalResult> pca;
  // The spacing's select and sum are serial (their order sets the sum's last bits): beside the normals, which do
  // not read it.
  tbb::parallel_invoke([&] { surface.spacing = neighbourhood::mean_spacing(surface.neighbourhoods); },
                       [&] {
                         if (estimate)
                           pca = timed(t.normals, [&] {
                             return estimate_normals(cloud.positions, surface.neighbourhoods,
                                                     with_progress(options.normals, options.progress));
                           });
                       });
  // A thin part's lists reach its other face: from here on they hold the point's own face (docs/geometry.md).
  if (estimate && !pca->own_face.empty())
    surface.own_face_lists = timed(t.normals, [&] {
      return detail::separate_faces(cloud.positions, pca->normals, pca->own_face, surface.neighbourhoods);
    });
  // The curvature fits the raw points: denoising leaves its error correlated over a few h, which a quadric sees as
  // shape; the raw noise is independent, and the fit widens until it averages out.
  // Its frames are the raw points' normals too: at a crease they bisect the two faces, where the height field of a
  // quadric fits the fold; the filtered normal of one face turns the other into a wall (a noisy cube's edges were
  // traced over 69–89% of their length instead of ≥ 90%).
  // So the points move in a copy, and the raw ones stay where the tree indexes them until the curvature is done.
  // Where a group's wide support holds a crease, though, its points are fitted over their shared neighbours in the
  // copy: the bilateral filter kept the crease sharp there, and the wide raw fits had placed crests off the edges.
  std::vector<Vec3f> moved, raw_normals;
  DenoiseResult denoised;
  if (options.denoise.enabled) {
    moved = cloud.positions;
    raw_normals = estimate ? pca->normals : cloud.normals;
    denoised = timed(t.denoise, [&] {
      return denoise(moved, surface.neighbourhoods, surface.spacing, raw_normals,
                     with_progress(options.denoise, options.progress));
    });
  }
  surface.input_noise = denoised.noise_before;
  if (denoised.applied) {
    surface.denoised = true;
    if (!estimate) {
      // The filtered directions, with the file's signs: the file knows the orientation, the filter the direction.
      for (std::size_t i = 0; i < cloud.size(); ++i)
        if (denoised.normals[i].dot(cloud.normals[i]) < 0) denoised.normals[i] = -denoised.normals[i];
    }
    cloud.normals = std::move(denoised.normals);
  } else if (estimate) {
    cloud.normals = std::move(pca->normals);
  }
  const std::vector<Vec3f>& positions = surface.denoised ? moved : cloud.positions;
  if (estimate) {
    append(surface.warnings, pca->warnings);
    surface.normals_estimated = true;
  }
  bool orient = estimate || options.orient_file_normals;
  if (!orient) {
    const double disagreement = timed(t.orientation, [&] {
      return sign_disagreement(positions, cloud.normals, surface.neighbourhoods, options.orientation.criterion,
                               denoised.noise_before);
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
      return orient_normals(positions, cloud.normals, surface.neighbourhoods,
                            with_progress(options.orientation, options.progress), denoised.noise_before);
    });
    surface.components = orientation.components;
    append(surface.warnings, orientation.warnings);
  }

  surface.normal_noise = noise_tilt(normal_noise(cloud.normals, surface.neighbourhoods), surface, denoised);
  if (surface.denoised)
    for (std::size_t i = 0; i < cloud.size(); ++i)
      if (raw_normals[i].dot(cloud.normals[i]) < 0) raw_normals[i] = -raw_normals[i];  // the orientation's signs
  surface.curvature = timed(t.curvature, [&] {
    return estimate_curvature(cloud.positions, surface.denoised ? raw_normals : cloud.normals, surface.neighbourhoods,
                              *tree, with_progress(options.curvature, options.progress),
                              surface.denoised ? DenoisedCopy{&moved, &cloud.normals} : DenoisedCopy{});
  });
  append(surface.warnings, surface.curvature.warnings);
  if (surface.denoised) cloud.positions = std::move(moved);  // the tree indexes the raw points: dropped
  else if (tree_out) *tree_out = std::move(tree);
  return surface;
}

}  // namespace pcsketch::differential
