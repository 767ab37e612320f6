#pragma once
// The point cloud: parallel per-point arrays with presence checks (Open3D's PointCloud, without the methods).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pcsketch {

using Vec3f = Eigen::Vector3f;
using Vec3d = Eigen::Vector3d;
using Vec2f = Eigen::Vector2f;
using Rgb8 = std::array<std::uint8_t, 3>;

/// Axis-aligned bounding box.
struct Box3f {
  Vec3f min = Vec3f::Constant(std::numeric_limits<float>::max());
  Vec3f max = Vec3f::Constant(std::numeric_limits<float>::lowest());
  bool empty() const { return (min.array() > max.array()).any(); }
  Vec3f size() const { return empty() ? Vec3f::Zero() : Vec3f(max - min); }
  Vec3f center() const { return 0.5f * (min + max); }
  float diagonal() const { return size().norm(); }
  void extend(const Vec3f& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
};

/// A scalar per point read from the file (LAS classification, intensity, return number; an XYZ intensity column).
/// float holds every LAS field kept exactly (they are at most 16-bit integers).
struct PointAttribute {
  std::string name;           ///< "classification", "intensity", "return_number"
  std::vector<float> values;  ///< #P
};

/// A cloud of #P points. Positions are float, relative to a double `origin`, so that georeferenced scans with large
/// offsets (UTM) keep their precision: world = origin + position.
struct PointCloud {
  std::vector<Vec3f> positions;  ///< #P, relative to origin
  std::vector<Vec3f> normals;    ///< empty or #P, unit length
  std::vector<Rgb8> colors;      ///< empty or #P
  std::vector<PointAttribute> attributes;  ///< each #P
  Vec3d origin = Vec3d::Zero();  ///< world offset of every position
  /// empty or #P: index of each point in the file it was read from (after reordering, the mapping back).
  std::vector<std::uint32_t> source_index;

  std::size_t size() const { return positions.size(); }
  bool empty() const { return positions.empty(); }
  bool has_normals() const { return !positions.empty() && normals.size() == positions.size(); }
  bool has_colors() const { return !positions.empty() && colors.size() == positions.size(); }
  Vec3d world(std::size_t i) const { return origin + positions[i].cast<double>(); }
  /// The attribute called `name`, or nullptr.
  const PointAttribute* attribute(std::string_view name) const {
    for (const PointAttribute& a : attributes)
      if (a.name == name) return &a;
    return nullptr;
  }
};

/// Bounding box of the positions (relative coordinates).
Box3f bounding_box(const std::vector<Vec3f>& positions);

/// Reorders every per-point array of `cloud` by `order` (new i = old order[i]) and composes source_index with it.
void permute(PointCloud& cloud, const std::vector<std::uint32_t>& order);
/// Keeps the points `order` lists, in that order (new i = old order[i]), in every per-point array; source_index is
/// composed with it, so kept points still name their place in the file.
void select(PointCloud& cloud, const std::vector<std::uint32_t>& order);

/// Keeps the points `kept` (indices into the cloud, each at most once; new i = old kept[i]) in every per-point
/// array and removes the others. A non-empty source_index is composed; an empty one stays empty.
void keep_points(PointCloud& cloud, const std::vector<std::uint32_t>& kept);

/// A triangle mesh: #V vertices (same origin convention as PointCloud) and #F index triples.
struct Mesh {
  std::vector<Vec3f> vertices;
  std::vector<std::array<std::uint32_t, 3>> faces;
  Vec3d origin = Vec3d::Zero();
};

}  // namespace pcsketch
