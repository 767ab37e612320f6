#pragma once
// One consistent normal orientation over the whole cloud.

#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::differential {

/// How each connected component is turned outward once its normals agree.
enum class OutwardRule {
  /// Σ n_i·(p_i − c) > 0 over the component (c its centroid): by the divergence theorem this sum is 3× the enclosed
  /// volume for outward normals on a closed, evenly sampled surface. Uses every point, so one outlier cannot flip it.
  Volume,
  /// The point farthest from the centroid must face away from it (one point decides, as in Hoppe et al.).
  FarthestPoint,
  /// Keep the sign propagation gives (the root of each component keeps its input sign).
  None,
};

/// When the normals of two neighbours p, q agree in sign, and how sure that is (the weight of their graph edge).
enum class OrientCriterion {
  /// n_q mirrored in the plane bisecting p and q, against n_p (König and Gumhold 2009): exact for any circular arc
  /// through p and q, so a 90° edge, whose two faces have perpendicular normals, is crossed as surely as a flat face.
  /// Default: on the fandisk's own vertices the Parallel rule leaves a third of the normals inward.
  Reflect,
  /// The sign and magnitude of n_p·n_q (Hoppe et al. 1992): undecided where a sharp edge turns the normal by 90°.
  Parallel,
};

struct OrientOptions {
  /// Neighbours per point used as graph edges; 0 = all of the shared neighbourhood (its k). Fewer edges are faster
  /// but may split thin parts into separate components.
  std::size_t k = 0;
  /// Agreement test of two neighbours' normals (see OrientCriterion).
  OrientCriterion criterion = OrientCriterion::Reflect;
  /// Rule turning each component outward (Volume by default: robust to outliers, unlike the farthest point).
  OutwardRule outward = OutwardRule::Volume;
  ProgressFn progress;  ///< optional
};

struct OrientResult {
  std::size_t components = 0;  ///< connected components of the neighbour graph, each oriented on its own
  std::size_t flipped = 0;     ///< normals whose sign was changed
  Warnings warnings;
};

/// Flips normals in place so that neighbours agree (propagation along a maximum-confidence spanning tree of the
/// neighbour graph, Hoppe et al. 1992, with the agreement test of `options.criterion`), then turns each component
/// outward by `options.outward`.
/// The tree is built by Kruskal's algorithm over the agreement's magnitude quantised to 4096 levels, with a
/// union-find that tracks relative signs, in two rounds: first inside blocks of 8192 consecutive points (spatially sorted clouds
/// make these compact patches), in parallel; then over the edges between blocks, joining the block trees. Linear
/// time, deterministic for any thread count; it differs from one global tree only where a block's best internal
/// path is worse than a detour outside it. Zero normals are left as they are. Expects spatially sorted points
/// (reorder_spatially) for speed and block compactness; any order gives a consistent result.
/// `noise_sigma`: the cloud's estimated noise σ̂, model units (analyse_surface passes its estimate; 0: none). Two
/// neighbours stacked along their normals (the line between them within 37° of both) and no farther apart along
/// them than 3 σ̂ lie on one sheet, offset by noise: their mirror plane is about the tangent plane, and Reflect would
/// read them as opposed with full confidence (a noisy cube's faces came out inward, their edges drawn as valleys).
/// They are compared as Parallel. A thin part's two sides lie farther apart and keep Reflect.
/// @throws pcsketch::Error if the sizes disagree
OrientResult orient_normals(const std::vector<Vec3f>& points, std::vector<Vec3f>& normals,
                            const neighbourhood::Neighbourhoods& neighbourhoods, const OrientOptions& options = {},
                            float noise_sigma = 0);

/// Fraction of the k-NN pairs (i, j) whose normals surely disagree in sign: agreement below −0.5 by `criterion`
/// (see OrientCriterion). A consistently oriented surface gives almost none (bunny samples 0, hippo1.ply's file
/// normals 0.0000); normals whose signs are arbitrary give many (building.ply's file normals 0.098).
/// `noise_sigma`: as in orient_normals, pairs stacked by the noise are compared as Parallel.
/// @throws pcsketch::Error if the sizes disagree
double sign_disagreement(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                         const neighbourhood::Neighbourhoods& neighbourhoods,
                         OrientCriterion criterion = OrientCriterion::Reflect, float noise_sigma = 0);

}  // namespace pcsketch::differential
