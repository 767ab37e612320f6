#include "group_fit.h"

#include <tbb/parallel_sort.h>
#include <tbb/task_group.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>

#include "common.h"
#include "core/nth_value.h"
#include "core/parallel_chunks.h"
#include "graph_curvature.h"

namespace pcsketch::differential::detail {

namespace {

/// Largest group: beyond it the groups' cost is all in the ball query, which it no longer divides.
constexpr std::size_t kMaxGroup = 64;

using Vec10 = Eigen::Matrix<double, 10, 1>;
using Mat10 = Eigen::Matrix<double, 10, 10>;

/// Monomials of the cubic, in the order of its coefficients: 1, x, y, x², xy, y², x³, x²y, xy², y³. The first six
/// are the quadric's.
Vec10 cubic_basis(double x, double y) {
  Vec10 b;
  b << 1, x, y, x * x, x * y, y * y, x * x * x, x * x * y, x * y * y, y * y * y;
  return b;
}

/// Estimated radius holding `fit` neighbours of a point whose k-th shared distance is `kth`: kth scaled by √(fit / k).
/// Monotone in kth, so the median radius is the radius of the median distance.
double radius_for(float kth, std::size_t k, std::size_t fit) {
  return kth * std::sqrt(static_cast<double>(fit) / static_cast<double>(k));
}

/// Estimated radius holding `fit` neighbours of point i.
double fit_radius(const neighbourhood::Neighbourhoods& shared, std::size_t i, std::size_t fit) {
  if (shared.k == 0) return 0;
  return radius_for(shared.distances[i * shared.k + shared.k - 1], shared.k, fit);
}

/// Each point's own support where a group's shared fit fails: a ball around the point, of the radius that holds
/// about k there (GroupFitter::run), cut out of one query around the whole group. Picking each point's exact k
/// nearest instead (a sort of the group's ball and a selection per point) was 60% of a noisy CAD part's crease fits,
/// and on an even cloud the ball holds about as many. A ball holding under half or over twice the k asked for
/// (uneven sampling, such as a coarse mesh's vertices) gives way to the point's exact k nearest.
class GroupNeighbours {
 public:
  GroupNeighbours(const std::vector<Vec3f>& points, const neighbourhood::KdTree& tree, std::size_t k)
      : points_(points), tree_(tree), k_(k) {}

  /// Gathers every point within `radius` of any of the group's.
  void gather(std::span<const std::uint32_t> group, float radius) {
    Vec3f centre = Vec3f::Zero();
    for (const std::uint32_t i : group) centre += points_[i];
    centre /= static_cast<float>(group.size());
    float spread = 0;
    for (const std::uint32_t i : group) spread = std::max(spread, (points_[i] - centre).norm());
    radius_ = radius;
    tree_.radius_unsorted(centre, (spread + radius) * (1 + 1e-5f), ball_);
    x_.resize(ball_.size()), y_.resize(ball_.size()), z_.resize(ball_.size());
    for (std::size_t b = 0; b < ball_.size(); ++b)
      x_[b] = points_[ball_[b]].x(), y_[b] = points_[ball_[b]].y(), z_[b] = points_[ball_[b]].z();
  }

  /// Point i's neighbours within the gathered radius (i excluded), or its exact k nearest; in no particular order.
  /// The ball's coordinates side by side and no branch: about half of the ball is kept, at random.
  const std::vector<std::uint32_t>& of(std::size_t i) {
    const Vec3f& p = points_[i];
    const float limit = radius_ * radius_;
    const std::size_t size = ball_.size();
    const auto self = static_cast<std::uint32_t>(i);
    // The distances in a loop of their own, which vectorises; the selection after them.
    inside_.resize(size);
    for (std::size_t b = 0; b < size; ++b) {
      const float dx = x_[b] - p.x(), dy = y_[b] - p.y(), dz = z_[b] - p.z();
      inside_[b] = (dx * dx + dy * dy + dz * dz <= limit) & (ball_[b] != self);
    }
    found_.resize(size);
    std::size_t count = 0;
    for (std::size_t b = 0; b < size; ++b) {
      found_[count] = ball_[b];
      count += inside_[b];
    }
    found_.resize(count);
    if (2 * count < k_ || count > 2 * k_) tree_.knn_of_point(i, k_, found_, distances_);
    return found_;
  }

