#include "pcsketch/features/trace_lines.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/angles.h"
#include "core/progress.h"
#include "pcsketch/core/error.h"
#include "pcsketch/neighbourhood/kd_tree.h"

namespace pcsketch::features {
namespace {

struct Vertex {
  Vec3f position;
  float curvature;
  std::uint32_t point;  // index into the feature subset
};

// Traces the lines of one kind over the subset of points carrying that label.
class KindTracer {
 public:
  KindTracer(std::vector<Vec3f> points, std::vector<float> curvature, float radius, float corridor, float cos_max_turn)
      : points_(std::move(points)),
        curvature_(std::move(curvature)),
        tree_(points_),
        used_(points_.size(), false),
        radius_(radius),
        corridor_(corridor),
        cos_max_turn_(cos_max_turn) {}

  std::size_t size() const { return points_.size(); }
  bool used(std::uint32_t i) const { return used_[i]; }

  // Grows the line seeded at feature point `seed`; empty when it cannot grow (isolated seed, nothing ahead either way).
  std::vector<Vertex> trace(std::uint32_t seed, bool& closed) {
    closed = false;
    gather(points_[seed], radius_);
    if (found_.size() < 2) {
      used_[seed] = true;  // isolated point: noise, no line through it
      return {};
    }
    const Vertex start = make_vertex(found_);
    Vec3f dir = principal_axis(found_, start.position).value_or(farthest_direction(found_, start.position));
    std::vector<Vertex> forward = grow(start, dir, &closed);
    std::vector<Vertex> backward;
    if (!closed) backward = grow(start, -dir, nullptr);
    std::vector<Vertex> line(backward.rbegin(), backward.rend());
    line.push_back(start);
    line.insert(line.end(), forward.begin(), forward.end());
    if (line.size() == 1) {
      // No growth either way: only the seed is spent, so a bad start cannot punch a hole into a band.
      used_[seed] = true;
      return {};
    }
    use_up(line, closed);
    return line;
  }

 private:
  // Unused feature points within `r` of `centre` into found_.
  void gather(const Vec3f& centre, float r) {
    tree_.radius(centre, r, hits_, distances_);
    found_.clear();
    for (std::uint32_t j : hits_)
      if (!used_[j]) found_.push_back(j);
  }

  Vertex make_vertex(const std::vector<std::uint32_t>& set) const {
    Vec3f mean = Vec3f::Zero();
    double k = 0;
    for (std::uint32_t j : set) {
      mean += points_[j];
      k += curvature_[j];
    }
    mean /= static_cast<float>(set.size());
    std::uint32_t nearest = set.front();
    for (std::uint32_t j : set)
      if ((points_[j] - mean).squaredNorm() < (points_[nearest] - mean).squaredNorm()) nearest = j;
    return {mean, static_cast<float>(k / static_cast<double>(set.size())), nearest};
  }

