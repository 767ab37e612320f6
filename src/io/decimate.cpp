// Voxel thinning: the point nearest each occupied cell's centre, found by one sort of (cell, distance, index).

#include "pcsketch/io/decimate.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>
#include <tuple>

#include "pcsketch/core/error.h"

namespace pcsketch::io {
namespace {

using Cell = std::array<std::int64_t, 3>;

struct Candidate {
  Cell cell;
  double distance2;               ///< to the cell's centre
  std::array<float, 3> position;  ///< ties in distance: the smallest position, so that the input order does not matter
  std::uint32_t index;
  bool operator<(const Candidate& o) const {
    return std::tie(cell, distance2, position, index) < std::tie(o.cell, o.distance2, o.position, o.index);
  }
};

// Positions relative to the box minimum in double, so that the grid does not depend on the cloud's origin.
std::vector<Candidate> candidates(const PointCloud& cloud, double cell) {
  const Box3f box = bounding_box(cloud.positions);
  const Vec3d lo = box.min.cast<double>();
  std::vector<Candidate> out(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Vec3d q = (cloud.positions[i].cast<double>() - lo) / cell;
    Candidate& c = out[i];
    for (int a = 0; a < 3; ++a) c.cell[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(std::floor(q[a]));
    const Vec3d centre(double(c.cell[0]) + 0.5, double(c.cell[1]) + 0.5, double(c.cell[2]) + 0.5);
    c.distance2 = (q - centre).squaredNorm();
    c.position = {cloud.positions[i].x(), cloud.positions[i].y(), cloud.positions[i].z()};
    c.index = static_cast<std::uint32_t>(i);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The first candidate of each cell, in the cloud's order.
std::vector<std::uint32_t> representatives(const PointCloud& cloud, double cell) {
  const std::vector<Candidate> sorted = candidates(cloud, cell);
  std::vector<std::uint32_t> kept;
  for (std::size_t i = 0; i < sorted.size(); ++i)
    if (i == 0 || sorted[i].cell != sorted[i - 1].cell) kept.push_back(sorted[i].index);
  std::sort(kept.begin(), kept.end());
  return kept;
}

// The smallest cell (to 1 part in 1000) that leaves at most `max_points`, by bisection on a log scale: the count
// falls as the cell grows, and one cell as large as the box leaves at most 8 points.
double cell_for(const PointCloud& cloud, std::size_t max_points) {
  const double extent = std::max(static_cast<double>(bounding_box(cloud.positions).size().maxCoeff()), 1e-30);
  double lo = extent * 1e-7, hi = extent;
  if (representatives(cloud, lo).size() <= max_points) return lo;
  while (hi / lo > 1.001) {
    const double mid = std::sqrt(lo * hi);
    (representatives(cloud, mid).size() <= max_points ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace

std::vector<std::uint32_t> voxel_representatives(const PointCloud& cloud, double cell) {
  if (!(cell > 0) || !std::isfinite(cell)) throw Error("decimate: the cell edge must be positive");
  return representatives(cloud, cell);
}

double resolution_cell(const OutputResolution& r, const Vec3d& extent) {
  std::array<double, 3> sides{extent.x(), extent.y(), extent.z()};
  std::sort(sides.begin(), sides.end());
  double pixel = sides[1] / static_cast<double>(std::max({r.width, r.height, 1}));
  if (r.perspective) {
    // Default framing: the eye at R / sin(fov/2) from the centre, the focal length from the height; the nearest
    // point is at least R / sin(fov/2) - R deep. R from the robust box is at most the framed box's.
    const double half = 0.5 * r.fov_deg * 3.14159265358979323846 / 180.0;
    const double radius = 0.5 * extent.norm();
    pixel = 2.0 * radius * (1.0 / std::sin(half) - 1.0) * std::tan(half) / static_cast<double>(std::max(r.height, 1));
  }
  return r.cell_pixels * pixel;
}

DecimateReport decimate(PointCloud& cloud, const DecimateOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.voxel && !(*options.voxel > 0.0 && std::isfinite(*options.voxel)))
    throw Error("decimate: the voxel size must be a positive number, not " + std::to_string(*options.voxel));
  if (options.max_points && *options.max_points < 8)
    throw Error("decimate: max_points must be at least 8 (one cell as large as the cloud may keep 8 points)");
  DecimateReport report;
  report.points_before = cloud.size();
  double cell = options.voxel.value_or(0.0);
  if (options.max_points && cloud.size() > *options.max_points)
    cell = std::max(cell, cell_for(cloud, *options.max_points));
  if (cell > 0.0 && !cloud.empty()) {
    keep_points(cloud, representatives(cloud, cell));
    report.cell = cell;
  }
  report.points_after = cloud.size();
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace pcsketch::io
