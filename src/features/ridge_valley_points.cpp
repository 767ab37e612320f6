#include "pcsketch/features/ridge_valley_points.h"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "core/angles.h"
#include "core/parallel_chunks.h"
#include "pcsketch/core/error.h"

namespace pcsketch::features {
namespace {

// The value at percentile `pct` (0–100, nearest rank) of `values`, which it reorders. 0 for an empty set.
float percentile(std::vector<float>& values, float pct) {
  if (values.empty()) return 0.f;
  const auto rank = static_cast<std::size_t>(std::ceil(static_cast<double>(pct) / 100.0 * static_cast<double>(values.size())));
  const std::size_t nth = std::min(values.size() - 1, rank == 0 ? 0 : rank - 1);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(nth), values.end());
  return values[nth];
}

void check_options(const DetectionOptions& o) {
  const auto fail = [](const std::string& what) { throw Error("ridge/valley detection: " + what); };
  if (!(o.ridge_threshold_alpha > 0.f && o.ridge_threshold_alpha < 1.f)) fail("ridge threshold alpha must be in (0, 1)");
  if (!(o.extreme_percentile > 0.f && o.extreme_percentile <= 100.f)) fail("extreme percentile must be in (0, 100]");
  if (!(o.saliency_floor >= 0.f)) fail("saliency floor must be >= 0");
  if (!(o.median_factor >= 0.f)) fail("median factor must be >= 0");
  if (!(o.suppression_cone_deg > 0.f && o.suppression_cone_deg < 90.f)) fail("suppression cone must be in (0, 90) degrees");
}

}  // namespace

float feature_curvature(const differential::Curvature& curvature, std::size_t i) {
  return std::abs(curvature.k1[i]) >= std::abs(curvature.k2[i]) ? curvature.k1[i] : curvature.k2[i];
}

const Vec3f& feature_direction(const differential::Curvature& curvature, std::size_t i) {
  return std::abs(curvature.k1[i]) >= std::abs(curvature.k2[i]) ? curvature.dir1[i] : curvature.dir2[i];
}

DetectionResult detect_ridge_valley_points(const std::vector<Vec3f>& points, const differential::Curvature& curvature,
                                           const neighbourhood::Neighbourhoods& neighbourhoods, float spacing,
                                           const DetectionOptions& options, const ProgressFn& progress) {
  check_options(options);
  const std::size_t n = points.size();
  if (curvature.k1.size() != n || curvature.k2.size() != n || curvature.dir1.size() != n || curvature.dir2.size() != n)
    throw Error("ridge/valley detection: curvature arrays do not have one entry per point (run estimate_curvature)");
  const bool salient = options.rule == DetectionRule::Salient;
  if (salient && options.non_maximum_suppression && neighbourhoods.size() != n)
    throw Error("ridge/valley detection: neighbourhoods do not have one entry per point");
  if (salient && !(spacing > 0.f)) throw Error("ridge/valley detection: the mean spacing h must be positive");

  DetectionResult result;
  result.feature_curvature.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) result.feature_curvature[i] = feature_curvature(curvature, i);
  });
  const std::vector<float>& k = result.feature_curvature;

  // Extremes of each side, as magnitudes.
  std::vector<float> convex, concave, magnitude;
  for (float v : k) {
    if (v > 0.f) convex.push_back(v);
    else if (v < 0.f) concave.push_back(-v);
  }
  if (options.extreme == CurvatureExtreme::MinMax) {
    result.convex_extreme = convex.empty() ? 0.f : *std::max_element(convex.begin(), convex.end());
    result.concave_extreme = concave.empty() ? 0.f : -*std::max_element(concave.begin(), concave.end());
  } else {
    result.convex_extreme = percentile(convex, options.extreme_percentile);
    result.concave_extreme = -percentile(concave, options.extreme_percentile);
  }
  float ridge_min = options.ridge_threshold_alpha * result.convex_extreme;
  float valley_min = options.ridge_threshold_alpha * -result.concave_extreme;
  if (salient) {
    magnitude.resize(n);
    std::transform(k.begin(), k.end(), magnitude.begin(), [](float v) { return std::abs(v); });
    const float floor = std::max(options.saliency_floor / spacing, options.median_factor * percentile(magnitude, 50.f));
    ridge_min = std::max(ridge_min, floor);
    valley_min = std::max(valley_min, floor);
  }
  // A side without any point of that sign has extreme 0: no point can be "beyond" it.
  ridge_min = std::max(ridge_min, std::numeric_limits<float>::min());
  valley_min = std::max(valley_min, std::numeric_limits<float>::min());
  result.ridge_threshold = ridge_min;
  result.valley_threshold = -valley_min;

  const bool suppress = salient && options.non_maximum_suppression;
  const float cone_cos = std::cos(options.suppression_cone_deg * pcsketch::detail::kDegToRad);
  result.labels.assign(n, PointLabel::None);
  pcsketch::detail::parallel_chunks(n, progress, "ridge/valley detection", [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i != end; ++i) {
      const float ki = k[i];
      PointLabel label = PointLabel::None;
      if (ki >= ridge_min) label = PointLabel::Ridge;
      else if (-ki >= valley_min) label = PointLabel::Valley;
      if (label != PointLabel::None && suppress) {
        // A neighbour across the ridge (within the cone around dir) with a stronger curvature of the same sign wins;
        // equal values are broken by index so that exactly one of two tied points survives. A stronger feature of the
        // opposite sign wins too: the quadric fit around a sharp edge overshoots into a weaker lobe of the other sign
        // beside it (a valley line 1–2h off a convex edge), and two real features closer than the fit's support are
        // not resolved by it anyway.
        const Vec3f& dir = feature_direction(curvature, i);
        const float sign = label == PointLabel::Ridge ? 1.f : -1.f;
        const float opposite_min = label == PointLabel::Ridge ? valley_min : ridge_min;
        const float kself = sign * ki;
        for (std::uint32_t j : neighbourhoods.of(i)) {
          const Vec3f offset = points[j] - points[i];
          const float along = std::abs(offset.dot(dir));
          if (along < cone_cos * offset.norm() || along == 0.f) continue;
          const float kj = sign * k[j];
          if (kj > kself || (kj == kself && j < i) || (-kj > kself && -kj >= opposite_min)) {
            label = PointLabel::None;
            break;
          }
        }
      }
      result.labels[i] = label;
    }
  });
  for (PointLabel l : result.labels) {
    result.ridge_points += l == PointLabel::Ridge;
    result.valley_points += l == PointLabel::Valley;
  }
  return result;
}

}  // namespace pcsketch::features
