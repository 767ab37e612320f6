#include "pcsketch/differential/normals.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <atomic>

#include "common.h"
#include "core/parallel_chunks.h"
#include "core/smallest_eigenpair.h"

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

  pcsketch::detail::parallel_chunks(n, options.progress, "normals", [&](std::size_t begin, std::size_t end) {
    std::size_t local_degenerate = 0;
    for (std::size_t i = begin; i < end; ++i) {
      // Covariance of the point and its neighbours, relative to the point (exact differences in double).
      const Vec3d origin = points[i].cast<double>();
      Vec3d sum = Vec3d::Zero();
      Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
      const auto nb = neighbourhoods.indices.data() + i * neighbourhoods.k;
      for (std::size_t m = 0; m < k; ++m) {
        const Vec3d d = points[nb[m]].cast<double>() - origin;
        sum += d;
        outer.noalias() += d * d.transpose();
      }
      const double count = static_cast<double>(k + 1);
      const Vec3d mean = sum / count;
      const Eigen::Matrix3d covariance = outer / count - mean * mean.transpose();
      Vec3d normal;
      double variation;
      local_degenerate += !pca_normal(covariance, normal, variation);
      result.normals[i] = normal.cast<float>();
      result.surface_variation[i] = static_cast<float>(variation);
    }
    degenerate += local_degenerate;
  });
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
