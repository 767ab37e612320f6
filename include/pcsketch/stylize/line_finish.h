#pragma once
// Line finish: what a careful illustrator does to traced lines before inking them. Polylines are smoothed by a
// filter that keeps corners (a CAD crease traced through alternating points loses its stairs, its corners stay),
// and strokes too short to read as lines (a pen dab, an ink blot) are left out.

#include <vector>

#include "pcsketch/core/polyline.h"
#include "pcsketch/stylize/thickness.h"
#include "pcsketch/view/camera.h"

namespace pcsketch::stylize {

struct FinishOptions {
  bool smooth = true;  ///< false keeps the traced vertices
  /// Taubin λ|μ passes (λ = 0.5, μ = −0.53): each pass is a low-pass over a vertex and its two neighbours that does
  /// not shrink curves. 3 removes one-vertex zigzags and stairs a few vertices long; more rounds bends.
  int smooth_passes = 3;
  /// A vertex whose bend (measured in the image over `corner_arm_px`, or over two of the line's median segments
  /// when longer) is sharper than this is a corner and does not move, degrees (180 = straight). 135: a cube's or a
  /// fandisk's corners (about 90°–120° in the image) stay, a staircase (nearly straight at that scale) is smoothed.
  float corner_angle_deg = 135.f;
  /// Arm of the corner test, px (about three pen widths). A vertex whose two segments both exceed 1.5 arms is a
  /// sample of a sparse line (a coarse cloud's outline) and keeps its place too.
  float corner_arm_px = 8.f;
  /// Lines seen over less than this (the image length of their visible runs together) are left out, px: a pen only
  /// dabs on them (1 mm is about 5 px at 1024 px on a 200 mm page). Hidden runs and hatching are kept as they are.
  float min_length_px = 5.f;
  /// A line shorter than that stays when one of its ends lies within this distance (px) of the end of a longer line:
  /// it continues that line (a contour traced in two parts) rather than standing alone as a dab.
  float join_px = 10.f;
};

/// `line` smoothed in place of its vertices (same count, same order, same per-point data): open ends, corners and
/// the vertices of sparse stretches stay, the vertices between them move toward their neighbours by
/// `options.smooth_passes` Taubin passes in 3D. Corners are found in the image of `camera`, so the drawing keeps the
/// corners it shows.
Polyline smooth_line(const Polyline& line, const view::Camera& camera, const FinishOptions& options = {});

/// Leaves out the visible strokes of every line whose visible strokes are shorter than `options.min_length_px`
/// together (image length), with their `line` entries, unless they start or end within `options.join_px` of the end
/// of a longer line's visible stroke (they continue it, as if joined to it).
/// @return how many strokes were left out.
std::size_t drop_short_strokes(StrokesResult& strokes, const FinishOptions& options = {});

}  // namespace pcsketch::stylize
