#include "pcsketch/core/point_cloud.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <numeric>

#include "pcsketch/core/assert.h"
#include "pcsketch/core/polyline.h"

namespace pcsketch {

Box3f bounding_box(const std::vector<Vec3f>& positions) {
  // In parallel: min and max are exact, and each part's box joins the one before it in order, by the same
  // comparisons as the serial loop, so the box is that loop's for any split (even where -0 meets +0).
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, positions.size(), 16384), Box3f{},
      [&](const tbb::blocked_range<std::size_t>& r, Box3f box) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) box.extend(positions[i]);
        return box;
      },
      [](Box3f before, const Box3f& after) {
        before.min = before.min.cwiseMin(after.min);
        before.max = before.max.cwiseMax(after.max);
        return before;
      });
}

namespace {
template <class T>
void apply_order(std::vector<T>& values, const std::vector<std::uint32_t>& order) {
  if (values.empty()) return;
  std::vector<T> out(order.size());
  // A gather of scattered reads: in parallel, each slot written once.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size(), 16384),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) out[i] = values[order[i]];
                    });
  values.swap(out);
}
}  // namespace

void permute(PointCloud& cloud, const std::vector<std::uint32_t>& order) {
  PCS_ASSERT(order.size() == cloud.size(), "permutation size must match the cloud");
  select(cloud, order);
}

void select(PointCloud& cloud, const std::vector<std::uint32_t>& order) {
  for (const std::uint32_t i : order) PCS_ASSERT(i < cloud.size(), "selected index out of range");
  if (cloud.source_index.empty()) {
    cloud.source_index.resize(cloud.size());
    std::iota(cloud.source_index.begin(), cloud.source_index.end(), 0u);
  }
  keep_points(cloud, order);
}

void keep_points(PointCloud& cloud, const std::vector<std::uint32_t>& kept) {
  PCS_ASSERT(kept.size() <= cloud.size(), "cannot keep more points than the cloud holds");
  apply_order(cloud.positions, kept);
  apply_order(cloud.normals, kept);
  apply_order(cloud.colors, kept);
  for (PointAttribute& a : cloud.attributes) apply_order(a.values, kept);
  apply_order(cloud.source_index, kept);
}

std::string_view to_string(LineKind kind) {
  switch (kind) {
    case LineKind::Contour: return "contour";
    case LineKind::Ridge: return "ridge";
    case LineKind::Valley: return "valley";
    case LineKind::Hatch: return "hatch";
    case LineKind::Boundary: return "boundary";
  }
  return "unknown";
}

float Polyline::length() const {
  float total = 0.f;
  for (std::size_t i = 1; i < points.size(); ++i) total += (points[i] - points[i - 1]).norm();
  if (closed && points.size() > 2) total += (points.front() - points.back()).norm();
  return total;
}

void Polyline::reverse() {
  std::reverse(points.begin(), points.end());
  std::reverse(curvature.begin(), curvature.end());
  std::reverse(point_index.begin(), point_index.end());
}

void Polyline::append(Polyline&& other) {
  const std::size_t n = size();
  points.insert(points.end(), other.points.begin(), other.points.end());
  if (curvature.size() == n && other.curvature.size() == other.size())
    curvature.insert(curvature.end(), other.curvature.begin(), other.curvature.end());
  else
    curvature.clear();
  if (point_index.size() == n && other.point_index.size() == other.size())
    point_index.insert(point_index.end(), other.point_index.begin(), other.point_index.end());
  else
    point_index.clear();
}

}  // namespace pcsketch
