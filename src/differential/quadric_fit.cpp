#include "quadric_fit.h"

#include <Eigen/Cholesky>
#include <array>
#include <cmath>

#include "graph_curvature.h"

namespace pcsketch::differential::detail {

namespace {

/// Two doubles side by side (GCC and Clang vector extension): two neighbours at a time in SSE2's registers.
using Pair = double __attribute__((vector_size(16)));

/// From this many points on, the moments are summed two neighbours at a time (about 2.5× faster: the scalar loop
/// waits on its adds). Smaller fits, the shared neighbourhoods of every clean cloud, keep the sum in point order:
/// their results are the same bits as before.
constexpr std::size_t kPairedFrom = 64;

/// The point and its neighbours in its tangent frame (u, v, n), one array per coordinate.
struct Local {
  std::vector<double> x, y, z;
};

/// The moments Σ x^a y^b (a + b ≤ 4) and Σ z x^a y^b (a + b ≤ 2): all the quadric's normal equations need. T is a
/// double, or a Pair summing two interleaved halves of the points.
template <class T>
struct Moments {
  enum { x4, x3y, x2y2, xy3, y4, x3, x2y, xy2, y3, x2, xy, y2, x1, y1, zx2, zxy, zy2, zx, zy, z1, count };
  std::array<T, count> s{};