 private:
  const std::vector<Vec3f>& points_;
  const neighbourhood::KdTree& tree_;
  std::size_t k_;
  float radius_ = 0;
  std::vector<std::uint32_t> ball_, found_, inside_;
  std::vector<float> x_, y_, z_, distances_;
};

/// One group's fit, with per-thread buffers.
struct GroupFitter {
  const std::vector<Vec3f>& points;
  const std::vector<Vec3f>& normals;
  const neighbourhood::Neighbourhoods& shared;
  const neighbourhood::KdTree& tree;
  const GroupFitOptions& options;
  const PointFitFn& point_fit;
  Curvature& result;
  GroupNeighbours near;
  std::vector<std::uint32_t> ball;
  std::vector<Vec3d> local;

  /// One group: one height field (solve), or a fit per point over its exact k nearest where solve finds a crease.
  /// The group's support is the ball of the radius estimated to hold `fit` points (picking the k nearest out of a
  /// ball was a quarter of the cost). Returns whether it fell back to the per-point fits.
  bool run(std::span<const std::uint32_t> group) {
    Vec3d centre = Vec3d::Zero(), normal = Vec3d::Zero();
    double radius = 0;
    for (const std::uint32_t i : group) {
      centre += points[i].cast<double>();
      normal += normals[i].cast<double>();
      radius += fit_radius(shared, i, options.fit);
    }
    centre /= static_cast<double>(group.size());
    radius /= static_cast<double>(group.size());
    tree.radius_unsorted(centre.cast<float>(), static_cast<float>(radius), ball);
    // Oriented normals agree within a group; if they cancel (a sheet seen from both sides), the first one decides.
    normal = normal.norm() > 1e-6 ? Vec3d(normal.normalized()) : normals[group.front()].cast<double>();
    Vec3d u, v;
    tangent_frame(normal, u, v);

    local.clear();
    double spread = 0;
    for (const std::uint32_t j : ball) {
      const Vec3d d = points[j].cast<double>() - centre;
      local.emplace_back(d.dot(u), d.dot(v), d.dot(normal));
      spread += local.back().head<2>().squaredNorm();
    }
    // Tangent coordinates scaled to unit RMS radius: keeps the normal equations well conditioned at any scale.
    const double scale = spread > 0 ? std::sqrt(static_cast<double>(local.size()) / spread) : 1.0;
    // The lower triangle is summed row after row in one packed array: each row's products b[r]·b[0..r] then lie
    // side by side and vectorise, where the matrix's columns scattered them 80 bytes apart. Each entry is still
    // summed over the points in the same order: the same bits.
    std::array<double, 55> lower{};
    Vec10 rhs = Vec10::Zero();
    double zz = 0;
    for (const Vec3d& q : local) {
      const Vec10 b = cubic_basis(q.x() * scale, q.y() * scale);
      for (int r = 0, at = 0; r < 10; at += ++r)
        for (int c = 0; c <= r; ++c) lower[at + c] += b[r] * b[c];
      rhs += q.z() * b;
      zz += q.z() * q.z();
    }
    Mat10 normal_matrix = Mat10::Zero();
    for (int r = 0, at = 0; r < 10; at += ++r)
      for (int c = 0; c <= r; ++c) normal_matrix(r, c) = lower[at + c];
    // The same tiny ridge as the per-point fits: positive definite always, unseen terms zero.
    normal_matrix.diagonal().array() += 1e-9 * static_cast<double>(local.size());
    const std::optional<Vec10> c = solve(normal_matrix, rhs, zz, local.size());
    if (!c && options.shared_at_creases) {
      for (const std::uint32_t i : group) point_fit(i, shared.of(i).data(), shared.k);
      return true;
    }
    if (!c) {
      // The group's ball held ball.size() points: on a surface the radius holding `fit` scales as its root.
      const double share = ball.empty() ? 1.0 : static_cast<double>(options.fit) / static_cast<double>(ball.size());
      near.gather(group, static_cast<float>(radius * std::sqrt(share)));
      for (const std::uint32_t i : group) {
        const std::vector<std::uint32_t>& nb = near.of(i);
        point_fit(i, nb.data(), nb.size());
      }
      return true;
    }
    for (const std::uint32_t i : group) store(i, *c, centre, normal, u, v, scale);
    return false;
  }

