#include "options.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>

#include "pcsketch/core/atomic_file.h"
#include "pcsketch/core/error.h"
#include "pcsketch/validate.h"

namespace pcsketch::cli {

namespace {

template <class T>
constexpr bool is_optional = false;
template <class T>
constexpr bool is_optional<std::optional<T>> = true;

/// An option with a check on its value, in `group`; --help shows its default (an unset override has none).
template <class T>
CLI::Option* add_checked(CLI::App* cmd, const std::string& name, T& target, const std::string& help,
                         const CLI::Validator& check, const std::string& group) {
  CLI::Option* option = cmd->add_option(name, target, help);
  if constexpr (!is_optional<T>) option->capture_default_str();
  return option->check(check)->group(group);
}

// "xmin,ymin,zmin,xmax,ymax,zmax" → box; throws CLI::ValidationError (exit 1) otherwise.
io::CropBox parse_crop(const std::string& text) {
  std::istringstream in(text);
  std::array<double, 6> v{};
  for (std::size_t i = 0; i < v.size(); ++i) {
    char comma = ',';
    if ((i > 0 && !(in >> comma)) || comma != ',' || !(in >> v[i]) || !std::isfinite(v[i]))
      throw CLI::ValidationError("--crop", "expected six numbers xmin,ymin,zmin,xmax,ymax,zmax, got '" + text + "'");
  }
  if (!(in >> std::ws).eof())
    throw CLI::ValidationError("--crop", "expected six numbers xmin,ymin,zmin,xmax,ymax,zmax, got '" + text + "'");
  const io::CropBox box{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
  if ((box.min.array() > box.max.array()).any())
    throw CLI::ValidationError("--crop", "each minimum must be at most its maximum, got '" + text + "'");
  return box;
}

}  // namespace

void add_read_options(CLI::App* cmd, io::ReadOptions& read) {
  const std::string group = "Input";
  cmd->add_option_function<std::string>(
         "--columns",
         [&read](const std::string& spec) {
           try {
             read.columns = io::parse_columns(spec);
           } catch (const Error& e) {
             throw CLI::ValidationError("--columns", e.what());
           }
         },
         "Text files: what each column holds, e.g. x,y,z,r,g,b (names: x y z r g b i nx ny nz skip); default: "
         "the header row, else guessed from the values")
      ->group(group);
  cmd->add_option("--classes", read.classes, "LAS: keep only these classifications, e.g. 2,6 (ground, building)")
      ->delimiter(',')
      ->check(CLI::Range(0, 255))
      ->group(group);
  cmd->add_option("--drop-classes", read.drop_classes, "LAS: remove these classifications, e.g. 7 (noise)")
      ->delimiter(',')
      ->check(CLI::Range(0, 255))
      ->group(group);
  cmd->add_option_function<std::string>(
         "--crop", [&read](const std::string& s) { read.crop = parse_crop(s); },
         "Keep only the points in this box, in the file's coordinates: xmin,ymin,zmin,xmax,ymax,zmax")
      ->group(group);
  cmd->add_option("--voxel", read.decimate.voxel,
                  "Thin to one point per cube of this edge (model units), the one nearest its centre")
      ->check(CLI::PositiveNumber)
      ->group(group);
  cmd->add_option("--max-points", read.decimate.max_points,
                  "Thin to at most this many points with the smallest voxel that gets there (at least 8)")
      ->check(CLI::Range(std::size_t{8}, std::numeric_limits<std::size_t>::max()))
      ->group(group);
}

std::string describe_reduction(const io::ReadResult& read) {
  std::string out;
  if (read.dropped_by_filter > 0)
    out += std::to_string(read.dropped_by_filter) + " outside the crop box or of classes not kept";
  if (read.decimation) {
    const io::DecimateReport& d = *read.decimation;
    char text[160];
    std::snprintf(text, sizeof text, "voxel thinning %zu -> %zu points (cell %.6g, %.3f s)", d.points_before,
                  d.points_after, d.cell, d.seconds);
    out += (out.empty() ? "" : "; ") + std::string(text);
  }
  return out;
}

void add_surface_options(CLI::App* cmd, differential::SurfaceOptions& surface) {
  const std::string group = "Surface analysis";
  add_checked(cmd, "--neighbours", surface.neighbourhood.k, "Paper's k: neighbours per point (normals, curvature)",
              CLI::Range(3, 256), group);
  cmd->add_flag("--recompute-normals", surface.recompute_normals, "Ignore the file's normals, estimate them by PCA")
      ->group(group);
  cmd->add_option_function<std::string>(
         "--file-normals",
         [&surface](const std::string& mode) {
           surface.orient_file_normals = mode == "orient";
           if (mode == "trust") surface.file_normal_disagreement = 1.0;
         },
         "Normals read from the file: auto (kept, but re-oriented when their signs disagree between neighbours), "
         "trust (kept as they are) or orient (always re-oriented)")
      ->check(CLI::IsMember({"auto", "trust", "orient"}))
      ->default_str("auto")
      ->group(group);
  cmd->add_flag("!--keep-outliers", surface.outliers.enabled,
                "Draw every point (default: stray points far sparser than the cloud, and detached clumps, are left "
                "out)")
      ->group(group);
  add_checked(cmd, "--outlier-density", surface.outliers.density_factor,
              "A point is stray when its mean distance to its 8 nearest exceeds this times the cloud's median and no "
              "denser point is near",
              CLI::Range(1.0, 1000.0), group);
  add_checked(cmd, "--outlier-min-cluster", surface.outliers.min_cluster,
              "Detached clumps with fewer points are left out (at least 0.05% of the cloud)", CLI::Range(1, 1 << 30),
              group);
  cmd->add_flag("!--no-denoise", surface.denoise.enabled,
                "Keep noisy points where they are (default: a cloud whose estimated noise exceeds --denoise-trigger "
                "is denoised, edges kept sharp)")
      ->group(group);
  add_checked(cmd, "--denoise-trigger", surface.denoise.min_noise_factor,
              "Denoise when the estimated noise sigma exceeds this many h", CLI::Range(0.0, 100.0), group);
  add_checked(cmd, "--denoise-iterations", surface.denoise.iterations,
              "Denoising rounds (normals filtered, points moved onto their neighbours' tangent planes)",
              CLI::Range(1, 100), group);
  add_checked(cmd, "--denoise-passes", surface.denoise.normal_passes,
              "Bilateral normal-filtering passes per denoising round", CLI::Range(0, 100), group);
  add_checked(cmd, "--denoise-cutoff", surface.denoise.normal_cutoff,
              "Normals differing by 1-|cos| of at least this are not averaged (0.15: creases over 32 degrees stay "
              "sharp)",
              CLI::Range(0.001, 1.0), group);
  // Orientation runs on estimated normals, and on file normals when --file-normals re-orients them.
  add_enum(cmd, "--orientation", surface.orientation.criterion,
           {{"reflect", differential::OrientCriterion::Reflect}, {"parallel", differential::OrientCriterion::Parallel}},
           "Normal orientation test: reflect (König-Gumhold, crosses sharp edges) or parallel (Hoppe's |n_i.n_j|)")
      ->group(group);
  add_enum(cmd, "--outward", surface.orientation.outward,
           {{"volume", differential::OutwardRule::Volume},
            {"farthest", differential::OutwardRule::FarthestPoint},
            {"none", differential::OutwardRule::None}},
           "Turning each part of the cloud outward: volume (sum of n.(p - centroid) > 0, robust), farthest (the "
           "farthest point faces away, Hoppe's) or none")
      ->group(group);
}

void add_ridge_valley_options(CLI::App* cmd, features::RidgeValleyOptions& options) {
  features::DetectionOptions& det = options.detection;
  const std::string dgroup = "Ridge/valley detection (paper IV.A)";
  add_checked(cmd, "--alpha", det.ridge_threshold_alpha,
              "Paper's alpha: a ridge/valley point's |k| is at least alpha times the extreme curvature of its "
              "side (smaller: more points)",
              CLI::Range(0.0, 1.0), dgroup);
  add_enum(cmd, "--detection", det.rule,
           {{"salient", features::DetectionRule::Salient}, {"paper", features::DetectionRule::Paper}},
           "salient (paper's rule + saliency floors and non-maximum suppression) or paper (the plain rule)")
      ->group(dgroup);
  add_enum(cmd, "--extreme", det.extreme,
           {{"percentile", features::CurvatureExtreme::Percentile}, {"minmax", features::CurvatureExtreme::MinMax}},
           "Extreme curvature of each side: percentile (robust) or minmax (the paper's)")
      ->group(dgroup);
  add_checked(cmd, "--extreme-percentile", det.extreme_percentile, "Percentile taken as the extreme, 0-100",
              CLI::Range(0.0, 100.0), dgroup);
  add_checked(cmd, "--saliency-floor", det.saliency_floor,
              "Salient rule: |k|*h must reach this (radius of curvature at most h/floor)", CLI::NonNegativeNumber,
              dgroup);
  add_checked(cmd, "--median-factor", det.median_factor, "Salient rule: |k| must reach this times the median |k|",
              CLI::NonNegativeNumber, dgroup);
  cmd->add_flag("!--no-suppression", det.non_maximum_suppression,
                "Salient rule: keep the whole band of high curvature (no non-maximum suppression across ridges)")
      ->group(dgroup);
  add_checked(cmd, "--suppression-cone", det.suppression_cone_deg,
              "Half-angle (degrees) around the principal direction in which neighbours compete", CLI::Range(1.0, 89.0),
              dgroup);

  features::TraceOptions& tr = options.tracing;
  const std::string tgroup = "Ridge/valley tracing (paper IV.A)";
  add_checked(cmd, "--radius", tr.radius_factor, "Paper's r: tracing radius in units of h (mean spacing)",
              CLI::PositiveNumber, tgroup);
  add_checked(cmd, "--radius-abs", tr.radius, "Tracing radius r in model units (overrides --radius)",
              CLI::PositiveNumber, tgroup);
  add_checked(cmd, "--corridor", tr.corridor_fraction, "Corridor half-width around the direction, fraction of r",
              CLI::Range(0.01, 1.0), tgroup);
  add_checked(cmd, "--max-turn", tr.max_turn_deg, "Sharpest turn per step (degrees) before a line ends",
              CLI::Range(1.0, 90.0), tgroup);

  features::JoinOptions& jo = options.joining;
  const std::string jgroup = "Ridge/valley joining (paper IV.A)";
  add_checked(cmd, "--join-distance", jo.join_distance_alpha,
              "Join endpoints closer than this times r (paper: alpha*r)", CLI::NonNegativeNumber, jgroup);
  add_checked(cmd, "--beta", jo.join_angle_beta_deg,
              "Paper's beta: largest angle between end tangents (facing each other) when joining lines, degrees",
              CLI::Range(0.0, 90.0), jgroup);
  add_checked(cmd, "--min-length", jo.min_length_factor, "Drop ridge/valley lines shorter than this, in units of h",
              CLI::NonNegativeNumber, jgroup);
  add_checked(cmd, "--min-length-abs", jo.min_length, "Minimum line length in model units (overrides --min-length)",
              CLI::NonNegativeNumber, jgroup);
  add_checked(cmd, "--smooth", jo.smoothing_iterations, "Laplacian smoothing passes (endpoints fixed), 0 = off",
              CLI::Range(0, 100), jgroup);
  add_checked(cmd, "--smooth-weight", jo.smoothing_weight, "Weight of one smoothing pass, 0-1", CLI::Range(0.0, 1.0),
              jgroup);
}

void add_memory_option(CLI::App* cmd, std::optional<double>& target) {
  cmd->add_option("--max-memory", target,
                  "Refuse a cloud estimated to need more memory than this, GB, before the analysis starts (about "
                  "256 + 8 x --neighbours bytes a point, plus the image buffers); default: the machine's memory")
      ->check(CLI::PositiveNumber)
      ->group("Input");
}

std::filesystem::path same_file_key(const std::string& path) {
  // Without throwing: a name the file system refuses (too long) is refused by check_output_path, with a message.
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
  if (ec) return std::filesystem::path(path).lexically_normal();
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : canonical;
}

void check_output_path(const std::string& flag, const std::string& path) {
  try {
    check_writable(path);
  } catch (const Error& e) {
    throw OptionError(flag, e.what());
  }
}

}  // namespace pcsketch::cli
