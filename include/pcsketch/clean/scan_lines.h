#pragma once
// Scan lines: a scanner that sweeps lines (a LiDAR's rings, a profile or stripe scanner, a terrestrial scan at a
// grazing angle) samples densely along each line and sparsely across. A point's nearest neighbours then all lie on its
// own line: their PCA sees a line, not a surface, the gap tests of the outline and of the borders find a gap on both
// sides of every point, and h is the spacing along the lines. Drawn as they are, the lines themselves are drawn.
// Found from the shared neighbourhoods, such a cloud is thinned to one point per cube of the lines' spacing, which
// leaves it about as dense across the lines as along them (docs/geometry.md, "Scan lines").

#include <cstdint>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/neighbourhood/kd_tree.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::clean {

struct ScanLineOptions {
  bool enabled = true;  ///< off: every point is kept, whatever its neighbourhood (the paper's assumption)
  /// A point's 8 nearest neighbours make a line when their second PCA eigenvalue is under this fraction of the first.
  /// Evenly sampled surfaces have a median of 0.44–0.74 and 0–1% of their points under 0.1.
  float linearity = 0.1f;
  /// The cloud lies on scan lines when more than this fraction of the sampled points lie on a line whose nearest
  /// point off it lies on a parallel line (within 25°): evenly sampled surfaces and scans 0–0.2%, a profile scanner's
  /// 60 lines over a model's height 79–96% (bench_scans "scan lines")...
  float min_fraction = 0.05f;
  /// ...and the lines are this many times farther apart (the median distance from a point on a line to the nearest
  /// point off it) than the median nearest-neighbour distance: 11–60 on those lines. The vertices of CAD meshes whose
  /// faces hold none lie on lines too, their edges (25–46% of the points), but 5:1 apart or less.
  float min_anisotropy = 8.f;
  /// Where more than this fraction of the sampled points lie on lines (profile scans 87–100%; CAD vertices at most
  /// 46%, evenly sampled surfaces 0.2%)...
  float majority_fraction = 0.6f;
  /// ...lines this many times farther apart than the median nearest-neighbour distance are enough. Drawn as they were,
  /// a sphere's 4:1 to 6:1 rings lost their outline where it crosses them, and a 6:1 profile scan of the held-out
  /// cheese became a page of its lines (docs/geometry.md, "Scan lines").
  float majority_min_anisotropy = 3.5f;
  /// Noisy lines, whose 8 nearest points make no line: the cloud's median local dimension (log 2 over the log of the
  /// ratio of the distances to the 2m-th and m-th neighbours) falls to this at m = 8, 16 or 32 and rises past 1.8 at
  /// a larger m. Evenly sampled surfaces, noisy or not, 1.89–3.1; the 60 cuts of bench_scans with noise of 0.05–0.1%
  /// of the diagonal 1.06–1.46 (docs/geometry.md, "Scan lines"). 0: not sought.
  float noisy_dimension = 1.5f;
  /// The thinning's cube edge, in units of the lines' spacing: 0.7 keeps about 1.4 points per spacing along a line
  /// and closes the outline where 1 left gaps.
  float cell_factor = 0.7f;
  std::size_t max_samples = 4096;  ///< neighbourhoods examined, spread over the point order
};

struct ScanLines {
  /// Of the sampled points, those on a line next to a parallel one (noisy lines: those whose local dimension falls
  /// to noisy_dimension)
  double line_fraction = 0;
  /// The lines' spacing over the median nearest-neighbour distance (noisy lines: over the points' spacing along
  /// them); 0: not measured
  double anisotropy = 0;
  /// The lines' spacing, model units: the lower quartile of the distances from a point on a line to the nearest
  /// point off it (where a surface slopes along the lines they lie farther apart on it), or of noisy lines' spacing
  /// estimated from their densities. 0 when the cloud does not lie on scan lines.
  double spacing = 0;
  bool found() const { return spacing > 0; }
};

/// Whether the cloud lies on scan lines (see ScanLineOptions) and their spacing. `tree` indexes `points`.
/// Deterministic; at most max_samples k-NN queries of 64 (256 where lines lie farther apart), and where those find no
/// lines 256 queries of 256 for noisy ones, whatever #P.
/// @throws pcsketch::Error if the neighbourhoods or the tree do not match the points
ScanLines find_scan_lines(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& neighbourhoods,
                          const neighbourhood::KdTree& tree, const ScanLineOptions& options = {});

}  // namespace pcsketch::clean
