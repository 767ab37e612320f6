#include "outline_points.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "core/angles.h"
#include "core/angular_gap.h"
#include "core/parallel_chunks.h"
#include "image_cells.h"
#include "pcsketch/features/boundary_lines.h"
#include "point_grid.h"

namespace pcsketch::view::detail {

namespace {

using pcsketch::detail::kDegToRad;
/// Image cell, in mean point spacings, within which one point stands for all in the outline test.
constexpr float kImageCellFactor = 0.25f;

using pcsketch::detail::gap_exceeds;
using pcsketch::detail::largest_gap;
using pcsketch::detail::octant_bit;

/// The points of the rims that are not drawn and their nearest `m` neighbours (empty without a
/// border): the band of outline candidates a hole seen through makes is about r/2 wide, its rim one or two points.
std::vector<std::uint8_t> border_band(const std::vector<std::uint8_t>& border,
                                      const neighbourhood::Neighbourhoods& neighbourhoods, std::size_t m) {
  if (border.empty()) return {};
  std::vector<std::uint8_t> band(border.size(), 0);
  m = std::min(m, neighbourhoods.k);
  for (std::size_t i = 0; i < border.size(); ++i)
    if (border[i] == features::Boundary::kUndrawnRim) {
      band[i] = 1;
      for (const std::uint32_t j : neighbourhoods.of(i).first(m)) band[j] = 1;
    }
  return band;
}

/// One worker's buffers, reused from point to point.
struct Scratch {
  std::vector<std::pair<float, std::uint32_t>> near;
  std::vector<Vec2f> dirs;
  std::vector<float> angles;
};

/// The outline test over the asked points (`valid`, indices into `projected`): their image positions, the grid over
/// them and the test's thresholds. A point is named by its place v in `valid`.
class OutlineTest {
 public:
  OutlineTest(const std::vector<Vec3f>& projected, const std::vector<float>& spacing_px,
              const neighbourhood::Neighbourhoods& neighbourhoods, std::vector<std::uint32_t> valid, double mean_px,
              const ContourOptions& o)
      : projected_(projected), spacing_px_(spacing_px), neighbourhoods_(neighbourhoods), o_(o),
        valid_(std::move(valid)), uv_(image_positions(projected, valid_)),
        grid_(uv_, o.radius_factor * static_cast<float>(mean_px)), threshold_(o.gap_threshold_deg * kDegToRad),
        octant_shortcut_(o.gap_threshold_deg >= 90.f), cos_cone_(std::cos(o.confirm_half_angle_deg * kDegToRad)) {}

  /// The boundary points, ascending, less those near the border.
  OutlinePoints run(const std::vector<std::uint8_t>& border) const {
    const std::vector<char> inside = inside_by_3d_neighbours();
    std::vector<char> is_boundary(valid_.size(), 0);
    std::vector<Vec2f> outward(valid_.size(), Vec2f::Zero());
    // The 2D queries run in the grid's cell order so that neighbouring queries scan the same cells (cache).
    const std::vector<std::uint32_t>& grid_order = grid_.order();
    const auto test = [&](std::size_t begin, std::size_t end) {
      Scratch scratch;
      for (std::size_t g = begin; g != end; ++g) {
        const std::size_t v = grid_order[g];
        if (inside[v]) continue;
        const float r = o_.radius_factor * spacing_px_[valid_[v]];
        if (octant_shortcut_ && octants_filled(v, r)) continue;
        const std::optional<Vec2f> bisector = gap_bisector(v, r, scratch);
        if (bisector && confirmed(v, r, *bisector)) {
          is_boundary[v] = 1;
          outward[v] = *bisector;
        }
      }
    };
    pcsketch::detail::parallel_chunks(valid_.size(), o_.progress, "contour points", test);
    const std::vector<std::uint8_t> near_border = border_band(border, neighbourhoods_, o_.interior_neighbours);
    OutlinePoints outline;
    for (std::size_t v = 0; v < valid_.size(); ++v)
      if (is_boundary[v] && (near_border.empty() || !near_border[valid_[v]])) {
        outline.boundary.push_back(valid_[v]);
        outline.outward.push_back(outward[v]);
      }
    return outline;
  }

 private:
  static std::vector<Vec2f> image_positions(const std::vector<Vec3f>& projected,
                                            const std::vector<std::uint32_t>& valid) {
    std::vector<Vec2f> uv(valid.size());
    for (std::size_t v = 0; v < valid.size(); ++v) uv[v] = projected[valid[v]].head<2>();
    return uv;
  }

  /// Pre-filter: a point whose own 3D neighbours, projected, leave no gap over the threshold (and no empty
  /// quadrant) is inside the projection: nothing projects beyond the outline, so an outline point's neighbours
  /// leave a gap of about 180°. True of most points; it costs no 2D query. It runs in index order, where the 3D
  /// neighbourhoods are close in memory. All zero when the shortcut is off or there are no neighbourhoods.
  std::vector<char> inside_by_3d_neighbours() const {
    std::vector<char> inside(valid_.size(), 0);
    if (!octant_shortcut_ || neighbourhoods_.size() != projected_.size() || neighbourhoods_.k == 0) return inside;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, valid_.size(), 256), [&](const auto& range) {
      std::vector<Vec2f> dirs;
      for (std::size_t v = range.begin(); v != range.end(); ++v) inside[v] = surrounded(valid_[v], dirs);
    });
    return inside;
  }

