#include "pcsketch/differential/normals.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <atomic>

#include "common.h"
#include "core/parallel_chunks.h"
#include "core/smallest_eigenpair.h"
#include "faces.h"

namespace pcsketch::differential {

namespace {

/// Eigenvalue ratio below which a direction counts as absent: float positions leave relative variances of about
/// 1e-12 across a line, true surfaces are many orders above.
constexpr double kDegenerateRatio = 1e-9;

/// A unit vector perpendicular to `d` (unit), chosen deterministically.
Vec3d perpendicular(const Vec3d& d) {
  Eigen::Index axis;
  d.cwiseAbs().minCoeff(&axis);
  return d.cross(Vec3d::Unit(axis)).normalized();
}

/// The PCA normal of a covariance and its surface variation λ0 / (λ0 + λ1 + λ2); false where the normal is
/// arbitrary (all points identical or collinear).
bool pca_normal(const Eigen::Matrix3d& covariance, Vec3d& normal, double& variation) {
  double lambda0;
  if (pcsketch::detail::smallest_eigenpair(covariance, lambda0, normal)) {
    variation = lambda0 / covariance.trace();
    return true;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(covariance);
  const Vec3d lambda = eigen.eigenvalues().cwiseMax(0.0);  // ascending
  const double total = lambda.sum();
  variation = total > 0 ? lambda[0] / total : 0.0;
  if (!(total > 0) || !eigen.eigenvectors().allFinite()) {
    normal = Vec3d::UnitZ();  // all points identical: any direction is perpendicular to the data
    return false;
  }
  if (lambda[1] <= kDegenerateRatio * lambda[2]) {
    normal = perpendicular(eigen.eigenvectors().col(2));  // collinear
    return false;
  }
  normal = eigen.eigenvectors().col(0).normalized();  // smallest variance: across the surface
  return true;
}

/// Covariance of point `origin` and the neighbours `nb[0..count)` selected by `keep`, relative to the point.
template <typename Keep>
Eigen::Matrix3d covariance_of(const std::vector<Vec3f>& points, const Vec3d& origin, const std::uint32_t* nb,
                              std::size_t count, Keep keep) {
  Vec3d sum = Vec3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  double taken = 1;  // the point itself
  for (std::size_t m = 0; m < count; ++m) {
    if (!keep(m)) continue;
    const Vec3d d = points[nb[m]].cast<double>() - origin;
    sum += d;
    outer.noalias() += d * d.transpose();
    ++taken;
  }
  const Vec3d mean = sum / taken;
  return outer / taken - mean * mean.transpose();
}

/// Covariance of point i and its neighbours `nb[0..count)`, relative to the point (exact differences in double).
Eigen::Matrix3d every_neighbour_covariance(const std::vector<Vec3f>& points, std::size_t i, const std::uint32_t* nb,
                                           std::size_t count) {
  return covariance_of(points, points[i].cast<double>(), nb, count, [](std::size_t) { return true; });
}

/// The normal of the point's own face where its neighbours hold two: a plate about as thick as the neighbourhood is
/// wide puts points of both faces in the list, and their offset along the normal, as large as the spread across it,
/// tilts the PCA (a clean 1 × 0.6 × 0.006 plate of 100k points: median 26°). The nearest few lie on the point's own
/// face: their normal (or `seed`, a split neighbour's) finds a gap in the offsets (own_face), and the PCA is taken
/// again over the point's side of it (twice, the second time along the first result). False where no gap splits the
/// list (docs/geometry.md, "Thin parts").
bool own_face_normal(const std::vector<Vec3f>& points, std::size_t i, const std::uint32_t* nb, std::size_t k,
                     float radius, const Vec3f* seed, Vec3d& normal) {
  constexpr std::size_t kSeed = 6;        // nearest neighbours that start the search
  constexpr std::size_t kMinRemoved = 2;  // fewer points beyond a gap are not a second face
  if (k < 2 * kSeed || !(radius > 0)) return false;
  const Vec3d origin = points[i].cast<double>();
  double variation;
  if (seed)
    normal = seed->cast<double>();
  else if (!pca_normal(every_neighbour_covariance(points, i, nb, kSeed), normal, variation))
    return false;
  std::array<bool, neighbourhood::kMaxNeighbours> own;
  for (int round = 0; round < 2; ++round) {
    const std::size_t kept = detail::own_face(points, i, nb, k, normal, detail::kFaceGap * radius, own).kept;
    if (kept + kMinRemoved > k || kept < kSeed) return false;
    if (!pca_normal(covariance_of(points, origin, nb, k, [&](std::size_t m) { return own[m]; }), normal, variation))
      return false;
  }
  return true;
}

/// Surface variation over which a list is searched for two faces (own_face_normal): a plane's is 0, a mixed plate's
/// 0.1–0.3.
constexpr double kLayeredVariation = 0.1;

/// Another look at the points whose own nearest few reach the other face too (their PCA finds no gap): the normal
/// of the nearest neighbour the first pass split starts the search instead (marked 2 in `split`; only 1s are read).
/// More such rounds, each reading the last one's, changed nothing on the plates of docs/geometry.md.
void own_face_from_neighbours(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& nbh, std::size_t k,
                              std::vector<std::uint8_t>& split, NormalResult& result) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1024), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      if (split[i] || !(result.surface_variation[i] > kLayeredVariation)) continue;
      const std::uint32_t* nb = nbh.indices.data() + i * nbh.k;
      const std::uint32_t* seed = std::find_if(nb, nb + k, [&](std::uint32_t j) { return split[j] == 1; });
      Vec3d normal;
      if (seed != nb + k &&
          own_face_normal(points, i, nb, k, nbh.distances[i * nbh.k + k - 1], &result.normals[*seed], normal)) {
        result.normals[i] = normal.cast<float>();
        split[i] = 2;
      }
    }
  });
}

}  // namespace

