#include "end_grid.h"

#include <algorithm>
#include <cmath>

namespace pcsketch::plotter::detail {

EndGrid::EndGrid(std::vector<Vec2d> points)
    : points_(std::move(points)), alive_(points_.size(), 1), alive_count_(points_.size()) {
  rebuild();
}

void EndGrid::rebuild() {
  built_count_ = alive_count_;
  nx_ = ny_ = 0;
  start_.assign(1, 0);
  ids_.clear();
  if (alive_count_ == 0) return;
  Vec2d lo = Vec2d::Constant(std::numeric_limits<double>::max()), hi = -lo;
  for (std::size_t i = 0; i < points_.size(); ++i)
    if (alive_[i]) {
      lo = lo.cwiseMin(points_[i]);
      hi = hi.cwiseMax(points_[i]);
    }
  const Vec2d extent = hi - lo;
  const double n = static_cast<double>(alive_count_);
  // About one point a cell; a strip of points (zero area) gets square cells along its length.
  const double longest = std::max(extent.maxCoeff(), 1e-9);
  const double area = std::max(extent.x() * extent.y(), longest * longest / n);
  lo_ = lo;
  cell_ = std::max(std::sqrt(area / n), longest * 1e-6);
  nx_ = static_cast<long>(extent.x() / cell_) + 1;
  ny_ = static_cast<long>(extent.y() / cell_) + 1;
  const std::size_t cells = static_cast<std::size_t>(nx_ * ny_);
  std::vector<std::uint32_t> cell_of_point(points_.size());
  start_.assign(cells + 1, 0);
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (!alive_[i]) continue;
    const long c = cell_of(points_[i].y(), lo_.y()) * nx_ + cell_of(points_[i].x(), lo_.x());
    cell_of_point[i] = static_cast<std::uint32_t>(c);
    ++start_[static_cast<std::size_t>(c) + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  ids_.resize(alive_count_);
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < points_.size(); ++i)
    if (alive_[i]) ids_[fill[cell_of_point[i]]++] = static_cast<std::uint32_t>(i);
}

long EndGrid::cell_of(double x, double lo) const {
  // Clamped: a query far outside a grid of tiny cells would overflow the conversion.
  return static_cast<long>(std::clamp(std::floor((x - lo) / cell_), -1e15, 1e15));
}

void EndGrid::remove(std::size_t id) {
  if (id >= points_.size() || !alive_[id]) return;
  alive_[id] = 0;
  --alive_count_;
  if (alive_count_ > 0 && alive_count_ * 4 < built_count_) rebuild();
}

std::size_t EndGrid::nearest(const Vec2d& q, double max_distance) const {
  if (alive_count_ == 0 || nx_ == 0) return npos;
  const long cx = cell_of(q.x(), lo_.x()), cy = cell_of(q.y(), lo_.y());
  // Rings nearer than the grid hold nothing: start at the first ring that reaches it.
  const long gap_x = std::max({0L, -cx, cx - (nx_ - 1)}), gap_y = std::max({0L, -cy, cy - (ny_ - 1)});
  const long first = std::max(gap_x, gap_y);
  const long last = std::max({cx, nx_ - 1 - cx, cy, ny_ - 1 - cy});
  std::size_t best = npos;
  double best_d2 = max_distance * max_distance;
  auto visit = [&](long x, long y) {
    if (x < 0 || y < 0 || x >= nx_ || y >= ny_) return;
    const std::size_t c = static_cast<std::size_t>(y * nx_ + x);
    for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
      const std::uint32_t id = ids_[k];
      if (!alive_[id]) continue;
      const double d2 = (points_[id] - q).squaredNorm();
      if (d2 < best_d2 || (d2 == best_d2 && id < best)) {
        best_d2 = d2;
        best = id;
      }
    }
  };
  for (long r = first; r <= last; ++r) {
    // Every point of ring r + 1 and beyond lies at least r cells away.
    const double reach = static_cast<double>(std::max(0L, r - 1)) * cell_;
    if (reach * reach > best_d2) break;
    // The ring's rows and columns, clipped to the grid (a query far outside it would walk empty cells).
    const long x0 = std::max(cx - r, 0L), x1 = std::min(cx + r, nx_ - 1);
    const long y0 = std::max(cy - r + 1, 0L), y1 = std::min(cy + r - 1, ny_ - 1);
    for (long x = x0; x <= x1; ++x) {
      visit(x, cy - r);
      if (r > 0) visit(x, cy + r);
    }
    for (long y = y0; y <= y1; ++y) {
      visit(cx - r, y);
      visit(cx + r, y);
    }
  }
  return best;
}

}  // namespace pcsketch::plotter::detail
