#include "pcsketch/clean/outliers.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>
#include <utility>

#include "core/nth_value.h"
#include "core/parallel_chunks.h"
#include "core/smallest_eigenpair.h"
#include "core/union_find.h"
#include "pcsketch/core/error.h"

namespace pcsketch::clean {

namespace {

using pcsketch::detail::Clusters;

constexpr std::size_t kBlockPoints = 8192;  // consecutive (spatially sorted) points joined by one task
constexpr std::size_t kMedianSamples = 16384;  // points whose exact plane offsets give a noisy cloud's median

float median(const std::vector<float>& values) { return pcsketch::detail::nth_value(values, values.size() / 2); }

/// Mean offset from point i of its k nearest neighbours (the point itself not included).
Vec3d mean_offset(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& nbh, std::size_t i,
                  std::size_t k) {
  Vec3d mean = Vec3d::Zero();
  for (const std::uint32_t j : nbh.of(i).first(k)) mean += (points[j] - points[i]).cast<double>();
  return mean / static_cast<double>(k);
}

/// Scatter matrix of point i's k nearest neighbours about their mean, whose offset from i is `mean`.
Eigen::Matrix3d neighbour_scatter(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& nbh,
                                  std::size_t i, std::size_t k, const Vec3d& mean) {
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const std::uint32_t j : nbh.of(i).first(k)) {
    const Vec3d d = (points[j] - points[i]).cast<double>() - mean;
    covariance.noalias() += d * d.transpose();
  }
  return covariance;
}

/// Distance of point i from the PCA plane of its k nearest neighbours, whose mean offset from i is `mean`.
float plane_offset(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& nbh, std::size_t i,
                   std::size_t k, const Vec3d& mean) {
  const Eigen::Matrix3d covariance = neighbour_scatter(points, nbh, i, k, mean);
  double lambda0;
  Vec3d normal;
  if (pcsketch::detail::smallest_eigenpair(covariance, lambda0, normal))
    return static_cast<float>(std::abs(normal.dot(mean)));
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(covariance);
  if (!eigen.eigenvectors().allFinite()) return 0.f;
  return static_cast<float>(std::abs(eigen.eigenvectors().col(0).dot(mean)));
}

/// A float no smaller than plane_offset(i) for the same mean: |e · mean| <= |mean| for a unit e, and the margin
/// covers the rounding of e's length and of both casts to float.
float offset_bound(const Vec3d& mean) { return static_cast<float>(mean.norm() * (1 + 1e-6)); }

/// Each point's distance from its neighbours' plane, where it can matter: the off-surface limit is
/// max(`base_limit`, 6 × the median offset), so a point whose bound is within the limit is never off the surface and
/// keeps its bound, skipping the eigen solve. Where the bounds' median shows that the limit is `base_limit` (nearly
/// all points of a clean surface: their neighbours' mean lies well within 2 m), the limit is exact. Elsewhere (noisy
/// clouds: a point's own noise moves its mean) the median is taken over the exact offsets of every ⌊n/16384⌋-th
/// point (in space-filling-curve order): all of them cost a fifth of a noisy cloud's PCA solves, and a sample of
/// 16k gives the median within about 1%. Returns the limit; every entry is the exact offset where it exceeds the
/// limit, so that `offset[i] > limit` decides as the exact offsets do.
float off_surface_limit(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& nbh, std::size_t k,
                        float base_limit, const ProgressFn& progress, std::vector<float>& offset) {
  const std::size_t n = points.size();
  offset.resize(n);
  // The bounds' pass is cheap and reports nothing: one stage's fraction never starts again at 0.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) offset[i] = offset_bound(mean_offset(points, nbh, i, k));
  });
  const auto exact = [&](std::size_t i) { return plane_offset(points, nbh, i, k, mean_offset(points, nbh, i, k)); };
  // Each bound is at least its exact offset, so their median is at least the exact median.
  float limit = base_limit;
  if (!(6.f * median(offset) <= base_limit)) {
    const std::size_t stride = std::max<std::size_t>(1, n / kMedianSamples);
    std::vector<float> sampled((n + stride - 1) / stride);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, sampled.size(), 512), [&](const auto& r) {
      for (std::size_t j = r.begin(); j != r.end(); ++j) sampled[j] = exact(j * stride);
    });
    limit = std::max(base_limit, 6.f * median(sampled));
  }
  pcsketch::detail::parallel_chunks(n, progress, "outliers", [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i != end; ++i)
      if (!(offset[i] <= limit)) offset[i] = exact(i);
  });
  return limit;
}

/// Sparse points on a sheet of their k nearest (OutlierOptions::sheet_variation; k: the whole shared lists, 8
/// neighbours leave too many random samplings' sheets elongated): 1 for each, 0 elsewhere. Only the sparse points
/// are solved (none on most clouds).
std::vector<std::uint8_t> sparse_sheets(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& nbh,
                                        std::size_t k, const std::vector<float>& d, float dense_limit,
                                        float max_variation) {
  constexpr double kMinSpread = 0.05;  // share of the variance along the sheet's second axis: not a line of points
  constexpr double kMaxOffset = 0.25;  // the point's distance from the sheet, in its d_i
  std::vector<std::uint8_t> sheet(points.size(), 0);
  if (!(max_variation > 0) || k < 3) return sheet;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 4096), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      if (!(d[i] > dense_limit) || !std::isfinite(d[i])) continue;
      const Vec3d mean = mean_offset(points, nbh, i, k);
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
      eigen.computeDirect(neighbour_scatter(points, nbh, i, k, mean));
      const Eigen::Vector3d lambda = eigen.eigenvalues();  // ascending
      const double total = lambda.sum();
      sheet[i] = total > 0 && lambda[0] <= max_variation * total && lambda[1] >= kMinSpread * total &&
                 std::abs(eigen.eigenvectors().col(0).dot(mean)) <= kMaxOffset * d[i];
    }
  });
  return sheet;
}

