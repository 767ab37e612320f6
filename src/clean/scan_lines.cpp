#include "pcsketch/clean/scan_lines.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "pcsketch/core/error.h"

namespace pcsketch::clean {

namespace {

/// Neighbours whose PCA tells a line: on 4:1 scan lines the nearest 8 still lie on the point's own line.
constexpr std::size_t kLineNeighbours = 8;
/// Neighbours searched first for the nearest point off a line (20:1 lines put it about 40th).
constexpr std::size_t kAcross = 64;

/// λ2/λ1 of the covariance of point i and its nearest kLineNeighbours, and the principal direction.
double linearity(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& nbh, std::size_t i,
                 Vec3d& direction) {
  const auto near = nbh.of(i).first(std::min(kLineNeighbours, nbh.k));
  Vec3d mean = points[i].cast<double>();
  for (const std::uint32_t j : near) mean += points[j].cast<double>();
  mean /= static_cast<double>(near.size() + 1);
  Eigen::Matrix3d c = (points[i].cast<double>() - mean) * (points[i].cast<double>() - mean).transpose();
  for (const std::uint32_t j : near) {
    const Vec3d d = points[j].cast<double>() - mean;
    c += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(c);
  direction = eig.eigenvectors().col(2);
  const double largest = eig.eigenvalues()[2];
  return largest > 0 ? eig.eigenvalues()[1] / largest : 1.0;
}

/// Point i lies on a scan line (its nearest kLineNeighbours make a line, direction t) next to a parallel one: the
/// nearest point more than 60° off t has a line neighbourhood within 25° of t. Returns the distance to that point,
/// -1 where i is on no line, 0 on a line with no parallel neighbour (a wire, an edge) among its nearest kAcross (or,
/// on lines so far apart that none is off the line, 4 kAcross).
double across(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& nbh,
              const neighbourhood::KdTree& tree, std::size_t i, float max_linearity, std::vector<std::uint32_t>& found,
              std::vector<float>& distances) {
  Vec3d t, u;
  if (!(linearity(points, nbh, i, t) < max_linearity)) return -1;
  for (const std::size_t k : {kAcross, 4 * kAcross}) {
    tree.knn_of_point(i, std::min(k, points.size() - 1), found, distances);
    for (std::size_t m = 0; m < found.size(); ++m) {
      const Vec3d d = (points[found[m]] - points[i]).cast<double>();
      if (!(distances[m] > 0 && std::abs(d.dot(t)) < 0.5 * d.norm())) continue;
      const bool parallel = linearity(points, nbh, found[m], u) < max_linearity && std::abs(u.dot(t)) > 0.9;
      return parallel ? distances[m] : 0;
    }
  }
  return 0;
}

/// The value of rank `fraction` of `values` (reordered), 0.5 the median.
double quantile(std::vector<double>& values, double fraction) {
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(fraction * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

/// Every stride-th point of n, at most about `most` of them, spread over the point order.
struct Sampling {
  std::size_t stride, count;
};
Sampling sampling(std::size_t n, std::size_t most) {
  const std::size_t stride = std::max<std::size_t>(1, n / most);
  return {stride, (n + stride - 1) / stride};
}

/// Neighbour counts at doubling scales, whose distances give the cloud's local dimension between them.
constexpr std::array<std::size_t, 7> kScales = {4, 8, 16, 32, 64, 128, 256};
constexpr std::size_t kPairs = kScales.size() - 1;
/// The scale pairs where noisy lines are one-dimensional: 8→16, 16→32 and 32→64 neighbours.
constexpr std::size_t kFirstLinePair = 1, kLastLinePair = 3;
/// Beyond the lines' spacing the cloud is a surface again: its median dimension rises past this.
constexpr double kSurfaceDimension = 1.8;
/// Points whose dimension profile is measured for noisy lines (medians over them decide).
constexpr std::size_t kProfileSamples = 256;

/// Distances of the kScales-th neighbours of one point.
using Profile = std::array<float, kScales.size()>;

/// log 2 / log(d(2m) / d(m)): the local dimension between scale pair j's two neighbour counts (2 on a surface, 1
/// along a line, 3 within noise; 9 where the distances do not grow).
double dimension(const Profile& p, std::size_t j) {
  const double ratio = static_cast<double>(p[j + 1]) / static_cast<double>(p[j]);
  return p[j] > 0 && ratio > 1 ? std::log(2.0) / std::log(ratio) : 9.0;
}

/// Noisy lines: noise as wide as a fraction of the lines' spacing makes each line a tube, whose 8 nearest points no
/// longer make a line. Between the tube's width and the lines' spacing the cloud is still one-dimensional, and beyond
/// the spacing two-dimensional: the cloud lies on lines when the median dimension falls to noisy_dimension at 8–64
/// neighbours and rises past 1.8 at a larger scale. Where the dimension is lowest, m points lie along 2 d_m of line
/// (λ = m / 2 d_m points per length), and at 256 neighbours the density per area is ρ = 256 / π d_256²: the lines lie
/// L = λ / ρ apart, L λ times farther than the points along them.
ScanLines noisy_lines(const std::vector<Vec3f>& points, const neighbourhood::KdTree& tree,
                      const ScanLineOptions& options) {
  const std::size_t n = points.size();
  ScanLines result;
  if (n <= kScales.back() || !(options.noisy_dimension > 0)) return result;
  const Sampling sampled = sampling(n, kProfileSamples);
  const std::size_t stride = sampled.stride, samples = sampled.count;  // lambdas capture variables, not bindings
  std::vector<Profile> profiles(samples);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples, 16), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<std::uint32_t> found;
    std::vector<float> distances;
    for (std::size_t s = r.begin(); s != r.end(); ++s) {
      tree.knn_of_point(s * stride, kScales.back(), found, distances);
      for (std::size_t j = 0; j < kScales.size(); ++j) profiles[s][j] = distances[kScales[j] - 1];
    }
  });
  std::array<double, kPairs> median{};
  std::vector<double> values(samples);
  for (std::size_t j = 0; j < kPairs; ++j) {
    for (std::size_t s = 0; s < samples; ++s) values[s] = dimension(profiles[s], j);
    median[j] = quantile(values, 0.5);
  }
  const auto first = median.begin() + kFirstLinePair, last = median.begin() + kLastLinePair;
  const std::size_t line = static_cast<std::size_t>(std::min_element(first, last + 1) - median.begin());
  const double beyond = *std::max_element(median.begin() + static_cast<std::ptrdiff_t>(line) + 1, median.end());
  if (!(median[line] <= options.noisy_dimension) || !(beyond >= kSurfaceDimension)) return result;
  std::vector<double> spacing, anisotropy;
  std::size_t on_lines = 0;
  for (const Profile& p : profiles) {
    double lowest = dimension(p, kFirstLinePair);
    for (std::size_t j = kFirstLinePair + 1; j <= kLastLinePair; ++j) lowest = std::min(lowest, dimension(p, j));
    on_lines += lowest <= options.noisy_dimension;
    const double along = static_cast<double>(kScales[line + 1]) / (2.0 * p[line + 1]);
    const double area = static_cast<double>(kScales.back()) / (std::numbers::pi * p.back() * p.back());
    if (!(along > 0 && std::isfinite(along) && area > 0 && std::isfinite(area))) continue;
    spacing.push_back(along / area);
    anisotropy.push_back(along * along / area);
  }
  result.line_fraction = static_cast<double>(on_lines) / static_cast<double>(samples);
  if (spacing.empty()) return result;
  result.anisotropy = quantile(anisotropy, 0.5);
  if (result.anisotropy >= options.min_anisotropy) result.spacing = quantile(spacing, 0.25);
  return result;
}

}  // namespace

ScanLines find_scan_lines(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& neighbourhoods,
                          const neighbourhood::KdTree& tree, const ScanLineOptions& options) {
  const std::size_t n = points.size();
  if (neighbourhoods.size() != n || tree.size() != n)
    throw Error("scan lines: the neighbourhoods or the kd-tree do not match the " + std::to_string(n) + " points");
  ScanLines result;
  if (!options.enabled || n < 2 * kAcross || neighbourhoods.k < kLineNeighbours || options.max_samples == 0)
    return result;
  const Sampling sampled = sampling(n, options.max_samples);
  const std::size_t stride = sampled.stride, samples = sampled.count;  // lambdas capture variables, not bindings
  std::vector<double> gaps(samples), nearest(samples);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples, 64), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<std::uint32_t> found;
    std::vector<float> distances;
    for (std::size_t s = r.begin(); s != r.end(); ++s) {
      nearest[s] = neighbourhoods.distances_of(s * stride)[0];
      gaps[s] = across(points, neighbourhoods, tree, s * stride, options.linearity, found, distances);
    }
  });
  std::erase_if(gaps, [](double g) { return !(g > 0); });
  result.line_fraction = static_cast<double>(gaps.size()) / static_cast<double>(samples);
  if (result.line_fraction > options.min_fraction) {
    result.anisotropy = quantile(gaps, 0.5) / std::max(quantile(nearest, 0.5), 1e-30);
    const float least = result.line_fraction > options.majority_fraction
                            ? std::min(options.min_anisotropy, options.majority_min_anisotropy)
                            : options.min_anisotropy;
    // Where a surface slopes along the lines, they lie farther apart on it than their spacing: the lower quartile.
    if (result.anisotropy >= least) result.spacing = quantile(gaps, 0.25);
  }
  if (result.found()) return result;
  // Light noise puts the nearest point off a line within its own tube, heavier noise hides the line from the PCA.
  const ScanLines noisy = noisy_lines(points, tree, options);
  return noisy.found() ? noisy : result;
}

}  // namespace pcsketch::clean