  void add(T x, T y, T z) {
    const T xx = x * x, xy_ = x * y, yy = y * y;
    s[x4] += xx * xx, s[x3y] += xx * xy_, s[x2y2] += xx * yy, s[xy3] += xy_ * yy, s[y4] += yy * yy;
    s[x3] += xx * x, s[x2y] += xx * y, s[xy2] += x * yy, s[y3] += yy * y;
    s[x2] += xx, s[xy] += xy_, s[y2] += yy, s[x1] += x, s[y1] += y;
    s[zx2] += z * xx, s[zxy] += z * xy_, s[zy2] += z * yy, s[zx] += z * x, s[zy] += z * y, s[z1] += z;
  }
};

/// The moments of local[0..size) with tangent coordinates scaled by `scale`.
Moments<double> moments(const Local& local, std::size_t size, double scale) {
  Moments<double> m;
  std::size_t q = 0;
  if (size >= kPairedFrom) {
    Moments<Pair> pairs;
    for (; q + 2 <= size; q += 2) {
      const Pair x = {local.x[q], local.x[q + 1]}, y = {local.y[q], local.y[q + 1]}, z = {local.z[q], local.z[q + 1]};
      pairs.add(x * scale, y * scale, z);
    }
    for (std::size_t e = 0; e < m.s.size(); ++e) m.s[e] = pairs.s[e][0] + pairs.s[e][1];
  }
  for (; q < size; ++q) m.add(local.x[q] * scale, local.y[q] * scale, local.z[q]);
  return m;
}

/// The quadric fit over local[0..size) (the point and its first size − 1 neighbours; `spread` is Σ x² + y² over
/// the neighbours).
PointFit fit_quadric(const Local& local, std::size_t size, double spread, const Vec3d& n, const Vec3d& u,
                     const Vec3d& v, Want want) {
  PointFit fit;
  const std::size_t count = size - 1;
  // Tangent coordinates scaled to unit RMS radius: keeps the normal equations well conditioned at any model scale.
  const double scale = spread > 0 ? std::sqrt(static_cast<double>(count) / spread) : 1.0;
  using M = Moments<double>;
  const std::array<double, M::count> s = moments(local, size, scale).s;
  const double w0 = static_cast<double>(size);
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  Eigen::Matrix<double, 6, 6> normal_matrix;  // rows/columns: x², xy, y², x, y, 1
  normal_matrix << s[M::x4], s[M::x3y], s[M::x2y2], s[M::x3], s[M::x2y], s[M::x2],  //
      s[M::x3y], s[M::x2y2], s[M::xy3], s[M::x2y], s[M::xy2], s[M::xy],             //
      s[M::x2y2], s[M::xy3], s[M::y4], s[M::xy2], s[M::y3], s[M::y2],               //
      s[M::x3], s[M::x2y], s[M::xy2], s[M::x2], s[M::xy], s[M::x1],                 //
      s[M::x2y], s[M::xy2], s[M::y3], s[M::xy], s[M::y2], s[M::y1],                 //
      s[M::x2], s[M::xy], s[M::y2], s[M::x1], s[M::y1], w0;
  const Vec6 rhs(s[M::zx2], s[M::zxy], s[M::zy2], s[M::zx], s[M::zy], s[M::z1]);
  // A tiny ridge makes every system positive definite; in well-posed fits its effect is ~1e-9 relative, in
  // rank-deficient ones it zeroes the unseen coefficients.
  normal_matrix.diagonal().array() += 1e-9 * w0;
  const Vec6 c = normal_matrix.llt().solve(rhs);
  if (!c.allFinite()) return fit;

  if (want != Want::shape) {
    double squares = 0;
    for (std::size_t q = 0; q < size; ++q) {
      const double x = local.x[q] * scale, y = local.y[q] * scale;
      squares += std::pow(local.z[q] - (c[0] * x * x + c[1] * x * y + c[2] * y * y + c[3] * x + c[4] * y + c[5]), 2);
    }
    const double dof = size > 6 ? static_cast<double>(size - 6) : 1.0;
    fit.residual = std::sqrt(squares / dof);
  }
  if (want == Want::residual) return fit;

  // Graph z = h(x, y): derivatives at the origin in model units.
  const double s2 = scale * scale;
  const GraphCurvature g = graph_curvature(c[3] * scale, c[4] * scale, 2 * c[0] * s2, c[1] * s2, 2 * c[2] * s2);
  fit.k1 = static_cast<float>(g.k1);
  fit.k2 = static_cast<float>(g.k2);
  // The tangent vector (ξ, η, hx ξ + hy η) projected onto the tangent plane of `normal` is ξ u + η v.
  const Vec3d dir = g.xi.squaredNorm() > 0 ? Vec3d(g.xi.x() * u + g.xi.y() * v).normalized() : u;
  fit.dir1 = dir.cast<float>();
  fit.dir2 = n.cross(dir).cast<float>();
  return fit;
}

}  // namespace

PointFit fit_point(const std::vector<Vec3f>& points, std::size_t i, const Vec3f& normal,
                   const std::uint32_t* neighbours, std::size_t count, double* inner, Want want) {
  if (inner) *inner = 0;
  const Vec3d n = normal.cast<double>();
  if (!(n.squaredNorm() > 0.5)) return {};  // no normal: no frame
  Vec3d u, v;
  tangent_frame(n, u, v);
  const Vec3d origin = points[i].cast<double>();

  thread_local Local local;
  local.x.resize(count + 1), local.y.resize(count + 1), local.z.resize(count + 1);
  local.x[0] = local.y[0] = local.z[0] = 0;
  double spread = 0, inner_spread = 0;
  std::size_t m = 0;
  // Two neighbours at a time, where the sum of the spread need not stop at kInnerFit: it no longer waits on each add.
  if (count >= kPairedFrom && !inner) {
    const auto pair = [](double a, double b) { return Pair{a, b}; };
    Pair spreads = {0, 0};
    for (; m + 2 <= count; m += 2) {
      const Vec3f &a = points[neighbours[m]], &b = points[neighbours[m + 1]];
      const Pair dx = pair(a.x(), b.x()) - origin.x(), dy = pair(a.y(), b.y()) - origin.y(),
                 dz = pair(a.z(), b.z()) - origin.z();
      const Pair x = dx * u.x() + dy * u.y() + dz * u.z(), y = dx * v.x() + dy * v.y() + dz * v.z();
      const Pair z = dx * n.x() + dy * n.y() + dz * n.z();
      local.x[m + 1] = x[0], local.x[m + 2] = x[1], local.y[m + 1] = y[0], local.y[m + 2] = y[1];
      local.z[m + 1] = z[0], local.z[m + 2] = z[1];
      spreads += x * x + y * y;
    }
    spread = spreads[0] + spreads[1];
  }
  for (; m < count; ++m) {
    const Vec3d d = points[neighbours[m]].cast<double>() - origin;
    const double x = d.dot(u), y = d.dot(v);
    local.x[m + 1] = x, local.y[m + 1] = y, local.z[m + 1] = d.dot(n);
    spread += Eigen::Vector2d(x, y).squaredNorm();
    if (m + 1 == kInnerFit) inner_spread = spread;
  }
  if (inner && count >= kInnerFit)
    *inner = fit_quadric(local, kInnerFit + 1, inner_spread, n, u, v, Want::residual).residual;
  return fit_quadric(local, count + 1, spread, n, u, v, want);
}

}  // namespace pcsketch::differential::detail