  /// All eight 45° sectors filled settles it without angles; irregular or foreshortened neighbourhoods (two thirds
  /// of the bunny's vertices) need the gap.
  bool surrounded(std::uint32_t i, std::vector<Vec2f>& dirs) const {
    const Vec2f p = projected_[i].head<2>();
    const float min_d2 = 1e-8f * spacing_px_[i] * spacing_px_[i];
    unsigned octants = 0;
    dirs.clear();
    for (const std::uint32_t j : neighbourhoods_.of(i)) {
      const Vec2f c = projected_[j].head<2>() - p;
      if (spacing_px_[j] > 0 && c.squaredNorm() > min_d2) {
        octants |= octant_bit(c);
        dirs.push_back(c);
      }
    }
    if (octants == 0xFFu) return true;
    if (((octants | (octants >> 4)) & 0xFu) != 0xFu) return false;
    return !gap_exceeds(dirs, threshold_);
  }

  /// Points within r filling all eight 45° sectors: no gap reaches 90° (interior). The scan for them starts at v's
  /// own cell, which most often settles it.
  bool octants_filled(std::size_t v, float r) const {
    unsigned filled = 0;
    return !grid_.for_each_within_until_centre_first(uv_[v], r, [&](std::uint32_t j, float d2) {
      if (d2 > 1e-8f * r * r) filled |= octant_bit(uv_[j] - uv_[v]);  // self and duplicates: no direction
      return filled != 0xFFu;
    });
  }

  /// The bisector of the largest gap among v's k nearest within r (gathered in the grid's order) when that gap
  /// exceeds the threshold or, with quadrant_test, a quadrant is empty; nothing otherwise.
  std::optional<Vec2f> gap_bisector(std::size_t v, float r, Scratch& scratch) const {
    std::vector<std::pair<float, std::uint32_t>>& near = scratch.near;
    std::vector<Vec2f>& dirs = scratch.dirs;
    near.clear();
    grid_.for_each_within(uv_[v], r, [&](std::uint32_t j, float d2) {
      if (d2 > 1e-8f * r * r) near.emplace_back(d2, j);
    });
    if (near.size() > o_.k) {
      std::nth_element(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(o_.k), near.end());
      near.resize(o_.k);
    }
    dirs.clear();
    unsigned octants = 0;
    for (const auto& [d2, j] : near) {
      const Vec2f c = uv_[j] - uv_[v];
      dirs.push_back(c);
      octants |= octant_bit(c);
    }
    // Quadrant q holds octants q and q + 4.
    const bool empty_quadrant = ((octants | (octants >> 4)) & 0xFu) != 0xFu;
    if (!((o_.quadrant_test && empty_quadrant) || gap_exceeds(dirs, threshold_))) return std::nullopt;
    return largest_gap(scratch.angles, dirs).second;
  }

  /// Confirmation: outside a true outline the empty region goes on, while a sampling hole inside the outline
  /// (random sampling leaves some of about r) is closed beyond it.
  bool confirmed(std::size_t v, float r, const Vec2f& bisector) const {
    bool cone_empty = true;
    if (o_.confirm_factor > 1)
      grid_.for_each_within(uv_[v], o_.confirm_factor * r, [&](std::uint32_t j, float d2) {
        if (!cone_empty || d2 <= r * r) return;
        const Vec2f c = uv_[j] - uv_[v];
        if (c.dot(bisector) > cos_cone_ * std::sqrt(d2)) cone_empty = false;
      });
    return cone_empty;
  }

  const std::vector<Vec3f>& projected_;
  const std::vector<float>& spacing_px_;
  const neighbourhood::Neighbourhoods& neighbourhoods_;
  const ContourOptions& o_;
  const std::vector<std::uint32_t> valid_;
  const std::vector<Vec2f> uv_;
  const PointGrid<2> grid_;
  const float threshold_;
  const bool octant_shortcut_;
  const float cos_cone_;
};

}  // namespace

OutlinePoints find_outline_points(const std::vector<Vec3f>& projected, const std::vector<float>& spacing_px,
                                  const neighbourhood::Neighbourhoods& neighbourhoods,
                                  const std::vector<std::uint8_t>& border, const ContourOptions& o) {
  // Points behind a perspective eye are left out of the image-plane analysis.
  std::vector<std::uint32_t> valid;
  valid.reserve(projected.size());
  double mean_px = 0;
  for (std::size_t i = 0; i < projected.size(); ++i)
    if (spacing_px[i] > 0) {
      valid.push_back(static_cast<std::uint32_t>(i));
      mean_px += spacing_px[i];
    }
  if (valid.empty()) return {};
  mean_px /= static_cast<double>(valid.size());
  // Points a quarter spacing apart in the image tell the outline test nothing new: one of each such cell is asked.
  // The spacing is a low percentile of the points' own, so that the dense parts of an uneven cloud keep theirs.
  // It is read before `valid` is moved from.
  const float cell = kImageCellFactor * low_spacing(spacing_px, valid);
  valid = first_in_image_cells(projected, std::move(valid), cell);
  return OutlineTest(projected, spacing_px, neighbourhoods, std::move(valid), mean_px, o).run(border);
}

}  // namespace pcsketch::view::detail