NormalResult estimate_normals(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& neighbourhoods,
                              const NormalOptions& options) {
  const std::size_t n = points.size();
  detail::check_neighbourhoods("normals", n, neighbourhoods);
  const std::size_t k = detail::neighbours_used(options.k, neighbourhoods);
  NormalResult result;
  result.normals.resize(n);
  result.surface_variation.resize(n);
  std::atomic<std::size_t> degenerate{0};
  // Lists without distances (the denoising's wider ones) are in no order: no nearest few to start from.
  const bool layered = neighbourhoods.distances.size() == neighbourhoods.indices.size();
  std::vector<std::uint8_t> split(layered ? n : 0, 0);

  pcsketch::detail::parallel_chunks(n, options.progress, "normals", [&](std::size_t begin, std::size_t end) {
    std::size_t local_degenerate = 0;
    for (std::size_t i = begin; i < end; ++i) {
      const auto nb = neighbourhoods.indices.data() + i * neighbourhoods.k;
      Vec3d normal;
      double variation;
      local_degenerate += !pca_normal(every_neighbour_covariance(points, i, nb, k), normal, variation);
      Vec3d layer_normal;
      if (layered && variation > kLayeredVariation &&
          own_face_normal(points, i, nb, k, neighbourhoods.distances[i * neighbourhoods.k + k - 1], nullptr,
                          layer_normal)) {
        normal = layer_normal;
        split[i] = 1;
      }
      result.normals[i] = normal.cast<float>();
      result.surface_variation[i] = static_cast<float>(variation);
    }
    degenerate += local_degenerate;
  });
  if (std::find(split.begin(), split.end(), 1) != split.end())
    own_face_from_neighbours(points, neighbourhoods, k, split, result);
  for (std::size_t i = 0; i < split.size(); ++i)
    if (split[i]) result.own_face.push_back(static_cast<std::uint32_t>(i));
  if (degenerate > 0)
    result.warnings.push_back("normals: " + std::to_string(degenerate.load()) +
                              " points have all neighbours identical or collinear; their normals are arbitrary");
  return result;
}

}  // namespace pcsketch::differential

namespace pcsketch::differential {

float normal_noise(const std::vector<Vec3f>& normals, const neighbourhood::Neighbourhoods& neighbourhoods,
                   std::size_t max_samples) {
  const std::size_t n = normals.size();
  detail::check_neighbourhoods("normal noise", n, neighbourhoods);
  const std::size_t k = std::min<std::size_t>(8, neighbourhoods.k);
  if (n == 0 || k == 0) return 0.f;
  const std::size_t stride = detail::sample_stride(n, max_samples);
  std::vector<float> angle((n + stride - 1) / stride);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, angle.size(), 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t s = r.begin(); s != r.end(); ++s) {
      const Vec3f& ni = normals[s * stride];
      Vec3f mean = Vec3f::Zero();
      for (const std::uint32_t j : neighbourhoods.of(s * stride).first(k))
        mean += normals[j].dot(ni) < 0 ? Vec3f(-normals[j]) : normals[j];
      angle[s] = mean.squaredNorm() > 0 ? std::atan2(ni.cross(mean).norm(), ni.dot(mean)) : 0.f;
    }
  });
  const auto mid = angle.begin() + static_cast<std::ptrdiff_t>(angle.size() / 2);
  std::nth_element(angle.begin(), mid, angle.end());
  return *mid;
}

}  // namespace pcsketch::differential
