#pragma once
// Ground truth computed from a triangle mesh: its sharp edges, the occluding contours and sharp edges a camera sees,
// and a precision/recall score of drawn lines against them. Used by the feature and view tests and by benches
// scoring drawings.

#include <array>
#include <cstdint>
#include <vector>

#include "pcsketch/core/drawing.h"
#include "pcsketch/core/point_cloud.h"
#include "pcsketch/view/camera.h"
#include "pcsketch/view/visibility.h"

namespace pcsketch::test {

/// How mesh edges are sampled in the image and their visibility decided (occluding contours and sharp edges alike).
struct MeshContourOptions {
  /// Edges are sampled every this many pixels (image distance).
  float sample_step_px = 0.5f;
  /// A sample is visible when some pixel within this many pixels (a (2w+1)² window) holds a depth not in front of
  /// it: at a silhouette the pixels on its far side show the background or a farther surface, while a sample behind
  /// an occluder sees only nearer depths around it. 1 gives a ±1 px fuzz at the occluder's own silhouette.
  int depth_window = 1;
  /// Depth tolerance of that test, in pixel sizes (model units per pixel at the sample's depth).
  float depth_tolerance_px = 2.0f;
};

/// What a camera sees of a mesh's occluding contours.
struct MeshContours {
  /// Occluding contour edges (between a front- and a back-facing face) and boundary edges, 3D, relative coordinates.
  std::vector<std::array<Vec3f, 2>> edges;
  std::vector<Vec2f> visible;  ///< image positions (pixels) of the visible samples along those edges
  std::vector<Vec2f> hidden;   ///< image positions of the hidden samples
};

/// Occluding contours of `mesh` seen by `camera`, their visibility decided by a z-buffer of the mesh rasterised at
/// the camera's image size (perspective depths interpolated as 1/depth). Samples outside the image are dropped.
MeshContours mesh_contours(const Mesh& mesh, const view::Camera& camera, const MeshContourOptions& options = {});

/// Sharp edges of a mesh, 3D, relative coordinates.
struct SharpEdges {
  std::vector<std::array<Vec3f, 2>> convex, concave;
};

/// Edges of `mesh` shared by exactly two faces whose normals differ by more than `degrees`. An edge is convex when
/// the far vertex of its second face lies below the plane of its first face (faces wound with outward normals).
SharpEdges sharp_edges(const Mesh& mesh, float degrees);

/// Image samples of some edges, sorted by visibility.
struct EdgeSamples {
  std::vector<Vec2f> visible;  ///< image positions (pixels) of the visible samples
  std::vector<Vec2f> hidden;   ///< image positions of the hidden samples
};

/// What a camera sees of a mesh's sharp edges.
struct MeshSharpEdges {
  SharpEdges edges;     ///< every sharp edge, seen or not
  EdgeSamples convex;   ///< samples of the convex edges (ground truth of ridge lines)
  EdgeSamples concave;  ///< samples of the concave edges (ground truth of valley lines)
};

/// The sharp edges of `mesh` (dihedral angle above `degrees`) seen by `camera`: sampled in the image and their
/// visibility decided by the same z-buffer test as mesh_contours(). Samples outside the image are dropped.
MeshSharpEdges mesh_sharp_edges(const Mesh& mesh, const view::Camera& camera, float degrees,
                                const MeshContourOptions& options = {});

/// Precision and recall of drawn lines against ground truth, both given as dense 2D samples.
struct LineMatch {
  double precision = 0;  ///< fraction of drawn samples within the tolerance of a ground-truth sample
  double recall = 0;     ///< fraction of ground-truth samples within the tolerance of a drawn sample
  std::size_t drawn = 0, truth = 0;
};

/// For each of `queries`, whether a point of `targets` lies within `tolerance_px` (image positions, pixels).
std::vector<bool> matched_samples(const std::vector<Vec2f>& queries, const std::vector<Vec2f>& targets,
                                  float tolerance_px);
/// Scores `drawn` against `truth` (image positions, pixels) with a tolerance in pixels. Empty sets score 0.
LineMatch match_lines(const std::vector<Vec2f>& drawn, const std::vector<Vec2f>& truth, float tolerance_px);

/// #W·#H flags, row-major: the pixels whose centre the mesh covers as seen by `camera` (its filled silhouette).
std::vector<std::uint8_t> mesh_silhouette(const Mesh& mesh, const view::Camera& camera);

/// Image positions (pixel centres) of the covered pixels of mesh_silhouette() with an uncovered 4-neighbour or on the
/// image's edge: the mesh's outline, which on a coarse mesh is steadier truth than its faceted contour edges.
std::vector<Vec2f> mesh_outline(const Mesh& mesh, const view::Camera& camera);

/// Samples of a 2D polyline every `step_px` pixels (vertices included).
std::vector<Vec2f> sample_polyline(const std::vector<Vec2f>& points, bool closed, float step_px);

/// Image samples (every `step_px`) of the visible strokes of one kind of a drawing.
std::vector<Vec2f> sample_visible_strokes(const Drawing& drawing, LineKind kind, float step_px = 0.5f);

/// Image samples (every `step_px`) of the runs of `lines` of the given kind: visible runs, or hidden ones.
std::vector<Vec2f> sample_view_lines(const std::vector<view::ViewLine>& lines, LineKind kind, bool visible,
                                     float step_px = 0.5f);

}  // namespace pcsketch::test
