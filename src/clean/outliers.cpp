#include "pcsketch/clean/outliers.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <nlohmann/json.hpp>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/parallel_chunks.h"
#include "core/union_find.h"
#include "pcsketch/core/error.h"

namespace pcsketch::clean {

namespace {

using pcsketch::detail::Clusters;

float median(std::vector<float> values) {
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

/// Distance of point i from the PCA plane of its k nearest neighbours (the point itself not included).
float plane_offset(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& nbh, std::size_t i,
                   std::size_t k) {
  Vec3d mean = Vec3d::Zero();
  for (const std::uint32_t j : nbh.of(i).first(k)) mean += (points[j] - points[i]).cast<double>();
  mean /= static_cast<double>(k);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const std::uint32_t j : nbh.of(i).first(k)) {
    const Vec3d d = (points[j] - points[i]).cast<double>() - mean;
    covariance.noalias() += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(covariance);
  if (!eigen.eigenvectors().allFinite()) return 0.f;
  return static_cast<float>(std::abs(eigen.eigenvectors().col(0).dot(mean)));
}

}  // namespace

OutlierResult find_outliers(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& nbh,
                            const OutlierOptions& options) {
  const std::size_t n = points.size();
  if (nbh.size() != n && !(n <= 1 && nbh.k == 0))
    throw Error("outliers: the neighbourhoods cover " + std::to_string(nbh.size()) + " points but the cloud has " +
                std::to_string(n));
  OutlierResult result;
  result.outlier.assign(n, 0);
  const std::size_t k = std::min(options.k, nbh.k);
  if (!options.enabled || k == 0 || n < 2) return result;

  std::vector<float> d(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const auto dist = nbh.distances_of(i).first(k);
      d[i] = std::accumulate(dist.begin(), dist.end(), 0.f) / static_cast<float>(k);
    }
  });
  const float m = median(d);
  result.median_distance = m;
  if (!(m > 0)) return result;  // mostly duplicates: nothing to compare with
  const float dense_limit = options.density_factor * m, link = options.link_factor * m;
  // Off-surface points count as sparse: they may neither be dense nor lend a border point their cluster.
  if (k >= 3) {
    std::vector<float> offset(n);
    pcsketch::detail::parallel_chunks(n, options.progress, "outliers", [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i != end; ++i) offset[i] = plane_offset(points, nbh, i, k);
    });
    const float off_limit = std::max(options.offset_factor * m, 6.f * median(offset));
    for (std::size_t i = 0; i < n; ++i)
      if (offset[i] > off_limit) d[i] = std::numeric_limits<float>::infinity();
  }

  // Dense points linked to their dense k-NN within `link`; a sparse point joins the cluster of its nearest dense
  // neighbour within `link` (border), or stays alone (isolated).
  Clusters clusters(n);
  std::vector<std::uint8_t> attached(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const bool dense = d[i] <= dense_limit;
    attached[i] = dense;
    const auto nb = nbh.of(i);
    const auto dist = nbh.distances_of(i);
    for (std::size_t a = 0; a < k && dist[a] <= link && std::isfinite(d[i]); ++a) {
      const std::uint32_t j = nb[a];
      if (d[j] > dense_limit) continue;
      clusters.join(static_cast<std::uint32_t>(i), j);
      attached[i] = 1;
      if (!dense) break;  // a border point joins its nearest dense neighbour only
    }
  }
  std::vector<std::uint32_t> size(n, 0);
  for (std::size_t i = 0; i < n; ++i) size[clusters.find(static_cast<std::uint32_t>(i))] += attached[i];
  // The largest cluster is the surface whatever its size (a small cloud is still a cloud).
  const auto minimum = std::min<std::size_t>(
      *std::max_element(size.begin(), size.end()),
      std::max<std::size_t>(options.min_cluster,
                            static_cast<std::size_t>(options.min_cluster_fraction * static_cast<double>(n))));
  for (std::size_t i = 0; i < n; ++i) {
    if (!attached[i]) {
      result.outlier[i] = 1;
      ++result.isolated;
    } else if (size[clusters.find(static_cast<std::uint32_t>(i))] < minimum) {
      result.outlier[i] = 1;
      ++result.clustered;
    }
  }
  return result;
}

}  // namespace pcsketch::clean