/// The links of the cluster graph: dense points to their dense k-NN within `link`; a sparse point on a sheet to its
/// dense or sheet neighbours within link_factor × the smaller d of the two; another sparse point to its nearest
/// dense neighbour within `link` (border), or to none (isolated). Off-surface points have d = ∞: never linked.
struct Linking {
  const std::vector<float>& d;
  const std::vector<std::uint8_t>& sheet;
  const neighbourhood::Neighbourhoods& nbh;
  std::size_t k;
  float dense_limit, link_factor, link;

  /// Calls to(j) for each point j that i links to; whether i belongs to a cluster (dense, or linked).
  template <class To>
  bool links(std::size_t i, const To& to) const {
    const bool dense = d[i] <= dense_limit;
    bool attached = dense;
    const auto nb = nbh.of(i);
    const auto dist = nbh.distances_of(i);
    if (sheet[i]) {
      for (std::size_t a = 0; a < k; ++a) {
        const std::uint32_t j = nb[a];
        if ((d[j] <= dense_limit || sheet[j]) && dist[a] <= link_factor * std::min(d[i], d[j])) {
          to(j);
          attached = true;
        }
      }
      return attached;
    }
    for (std::size_t a = 0; a < k && dist[a] <= link && std::isfinite(d[i]); ++a) {
      if (d[nb[a]] > dense_limit) continue;
      to(nb[a]);
      attached = true;
      if (!dense) break;  // a border point joins its nearest dense neighbour only
    }
    return attached;
  }
};

/// The clusters: each block of points joins its inner links in parallel, and counts its attached points by block
/// root; the links between blocks are joined after, serially, and only block roots are resolved to the final roots
/// (the smallest index of each set, whatever the order of joins). Returns the attached count of each final root
/// (0 elsewhere); `root` becomes each point's block root, whose parent in `clusters` is the final root.
std::vector<std::uint32_t> cluster_sizes(const Linking& linking, Clusters& clusters, std::vector<std::uint8_t>& attached,
                                         std::vector<std::uint32_t>& root) {
  const std::size_t n = attached.size(), blocks = (n + kBlockPoints - 1) / kBlockPoints;
  std::vector<std::uint32_t> size(n, 0);
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> crossing(blocks);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    const std::size_t first = b * kBlockPoints, last = std::min(n, first + kBlockPoints);
    for (std::size_t i = first; i < last; ++i) {
      const auto from = static_cast<std::uint32_t>(i);
      attached[i] = linking.links(i, [&](std::uint32_t j) {
        if (j >= first && j < last) clusters.join(from, j);
        else crossing[b].emplace_back(from, j);
      });
    }
    for (std::size_t i = first; i < last; ++i) {
      root[i] = clusters.find(static_cast<std::uint32_t>(i));
      size[root[i]] += attached[i];
    }
  });
  for (const auto& list : crossing)
    for (const auto& [a, b] : list) clusters.join(a, b);
  // Ascending, so a final root (the smallest of its set) holds its own count when the later block roots add theirs.
  for (std::uint32_t r = 0; r < n; ++r) {
    if (root[r] != r) continue;
    clusters.parent[r] = clusters.find(r);
    if (clusters.parent[r] != r) size[clusters.parent[r]] += std::exchange(size[r], 0);
  }
  return size;
}

/// Marks the points of no cluster, and those of clusters below the minimum size.
void mark_small_clusters(const Linking& linking, const OutlierOptions& options, OutlierResult& result) {
  const std::size_t n = result.outlier.size();
  Clusters clusters(n);
  std::vector<std::uint8_t> attached(n, 0);
  std::vector<std::uint32_t> root(n);
  const std::vector<std::uint32_t> size = cluster_sizes(linking, clusters, attached, root);
  // The largest cluster is the surface whatever its size (a small cloud is still a cloud).
  const auto minimum = std::min<std::size_t>(
      *std::max_element(size.begin(), size.end()),
      std::max<std::size_t>(options.min_cluster,
                            static_cast<std::size_t>(options.min_cluster_fraction * static_cast<double>(n))));
  using Counts = std::pair<std::size_t, std::size_t>;  // isolated, clustered
  const Counts counts = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, 16384), Counts{0, 0},
      [&](const tbb::blocked_range<std::size_t>& r, Counts c) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const bool isolated = !attached[i];
          const bool clustered = !isolated && size[clusters.parent[root[i]]] < minimum;
          result.outlier[i] = isolated || clustered;
          c.first += isolated;
          c.second += clustered;
        }
        return c;
      },
      [](Counts a, const Counts& b) { return Counts{a.first + b.first, a.second + b.second}; });
  result.isolated = counts.first;
  result.clustered = counts.second;
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
    std::vector<float> offset;
    const float off_limit = off_surface_limit(points, nbh, k, options.offset_factor * m, options.progress, offset);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i)
        if (offset[i] > off_limit) d[i] = std::numeric_limits<float>::infinity();
    });
  }

  const std::vector<std::uint8_t> sheet = sparse_sheets(points, nbh, nbh.k, d, dense_limit, options.sheet_variation);
  const Linking linking{d, sheet, nbh, k, dense_limit, options.link_factor, link};
  mark_small_clusters(linking, options, result);
  return result;
}

}  // namespace pcsketch::clean
