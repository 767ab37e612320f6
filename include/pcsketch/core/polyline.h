#pragma once
// Lines as every stage after detection passes them on.

#include <cstdint>
#include <string_view>
#include <vector>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch {

/// What a line depicts; also the SVG layer it is drawn in.
/// Boundary: the border of an open scan, where the surface ends (features/boundary_lines.h).
enum class LineKind : std::uint8_t { Contour, Ridge, Valley, Hatch, Boundary };

std::string_view to_string(LineKind kind);

/// An ordered 3D polyline (positions in the cloud's relative coordinates).
struct Polyline {
  LineKind kind = LineKind::Contour;
  std::vector<Vec3f> points;
  /// empty or one per point: the signed principal curvature there (ridge/valley lines).
  std::vector<float> curvature;
  /// empty or one per point: the cloud point the vertex came from.
  std::vector<std::uint32_t> point_index;
  bool closed = false;  ///< last point connects back to the first

  std::size_t size() const { return points.size(); }
  /// Sum of segment lengths (including the closing segment when closed).
  float length() const;
  /// Reverses the vertex order, and the per-vertex arrays with it.
  void reverse();
  /// Appends `other`'s vertices after this line's last (its last connects to other's first). A per-vertex array is
  /// kept only if both lines have it.
  void append(Polyline&& other);
};

}  // namespace pcsketch