  /// The group's height field: the quadric, plus the cubic terms shrunk towards 0 by how far they stand out of the
  /// noise (weight 1 − cubic_shrink·σ̂²/ΔRSS, at least 0; ΔRSS is the residual the 4 cubic terms remove, σ̂²χ²₄ on pure
  /// noise). Away from the group's centre the cubic terms add their own noise: on a noisy sphere they only add it, on a
  /// shape whose curvature changes across the group they follow the change. None where even the cubic leaves over
  /// `misfit_factor` × σ̂² per degree of freedom: a crease, or a shape changing faster than a cubic follows, lies in
  /// the support. There the cubic bends towards the face beyond the crease, and the point's own support, centred on it,
  /// is what places the crest.
  std::optional<Vec10> solve(const Mat10& normal_matrix, const Vec10& rhs, double zz, std::size_t count) const {
    if (count <= 10) return std::nullopt;
    const Eigen::Matrix<double, 6, 1> quadric_rhs = rhs.head<6>();
    const Eigen::Matrix<double, 6, 6> quadric_matrix = normal_matrix.topLeftCorner<6, 6>();
    const Eigen::Matrix<double, 6, 1> quadric = quadric_matrix.selfadjointView<Eigen::Lower>().llt().solve(quadric_rhs);
    const Vec10 cubic = normal_matrix.selfadjointView<Eigen::Lower>().llt().solve(rhs);
    if (!quadric.allFinite() || !cubic.allFinite()) return std::nullopt;
    const double cubic_residual = std::max(0.0, zz - cubic.dot(rhs));
    const double variance = options.noise_sigma * options.noise_sigma;
    if (!(cubic_residual <= options.misfit_factor * variance * static_cast<double>(count - 10))) return std::nullopt;
    const double gain = cubic.dot(rhs) - quadric.dot(quadric_rhs);  // ΔRSS of the cubic terms
    const double weight = gain > 0 ? std::max(0.0, 1 - options.cubic_shrink * variance / gain) : 0.0;
    Vec10 c = weight * cubic;
    c.head<6>() += (1 - weight) * quadric;
    return c;
  }

