#include "pcsketch/features/ridge_valley_lines.h"

#include <chrono>
#include <nlohmann/json.hpp>
#include <string>

#include "pcsketch/core/error.h"

namespace pcsketch::features {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

RidgeValleyLines extract_ridge_valley_lines(const PointCloud& cloud, const differential::Surface& surface,
                                            const RidgeValleyOptions& options) {
  if (surface.curvature.k1.size() != cloud.size() || surface.neighbourhoods.size() != cloud.size())
    throw Error("ridge/valley lines: the surface analysis has " + std::to_string(surface.curvature.k1.size()) +
                " points, the cloud " + std::to_string(cloud.size()) + " (run analyse_surface on this cloud)");
  RidgeValleyLines result;
  auto start = std::chrono::steady_clock::now();
  result.detection = detect_ridge_valley_points(cloud.positions, surface.curvature, surface.neighbourhoods,
                                                surface.spacing, options.detection, options.progress);
  result.timings.detection = seconds_since(start);

  start = std::chrono::steady_clock::now();
  TraceResult traced = trace_lines(cloud.positions, result.detection.labels, result.detection.feature_curvature,
                                   surface.spacing, options.tracing, options.progress);
  result.timings.tracing = seconds_since(start);
  result.radius = traced.radius;

  start = std::chrono::steady_clock::now();
  // Joining passes over line ends only (thousands, not millions): reported at its start and end.
  const ProgressReporter report_joining(options.progress, "ridge/valley joining");
  report_joining(0.0);
  JoinResult joined = join_lines(std::move(traced.lines), traced.radius, surface.spacing, options.joining);
  report_joining(1.0);
  result.timings.joining = seconds_since(start);
  result.lines = std::move(joined.lines);
  const DetectionResult& d = result.detection;
  if (d.ridge_points + d.valley_points == 0)
    result.warnings.push_back("ridge/valley lines: no point passed the detection (ridge threshold " +
                              std::to_string(d.ridge_threshold) + ", valley threshold " +
                              std::to_string(d.valley_threshold) + "); lower alpha or the saliency floor for more");
  else if (result.lines.empty())
    result.warnings.push_back("ridge/valley lines: " + std::to_string(d.ridge_points + d.valley_points) +
                              " ridge/valley points but no line long enough survived; lower the minimum length or "
                              "raise the tracing radius");
  result.joins = joined.joins;
  result.dropped = joined.dropped;
  return result;
}

}  // namespace pcsketch::features
