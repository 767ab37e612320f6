// smallest_eigenpair (the PCA normals' solver) against known eigenpairs and against Eigen's own solver on the
// covariances of noisy, curved and stretched neighbourhoods; the cases it must hand back to Eigen.

#include "core/smallest_eigenpair.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <random>

namespace pcsketch::detail {
namespace {

/// R · diag(values) · Rᵀ for a rotation R about `axis` by `angle`.
Eigen::Matrix3d rotated(const Eigen::Vector3d& values, const Eigen::Vector3d& axis, double angle,
                        Eigen::Matrix3d* rotation = nullptr) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  if (rotation) *rotation = r;
  return r * values.asDiagonal() * r.transpose();
}

TEST(SmallestEigenpair, FindsTheEigenpairOfAKnownRotatedDiagonal) {
  Eigen::Matrix3d r;
  const Eigen::Matrix3d c = rotated({0.25, 2, 3}, {1, 2, 0.5}, 0.7, &r);
  double lambda0 = 0;
  Eigen::Vector3d v;
  ASSERT_TRUE(smallest_eigenpair(c, lambda0, v));
  EXPECT_NEAR(lambda0, 0.25, 1e-13);
  EXPECT_NEAR(std::abs(v.dot(r.col(0))), 1.0, 1e-13);
  EXPECT_NEAR(v.norm(), 1.0, 1e-14);
}

TEST(SmallestEigenpair, AgreesWithEigenOnNoisyCurvedAndStretchedNeighbourhoods) {
  std::mt19937 random(7);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> uniform(0, 1);
  int solved = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    // 17 points of a patch: x, y spread, z noise of 1e-6 to 0.3 of the spread plus a bend, turned at random.
    const double stretch = 0.05 + 2 * uniform(random), noise = std::pow(10.0, -6 + 5.5 * uniform(random));
    const double bend = trial % 3 == 0 ? 0.0 : 0.3 * uniform(random);
    Eigen::Matrix<double, 3, 17> p;
    for (int c = 0; c < 17; ++c) {
      p(0, c) = gauss(random);
      p(1, c) = stretch * gauss(random);
      p(2, c) = noise * gauss(random) + bend * p(0, c) * p(0, c);
    }
    p = Eigen::AngleAxisd(6 * uniform(random), Eigen::Vector3d::Random().normalized()).toRotationMatrix() * p;
    const Eigen::Matrix<double, 3, 17> centred = p.colwise() - p.rowwise().mean();
    const Eigen::Matrix3d c = centred * centred.transpose() / 17;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(c);
    const Eigen::Vector3d lambda = eigen.eigenvalues();
    double lambda0 = 0;
    Eigen::Vector3d v;
    const bool fast = smallest_eigenpair(c, lambda0, v);
    if ((lambda[1] - lambda[0]) > 2e-4 * c.trace()) {
      EXPECT_TRUE(fast) << "trial " << trial;
    }
    if (!fast) continue;
    ++solved;
    EXPECT_NEAR(lambda0, std::max(0.0, lambda[0]), 1e-12 * c.trace()) << "trial " << trial;
    // The vector's error grows as the rounding over the gap λ1 − λ0, at least 1e-4 of the trace here.
    EXPECT_GT(std::abs(v.dot(eigen.eigenvectors().col(0))), 1 - 1e-10) << "trial " << trial;
  }
  EXPECT_GT(solved, 19000);
}

TEST(SmallestEigenpair, LeavesTiesLinesPointsAndNonFiniteInputToEigen) {
  double lambda0 = 0;
  Eigen::Vector3d v;
  EXPECT_FALSE(smallest_eigenpair(Eigen::Matrix3d::Zero(), lambda0, v));                // one point
  EXPECT_FALSE(smallest_eigenpair(Eigen::Matrix3d::Identity(), lambda0, v));            // isotropic
  EXPECT_FALSE(smallest_eigenpair(rotated({1, 1, 5}, {0, 1, 1}, 0.3), lambda0, v));     // tied smallest
  EXPECT_FALSE(smallest_eigenpair(rotated({0, 0, 4}, {1, 0, 1}, 1.1), lambda0, v));     // a line
  EXPECT_FALSE(smallest_eigenpair(rotated({0, 1e-9, 4}, {1, 0, 1}, 1.1), lambda0, v));  // nearly a line
  Eigen::Matrix3d bad = rotated({0.1, 1, 2}, {1, 1, 1}, 0.4);
  bad(1, 2) = bad(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(smallest_eigenpair(bad, lambda0, v));
  bad(0, 0) = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(smallest_eigenpair(bad, lambda0, v));
}

TEST(SmallestEigenpair, AFlatPatchGivesItsPlaneNormalAndAZeroEigenvalue) {
  Eigen::Matrix3d r;
  const Eigen::Matrix3d c = rotated({0, 0.5, 1.5}, {0.3, -1, 2}, 2.1, &r);
  double lambda0 = 1;
  Eigen::Vector3d v;
  ASSERT_TRUE(smallest_eigenpair(c, lambda0, v));
  EXPECT_NEAR(lambda0, 0.0, 1e-14);
  EXPECT_NEAR(std::abs(v.dot(r.col(0))), 1.0, 1e-14);
}

}  // namespace
}  // namespace pcsketch::detail