  /// Curvature of the fitted cubic at point i's (x, y).
  void store(std::size_t i, const Vec10& c, const Vec3d& centre, const Vec3d& normal, const Vec3d& u, const Vec3d& v,
             double scale) {
    const Vec3d d = points[i].cast<double>() - centre;
    const double x = d.dot(u) * scale, y = d.dot(v) * scale, s2 = scale * scale;
    const double hx = (c[1] + 2 * c[3] * x + c[4] * y + 3 * c[6] * x * x + 2 * c[7] * x * y + c[8] * y * y) * scale;
    const double hy = (c[2] + c[4] * x + 2 * c[5] * y + c[7] * x * x + 2 * c[8] * x * y + 3 * c[9] * y * y) * scale;
    const double hxx = (2 * c[3] + 6 * c[6] * x + 2 * c[7] * y) * s2;
    const double hxy = (c[4] + 2 * c[7] * x + 2 * c[8] * y) * s2;
    const double hyy = (2 * c[5] + 2 * c[8] * x + 6 * c[9] * y) * s2;
    const GraphCurvature g = graph_curvature(hx, hy, hxx, hxy, hyy);
    const Vec3d n = normals[i].cast<double>();
    // k1's direction on the graph, then in the tangent plane of the point's own normal.
    Vec3d t = g.xi.x() * (u + hx * normal) + g.xi.y() * (v + hy * normal);
    t -= t.dot(n) * n;
    if (!(t.squaredNorm() > 1e-24)) {  // umbilic, or a normal across the frame: any tangent direction
      Vec3d b;
      tangent_frame(n, t, b);
    }
    const Vec3d dir = t.normalized();
    result.k1[i] = static_cast<float>(g.k1);
    result.k2[i] = static_cast<float>(g.k2);
    result.dir1[i] = dir.cast<float>();
    result.dir2[i] = n.cross(dir).cast<float>();
  }
};

}  // namespace

Groups make_groups(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& shared, std::size_t fit,
                   double fraction, std::size_t max_size) {
  Groups groups;
  const std::size_t n = points.size();
  groups.starts.push_back(0);
  if (n == 0) return groups;
  const double median_radius =
      shared.k == 0 ? 0 : radius_for(pcsketch::detail::nth_value(farthest_distances(shared), n / 2), shared.k, fit);
  const double side = 2 * fraction * median_radius;
  Vec3f low = points[0], high = points[0];
  for (const Vec3f& p : points) low = low.cwiseMin(p), high = high.cwiseMax(p);
  // Cell keys of 21 bits an axis (cells grow if the cloud spans more); one sort by (key, index) lists each cell's
  // points together, in index order: deterministic.
  const double cell = std::max(side, static_cast<double>((high - low).maxCoeff()) / double(1 << 20));
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Eigen::Array3d c = ((points[i] - low).cast<double>() / cell).array().floor();
      const auto x = static_cast<std::uint64_t>(c.x()), y = static_cast<std::uint64_t>(c.y()),
                 z = static_cast<std::uint64_t>(c.z());
      keyed[i] = {(x << 42) | (y << 21) | z, static_cast<std::uint32_t>(i)};
    }
  });
  tbb::parallel_sort(keyed.begin(), keyed.end());
  groups.members.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    groups.members[i] = keyed[i].second;
    const bool new_cell = i > 0 && keyed[i].first != keyed[i - 1].first;
    if (i > 0 && (new_cell || i - groups.starts.back() == max_size)) groups.starts.push_back(i);
  }
  groups.starts.push_back(n);
  return groups;
}

std::size_t fit_groups(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                       const neighbourhood::Neighbourhoods& shared, const neighbourhood::KdTree& tree,
                       const GroupFitOptions& options, const PointFitFn& point_fit, Curvature& result) {
  // The tree's build is serial: it takes one core while the grouping's sort takes the other.
  tbb::task_group build;
  build.run([&tree] { tree.build(); });
  Groups groups;
  try {
    groups = make_groups(points, shared, options.fit, options.reach, kMaxGroup);
  } catch (...) {
    build.wait();
    throw;
  }
  build.wait();
  const std::size_t count = groups.size();
  std::vector<char> fell_back(count, 0);
  pcsketch::detail::parallel_chunks(count, options.progress, options.stage, [&](std::size_t begin, std::size_t end) {
    GroupFitter fitter{
        points, normals, shared, tree, options, point_fit, result, GroupNeighbours(points, tree, options.fit), {}, {}};
    for (std::size_t g = begin; g < end; ++g) fell_back[g] = fitter.run(groups.of(g));
  });
  std::size_t per_point = 0;
  for (std::size_t g = 0; g < count; ++g) per_point += fell_back[g] ? groups.of(g).size() : 0;
  return per_point;
}

}  // namespace pcsketch::differential::detail
