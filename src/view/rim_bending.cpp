#include "rim_bending.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "core/tangent_frame.h"

namespace pcsketch::view::detail {

namespace {

constexpr std::size_t kFewest = 8;

/// The F statistic of the plane fit of `facing` over `ring` (distinct points) in the tangent plane of `origin`.
double plane_f(const std::vector<Vec3f>& positions, const std::vector<float>& facing, const Vec3f& origin,
               const Vec3f& normal, const std::vector<std::uint32_t>& ring) {
  Vec3f u, w;
  pcsketch::detail::tangent_frame(normal, u, w);
  // Centred sums in double: the scatter of f is small against its mean on a face seen edge-on.
  double mx = 0, my = 0, mf = 0;
  for (const std::uint32_t s : ring) {
    const Vec3f d = positions[s] - origin;
    mx += d.dot(u), my += d.dot(w), mf += facing[s];
  }
  const auto count = static_cast<double>(ring.size());
  mx /= count, my /= count, mf /= count;
  double sxx = 0, sxy = 0, syy = 0, sxf = 0, syf = 0, sff = 0;
  for (const std::uint32_t s : ring) {
    const Vec3f d = positions[s] - origin;
    const double x = d.dot(u) - mx, y = d.dot(w) - my, f = facing[s] - mf;
    sxx += x * x, sxy += x * y, syy += y * y, sxf += x * f, syf += y * f, sff += f * f;
  }
  const double det = sxx * syy - sxy * sxy;
  if (!(det > 0)) return 0;
  const double gx = (syy * sxf - sxy * syf) / det, gy = (sxx * syf - sxy * sxf) / det;
  const double explained = gx * sxf + gy * syf, residual = std::max(0.0, sff - explained);
  if (!(residual > 0)) return explained > 0 ? INFINITY : 0;
  return (explained / 2) / (residual / (count - 3));
}

}  // namespace

std::vector<char> rim_bends(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                            const neighbourhood::Neighbourhoods& neighbourhoods, const std::vector<float>& facing,
                            const std::vector<std::uint32_t>& points, std::size_t m, float min_f) {
  std::vector<char> bends(points.size(), 1);
  m = std::min(m, neighbourhoods.k);
  // Each worker marks the points of its current ring with the sample's number: no sort to drop the repeats.
  tbb::enumerable_thread_specific<std::vector<std::uint32_t>> marks;
  const auto ring_of = [&](std::uint32_t i, std::uint32_t stamp, std::vector<std::uint32_t>& mark,
                           std::vector<std::uint32_t>& ring) {
    ring.clear();
    const auto add = [&](std::uint32_t q) {
      if (mark[q] != stamp) ring.push_back(q);
      mark[q] = stamp;
    };
    add(i);
    for (const std::uint32_t j : neighbourhoods.of(i).first(m)) {
      add(j);
      for (const std::uint32_t q : neighbourhoods.of(j).first(m)) add(q);
    }
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 64), [&](const auto& r) {
    std::vector<std::uint32_t>& mark = marks.local();
    if (mark.empty()) mark.assign(positions.size(), 0);
    std::vector<std::uint32_t> ring;
    for (std::size_t p = r.begin(); p != r.end(); ++p) {
      ring_of(points[p], static_cast<std::uint32_t>(p + 1), mark, ring);
      if (ring.size() >= kFewest)
        bends[p] = plane_f(positions, facing, positions[points[p]], normals[points[p]], ring) >= min_f;
    }
  });
  return bends;
}

}  // namespace pcsketch::view::detail
