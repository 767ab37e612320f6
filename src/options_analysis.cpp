// The option table (options_table.h), part 1: surface analysis, ridges and valleys, borders, camera, contours and
// visibility. Ranges are the ones validate() enforces; the help is the --help text.

#include "options_fields.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"
#include "pcsketch/validate.h"

namespace pcsketch::options::detail {

namespace {

constexpr double kMaxK = neighbourhood::kMaxNeighbours;

/// Stray points and noise (group "Surface analysis").
void add_cleaning(Builder& b) {
  b.add(PCSKETCH_OPTION(surface.outliers.enabled),
        {.flag = "--keep-outliers",
         .negated = true,
         .help = "Draw every point (default: stray points far sparser than the cloud, and detached clumps, are left "
                 "out)"});
  b.add(PCSKETCH_OPTION(surface.outliers.k),
        {.range = closed(1, kMaxK), .help = "Neighbours of the outlier distance statistic"});
  b.add(PCSKETCH_OPTION(surface.outliers.density_factor),
        {.flag = "--outlier-density",
         .range = closed(1, 1000),
         .help = "A point is stray when its mean distance to its 8 nearest exceeds this times the cloud's median and "
                 "no denser point is near"});
  b.add(PCSKETCH_OPTION(surface.outliers.link_factor),
        {.range = positive(1e4), .unit = "median distances", .help = "Dense points this close are one cluster"});
  b.add(PCSKETCH_OPTION(surface.outliers.offset_factor),
        {.range = positive(1e4),
         .unit = "median distances",
         .help = "A point this far off its neighbours' plane is stray"});
  b.add(PCSKETCH_OPTION(surface.outliers.sheet_variation),
        {.range = closed(0, 1),
         .help = "A sparse point whose neighbours spread round a plane with at most this share of their variance "
                 "across it is sparser surface, not stray (0: off)"});
  b.add(PCSKETCH_OPTION(surface.outliers.min_cluster),
        {.flag = "--outlier-min-cluster",
         .range = closed(1, 1 << 30),
         .help = "Detached clumps with fewer points are left out (at least 0.05% of the cloud)"});
  b.add(PCSKETCH_OPTION(surface.outliers.min_cluster_fraction),
        {.range = closed(0, 1), .help = "Detached clumps with fewer than this fraction of the points are left out"});
  b.add(PCSKETCH_OPTION(surface.scan_lines.enabled),
        {.flag = "--keep-scan-lines",
         .negated = true,
         .help = "Keep every point of a cloud on scan lines (default: points far denser along lines than across "
                 "them are thinned to the lines' spacing)"});
  b.add(PCSKETCH_OPTION(surface.scan_lines.linearity),
        {.range = closed(0, 1), .help = "8 nearest neighbours make a line under this ratio of PCA eigenvalues λ2/λ1"});
  b.add(PCSKETCH_OPTION(surface.scan_lines.min_fraction),
        {.range = closed(0, 1), .help = "A cloud lies on scan lines when more of its neighbourhoods than this are lines"});
  b.add(PCSKETCH_OPTION(surface.scan_lines.min_anisotropy),
        {.range = closed(1, 1e6),
         .help = "...and its lines lie this many times farther apart than their points along them"});
  b.add(PCSKETCH_OPTION(surface.scan_lines.majority_fraction),
        {.range = closed(0, 1),
         .help = "Where more of the neighbourhoods than this are lines, they need only lie farther apart by..."});
  b.add(PCSKETCH_OPTION(surface.scan_lines.majority_min_anisotropy),
        {.range = closed(1, 1e6), .help = "...this many times their points' spacing along them"});
  b.add(PCSKETCH_OPTION(surface.scan_lines.noisy_dimension),
        {.range = closed(0, 2),
         .help = "Noisy scan lines: the cloud's median local dimension falls to this at 8 to 64 neighbours (0: not "
                 "sought)"});
  b.add(PCSKETCH_OPTION(surface.scan_lines.cell_factor),
        {.range = positive(100), .unit = "line spacings", .help = "Cube edge of the thinning of scan lines"});
  b.add(PCSKETCH_OPTION(surface.denoise.enabled),
        {.flag = "--no-denoise",
         .negated = true,
         .help = "Keep noisy points where they are (default: a cloud whose estimated noise exceeds --denoise-trigger "
                 "is denoised, edges kept sharp)"});
  b.add(PCSKETCH_OPTION(surface.denoise.min_noise_factor),
        {.flag = "--denoise-trigger",
         .range = closed(0, 100),
         .unit = "units of h",
         .help = "Denoise when the estimated noise sigma exceeds this many h"});
  b.add(PCSKETCH_OPTION(surface.denoise.iterations),
        {.flag = "--denoise-iterations",
         .range = closed(1, 100),
         .help = "Denoising rounds (normals filtered, points moved onto their neighbours' tangent planes)"});
  b.add(PCSKETCH_OPTION(surface.denoise.normal_passes),
        {.flag = "--denoise-passes",
         .range = closed(0, 100),
         .help = "Bilateral normal-filtering passes per denoising round"});
  b.add(PCSKETCH_OPTION(surface.denoise.normal_cutoff),
        {.flag = "--denoise-cutoff",
         .range = closed(0.001, 1),
         .help = "Normals differing by 1-|cos| of at least this are not averaged (0.15: creases over 32 degrees stay "
                 "sharp)"});
}

void add_surface(Builder& b) {
  b.group("Surface analysis");
  b.add(PCSKETCH_OPTION(surface.neighbourhood.k), {.flag = "--neighbours",
                                                   .range = closed(3, kMaxK),
                                                   .help = "Paper's k: neighbours per point (normals, curvature)"});
  b.add(PCSKETCH_OPTION(surface.recompute_normals),
        {.flag = "--recompute-normals", .help = "Ignore the file's normals, estimate them by PCA"});
  // --file-normals auto|trust|orient sets both of these (cli/options.cpp).
  b.add(PCSKETCH_OPTION(surface.orient_file_normals),
        {.flag = "--file-normals",
         .cli = Cli::HandWritten,
         .help = "Re-orient file normals always (--file-normals orient; auto: only when their signs disagree, "
                 "trust: never)"});
  b.add(PCSKETCH_OPTION(surface.file_normal_disagreement),
        {.flag = "--file-normals",
         .cli = Cli::HandWritten,
         .range = closed(0, 1),
         .help = "File normals are re-oriented when more than this fraction of neighbour pairs disagree in sign "
                 "(trust: 1)"});
  b.add(PCSKETCH_OPTION(surface.reorder), {.help = "Sort points along a space-filling curve first (faster)"});
  add_cleaning(b);
  b.add(PCSKETCH_OPTION(surface.normals.k),
        {.range = closed(0, kMaxK), .help = "Neighbours of the PCA normals (0: --neighbours)"});
  b.add(PCSKETCH_OPTION(surface.orientation.k),
        {.range = closed(0, kMaxK), .help = "Neighbours of the orientation graph (0: --neighbours)"});
  b.choice(PCSKETCH_OPTION(surface.orientation.criterion), {"reflect", "parallel"},
           {.flag = "--orientation",
            .help = "Normal orientation test: reflect (König-Gumhold, crosses sharp edges) or parallel (Hoppe's "
                    "|n_i.n_j|)"});
  b.choice(PCSKETCH_OPTION(surface.orientation.outward), {"volume", "farthest", "none"},
           {.flag = "--outward",
            .help = "Turning each part of the cloud outward: volume (sum of n.(p - centroid) > 0, robust), farthest "
                    "(the farthest point faces away, Hoppe's) or none"});
  b.add(PCSKETCH_OPTION(surface.curvature.k),
        {.range = closed(0, kMaxK), .help = "Neighbours of the quadric fit (0: --neighbours)"});
  b.add(PCSKETCH_OPTION(surface.curvature.adapt_to_noise),
        {.help = "Widen the curvature fits on noisy clouds (up to max_k neighbours)"});
  b.add(PCSKETCH_OPTION(surface.curvature.noise_tolerance),
        {.range = non_negative(), .help = "Noise share of the fit residual tolerated before the fits widen"});
  b.add(PCSKETCH_OPTION(surface.curvature.max_k),
        {.range = closed(0, 2 * kMaxK), .help = "Most neighbours of a widened curvature fit"});
}

void add_detection(Builder& b) {
  b.group("Ridge/valley detection (paper IV.A)");
  // α = 0 would make every point a ridge/valley point (and fail late): a positive fraction.
  b.add(PCSKETCH_OPTION(features.detection.ridge_threshold_alpha),
        {.flag = "--alpha",
         .range = open(0, 1),
         .help = "Paper's alpha: a ridge/valley point's |k| is at least alpha times the extreme curvature of its "
                 "side (smaller: more points)"});
  b.choice(PCSKETCH_OPTION(features.detection.rule), {"paper", "salient"},
           {.flag = "--detection",
            .help = "salient (paper's rule + saliency floors and non-maximum suppression) or paper (the plain rule)"});
  b.choice(
      PCSKETCH_OPTION(features.detection.extreme), {"percentile", "minmax"},
      {.flag = "--extreme", .help = "Extreme curvature of each side: percentile (robust) or minmax (the paper's)"});
  b.add(PCSKETCH_OPTION(features.detection.extreme_percentile),
        {.flag = "--extreme-percentile", .range = above(0, 100), .help = "Percentile taken as the extreme, 0-100"});
  b.add(PCSKETCH_OPTION(features.detection.saliency_floor),
        {.flag = "--saliency-floor",
         .range = non_negative(),
         .help = "Salient rule: |k|*h must reach this (radius of curvature at most h/floor)"});
  b.add(PCSKETCH_OPTION(features.detection.median_factor),
        {.flag = "--median-factor",
         .range = non_negative(),
         .help = "Salient rule: |k| must reach this times the median |k|"});
  b.add(PCSKETCH_OPTION(features.detection.non_maximum_suppression),
        {.flag = "--no-suppression",
         .negated = true,
         .help = "Salient rule: keep the whole band of high curvature (no non-maximum suppression across ridges)"});
  b.add(PCSKETCH_OPTION(features.detection.suppression_cone_deg),
        {.flag = "--suppression-cone",
         .range = closed(1, 89),
         .unit = "degrees",
         .help = "Half-angle around the principal direction in which neighbours compete"});
}

/// The flags of the tracing and joining options of one kind of line; empty: JSON only.
struct LineFlags {
  std::string radius, radius_abs, corridor, max_turn, join_distance, beta, min_length, min_length_abs, smooth,
      smooth_weight;
};

/// Tracing and joining options, shared by ridge/valley lines (`prefix` features) and border lines (boundary);
/// `lines` reaches the RidgeValleyOptions or BoundaryOptions holding them.
template <class Lines>
void add_trace_join(Builder& b, const std::string& prefix, Lines lines, const LineFlags& f) {
  const std::string t = prefix + ".tracing.", j = prefix + ".joining.";
  b.add(t + "radius_factor", [lines](DrawOptions & o) -> auto& { return lines(o).tracing.radius_factor; },
        {.flag = f.radius, .range = positive(1e4), .unit = "units of h", .help = "Paper's r: tracing radius"});
  b.add(t + "radius", [lines](DrawOptions & o) -> auto& { return lines(o).tracing.radius; },
        {.flag = f.radius_abs,
         .range = positive(),
         .unit = "model units",
         .help = "Tracing radius r in model units (overrides the radius in h)"});
  b.add(t + "corridor_fraction", [lines](DrawOptions & o) -> auto& { return lines(o).tracing.corridor_fraction; },
        {.flag = f.corridor,
         .range = closed(0.01, 1),
         .unit = "fraction of r",
         .help = "Corridor half-width around the direction"});
  b.add(t + "max_turn_deg", [lines](DrawOptions & o) -> auto& { return lines(o).tracing.max_turn_deg; },
        {.flag = f.max_turn,
         .range = closed(1, 90),
         .unit = "degrees",
         .help = "Sharpest turn per step before a line ends"});
  b.add(j + "join_distance_alpha", [lines](DrawOptions & o) -> auto& { return lines(o).joining.join_distance_alpha; },
        {.flag = f.join_distance,
         .range = non_negative(1e4),
         .unit = "multiples of r",
         .help = "Join endpoints closer than this times r (paper: alpha*r)"});
  b.add(j + "join_angle_beta_deg", [lines](DrawOptions & o) -> auto& { return lines(o).joining.join_angle_beta_deg; },
        {.flag = f.beta,
         .range = closed(0, 90),
         .unit = "degrees",
         .help = "Paper's beta: largest angle between end tangents (facing each other) when joining lines"});
  b.add(j + "min_length_factor", [lines](DrawOptions & o) -> auto& { return lines(o).joining.min_length_factor; },
        {.flag = f.min_length, .range = non_negative(), .unit = "units of h", .help = "Drop lines shorter than this"});
  b.add(j + "min_length", [lines](DrawOptions & o) -> auto& { return lines(o).joining.min_length; },
        {.flag = f.min_length_abs,
         .range = non_negative(),
         .unit = "model units",
         .help = "Minimum line length in model units (overrides the length in h)"});
  b.add(j + "smoothing_iterations", [lines](DrawOptions & o) -> auto& { return lines(o).joining.smoothing_iterations; },
        {.flag = f.smooth, .range = closed(0, 100), .help = "Laplacian smoothing passes (endpoints fixed), 0 = off"});
  b.add(j + "smoothing_weight", [lines](DrawOptions & o) -> auto& { return lines(o).joining.smoothing_weight; },
        {.flag = f.smooth_weight, .range = closed(0, 1), .help = "Weight of one smoothing pass, 0-1"});
}

void add_features_lines(Builder& b) {
  b.group("Ridge/valley tracing and joining (paper IV.A)");
  add_trace_join(b, "features", [](DrawOptions & o) -> auto& { return o.features; },
                 {"--radius", "--radius-abs", "--corridor", "--max-turn", "--join-distance", "--beta", "--min-length",
                  "--min-length-abs", "--smooth", "--smooth-weight"});
}

void add_boundary(Builder& b) {
  b.group("Borders of open scans");
  b.add(PCSKETCH_OPTION(boundary.enabled),
        {.flag = "--no-boundary-detection",
         .negated = true,
         .help = "No border of open scans: every point may be outline, and hole rims seen through are drawn as "
                 "contours"});
  b.add(PCSKETCH_OPTION(boundary.gap_threshold_deg),
        {.flag = "--boundary-gap",
         .range = open(0, 360),
         .unit = "degrees",
         .help = "A border point's neighbours leave a gap wider than this in its tangent plane"});
  b.add(PCSKETCH_OPTION(boundary.fold_deg),
        {.range = above(0, 90),
         .unit = "degrees",
         .help = "A gap whose far side folds away by more than this is a crease, not a border"});
  b.add(
      PCSKETCH_OPTION(boundary.edge_band_fraction),
      {.range = closed(0, 1),
       .help = "A border point's neighbours reach at most this fraction of the neighbourhood radius towards its gap"});
  b.add(PCSKETCH_OPTION(boundary.confirm_factor),
        {.range = closed(1, 1e3),
         .help = "Confirmation: no point in the gap's cone out to this times the farthest shared neighbour"});
  b.add(PCSKETCH_OPTION(boundary.confirm_half_angle_deg),
        {.range = open(0, 90),
         .unit = "degrees",
         .help = "Half-angle of the confirmation cone around the gap's bisector"});
  b.add(PCSKETCH_OPTION(boundary.min_size_factor),
        {.flag = "--boundary-min-size",
         .range = non_negative(1e6),
         .unit = "units of h",
         .help = "Borders spanning less than this are small holes: not drawn"});
  add_trace_join(b, "boundary", [](DrawOptions & o) -> auto& { return o.boundary; }, {.radius = "--boundary-radius"});
}

}  // namespace

void add_analysis_options(Builder& b) {
  add_surface(b);
  add_detection(b);
  add_features_lines(b);
  add_boundary(b);
  add_view_options(b);
}

}  // namespace pcsketch::options::detail