  // Principal axis of the points of `set` around `centre`; none when the set is too small or not elongated.
  std::optional<Vec3f> principal_axis(const std::vector<std::uint32_t>& set, const Vec3f& centre) const {
    if (set.size() < 3) return std::nullopt;
    Eigen::Matrix3f cov = Eigen::Matrix3f::Zero();
    for (std::uint32_t j : set) {
      const Vec3f d = points_[j] - centre;
      cov += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> solver;
    solver.computeDirect(cov);
    const Eigen::Vector3f lambda = solver.eigenvalues();  // ascending
    // An elongation below 2:1 (in variance) gives no reliable direction (a blob at a corner).
    if (!(lambda[2] > 2.f * lambda[1])) return std::nullopt;
    return Vec3f(solver.eigenvectors().col(2).normalized());
  }

  // Moves `v` across `dir` to the middle of the band: the mean lateral offset of the unused feature points within r
  // of it and inside the corridor. A window of 2r along the band averages many more points than one step holds.
  void recentre(Vertex& v, const Vec3f& dir) {
    tree_.radius(v.position, radius_, hits_, distances_);
    Vec3f lateral = Vec3f::Zero();
    int count = 0;
    for (std::uint32_t j : hits_) {
      if (used_[j]) continue;
      const Vec3f offset = points_[j] - v.position;
      const Vec3f across = offset - offset.dot(dir) * dir;
      if (across.norm() > corridor_) continue;
      lateral += across;
      ++count;
    }
    if (count > 0) v.position += lateral / static_cast<float>(count);
  }

  // Without a clear principal axis (two or three points, a blob): towards the farthest of the points.
  Vec3f farthest_direction(const std::vector<std::uint32_t>& set, const Vec3f& centre) const {
    Vec3f best = Vec3f::Zero();
    for (std::uint32_t j : set)
      if ((points_[j] - centre).squaredNorm() > best.squaredNorm()) best = points_[j] - centre;
    return best.squaredNorm() > 0.f ? Vec3f(best.normalized()) : Vec3f::UnitX();
  }

  // Feature points of found_ ahead of `centre` along `dir` and inside the corridor, with their advance.
  void ahead(const Vec3f& centre, const Vec3f& dir) {
    ahead_.clear();
    for (std::uint32_t j : found_) {
      const Vec3f offset = points_[j] - centre;
      const float t = offset.dot(dir);
      if (t > 0.f && (offset - t * dir).norm() <= corridor_) ahead_.push_back({j, t});
    }
  }

  std::vector<Vertex> grow(const Vertex& start, Vec3f dir, bool* closed) {
    std::vector<Vertex> out;
    Vec3f centre = start.position;
    float length = 0.f;
    const float min_advance = 0.05f * radius_;
    for (std::size_t step = 0; step < points_.size(); ++step) {
      gather(centre, radius_);
      ahead(centre, dir);
      if (ahead_.empty()) break;
      float tmax = 0.f;
      for (const auto& [j, t] : ahead_) tmax = std::max(tmax, t);
      // The farther half of the points ahead: their mean is the next centre, in the middle of the band.
      step_set_.clear();
      for (const auto& [j, t] : ahead_)
        if (t >= 0.5f * tmax) step_set_.push_back(j);
      Vertex next = make_vertex(step_set_);
      recentre(next, dir);
      const float advance = (next.position - centre).dot(dir);
      if (advance < min_advance) break;
      if (closed && length > 3.f * radius_ && (next.position - start.position).norm() < 0.75f * radius_) {
        *closed = true;
        break;
      }
      length += (next.position - centre).norm();
      out.push_back(next);
      const Vec3f previous = centre;
      centre = next.position;
      gather(centre, radius_);
      // Direction at the new centre: PCA of the feature points around it inside the corridor of the old direction
      // (other lines crossing or meeting here stay out), falling back on the step direction.
      local_.clear();
      for (std::uint32_t j : found_) {
        const Vec3f offset = points_[j] - centre;
        if ((offset - offset.dot(dir) * dir).norm() <= corridor_) local_.push_back(j);
      }
      Vec3f next_dir = principal_axis(local_, centre).value_or(Vec3f((centre - previous).normalized()));
      if (next_dir.dot(dir) < 0.f) next_dir = -next_dir;
      // A sharper turn than max_turn within one step is a corner where another feature line meets this one.
      if (next_dir.dot(dir) < cos_max_turn_) break;
      dir = next_dir;
    }
    return out;
  }

  // Marks the feature points within the corridor of the line's segments as used.
  void use_up(const std::vector<Vertex>& line, bool closed) {
    const std::size_t n = line.size();
    const std::size_t segments = n < 2 ? 1 : (closed ? n : n - 1);
    for (std::size_t s = 0; s < segments; ++s) {
      const Vec3f& a = line[s].position;
      const Vec3f& b = line[(s + 1) % n].position;
      tree_.radius(0.5f * (a + b), 0.5f * (b - a).norm() + corridor_, hits_, distances_);
      for (std::uint32_t j : hits_)
        if (!used_[j] && segment_distance(points_[j], a, b) <= corridor_) used_[j] = true;
    }
    for (const Vertex& v : line) used_[v.point] = true;
  }

  static float segment_distance(const Vec3f& p, const Vec3f& a, const Vec3f& b) {
    const Vec3f ab = b - a;
    const float len2 = ab.squaredNorm();
    const float t = len2 > 0.f ? std::clamp((p - a).dot(ab) / len2, 0.f, 1.f) : 0.f;
    return (p - (a + t * ab)).norm();
  }

  std::vector<Vec3f> points_;
  std::vector<float> curvature_;
  neighbourhood::KdTree tree_;
  std::vector<bool> used_;
  float radius_, corridor_, cos_max_turn_;
  std::vector<std::uint32_t> hits_, found_, step_set_, local_;
  std::vector<float> distances_;
  std::vector<std::pair<std::uint32_t, float>> ahead_;
};

}  // namespace

TraceResult trace_lines(const std::vector<Vec3f>& points, const std::vector<PointLabel>& labels,
                        const std::vector<float>& feature_curvature, float spacing, const TraceOptions& options,
                        const ProgressFn& progress) {
  if (labels.size() != points.size() || feature_curvature.size() != points.size())
    throw Error("ridge/valley tracing: labels and curvatures must have one entry per point");
  if (!(options.corridor_fraction > 0.f && options.corridor_fraction <= 1.f))
    throw Error("ridge/valley tracing: corridor fraction must be in (0, 1]");
  if (!(options.max_turn_deg > 0.f && options.max_turn_deg <= 90.f))
    throw Error("ridge/valley tracing: max turn must be in (0, 90] degrees");
  TraceResult result;
  result.radius = options.radius ? *options.radius : options.radius_factor * spacing;
  if (!(result.radius > 0.f) || !std::isfinite(result.radius))
    throw Error("ridge/valley tracing: the radius r must be positive (is the spacing h zero?)");

  struct Seeded {
    std::uint32_t seed;
    Polyline line;
  };
  std::vector<Seeded> all;
  const auto features = static_cast<std::size_t>(
      std::count_if(labels.begin(), labels.end(), [](PointLabel l) { return l != PointLabel::None; }));
  pcsketch::detail::ProgressSteps steps(progress, "ridge/valley tracing", features);
  std::size_t seeds_done = 0;
  for (PointLabel kind : {PointLabel::Ridge, PointLabel::Valley}) {
    std::vector<std::uint32_t> subset;  // feature index -> point index, increasing
    for (std::uint32_t i = 0; i < points.size(); ++i)
      if (labels[i] == kind) subset.push_back(i);
    if (subset.empty()) continue;
    std::vector<Vec3f> sub_points(subset.size());
    std::vector<float> sub_curvature(subset.size());
    for (std::size_t s = 0; s < subset.size(); ++s) {
      sub_points[s] = points[subset[s]];
      sub_curvature[s] = feature_curvature[subset[s]];
    }
    KindTracer tracer(std::move(sub_points), std::move(sub_curvature), result.radius,
                      options.corridor_fraction * result.radius,
                      std::cos(options.max_turn_deg * pcsketch::detail::kDegToRad));
    for (std::uint32_t s = 0; s < tracer.size(); ++s) {
      steps.at(seeds_done + s);
      if (tracer.used(s)) continue;
      bool closed = false;
      const std::vector<Vertex> vertices = tracer.trace(s, closed);
      if (vertices.empty()) continue;
      Polyline line;
      line.kind = kind == PointLabel::Ridge ? LineKind::Ridge : LineKind::Valley;
      line.closed = closed;
      for (const Vertex& v : vertices) {
        line.points.push_back(v.position);
        line.curvature.push_back(v.curvature);
        line.point_index.push_back(subset[v.point]);
      }
      all.push_back({subset[s], std::move(line)});
    }
    seeds_done += subset.size();
  }
  steps.finish();
  std::stable_sort(all.begin(), all.end(), [](const Seeded& a, const Seeded& b) { return a.seed < b.seed; });
  for (Seeded& s : all) {
    result.seeds.push_back(s.seed);
    result.lines.push_back(std::move(s.line));
  }
  return result;
}

}  // namespace pcsketch::features
