#include "support/mesh_ground_truth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

namespace pcsketch::test {

namespace {

/// Min-depth buffer of the mesh; depth +inf where nothing is drawn.
struct DepthBuffer {
  int width = 0, height = 0;
  std::vector<float> depth;

  float at(int x, int y) const { return depth[static_cast<std::size_t>(y) * width + x]; }
};

DepthBuffer rasterise(const Mesh& mesh, const view::Camera& camera) {
  DepthBuffer buffer{camera.width, camera.height,
                     std::vector<float>(static_cast<std::size_t>(camera.width) * camera.height,
                                        std::numeric_limits<float>::infinity())};
  const bool perspective = camera.projection == view::Projection::Perspective;
  std::vector<Vec3f> projected(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) projected[i] = camera.project(mesh.vertices[i]);
  for (const auto& face : mesh.faces) {
    const Vec3f a = projected[face[0]], b = projected[face[1]], c = projected[face[2]];
    if (perspective && (a.z() <= 0 || b.z() <= 0 || c.z() <= 0)) continue;
    const float area = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (std::abs(area) < 1e-12f) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
    const int x1 = std::min(camera.width - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
    const int y1 = std::min(camera.height - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const float px = static_cast<float>(x) + 0.5f, py = static_cast<float>(y) + 0.5f;
        const float wa = ((b.x() - px) * (c.y() - py) - (c.x() - px) * (b.y() - py)) / area;
        const float wb = ((c.x() - px) * (a.y() - py) - (a.x() - px) * (c.y() - py)) / area;
        const float wc = 1.f - wa - wb;
        if (wa < 0 || wb < 0 || wc < 0) continue;
        // Perspective: 1/depth is affine in the image.
        const float d = perspective ? 1.f / (wa / a.z() + wb / b.z() + wc / c.z())
                                    : wa * a.z() + wb * b.z() + wc * c.z();
        float& slot = buffer.depth[static_cast<std::size_t>(y) * buffer.width + x];
        slot = std::min(slot, d);
      }
  }
  return buffer;
}

/// A uniform grid of 2D samples for "any sample within r" queries.
class SampleGrid {
 public:
  SampleGrid(const std::vector<Vec2f>& pts, float cell) : pts_(pts), cell_(cell) {
    if (pts.empty()) return;
    lo_ = hi_ = pts[0];
    for (const Vec2f& p : pts) {
      lo_ = lo_.cwiseMin(p);
      hi_ = hi_.cwiseMax(p);
    }
    nx_ = static_cast<int>((hi_.x() - lo_.x()) / cell_) + 1;
    ny_ = static_cast<int>((hi_.y() - lo_.y()) / cell_) + 1;
    start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    std::vector<std::size_t> cell_of(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
      cell_of[i] = index(cell_x(pts[i].x()), cell_y(pts[i].y()));
      ++start_[cell_of[i] + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    order_.resize(pts.size());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < pts.size(); ++i) order_[fill[cell_of[i]]++] = i;
  }

  bool any_within(const Vec2f& q, float r) const {
    if (pts_.empty()) return false;
    const int ax = cell_x(q.x() - r), bx = cell_x(q.x() + r), ay = cell_y(q.y() - r), by = cell_y(q.y() + r);
    for (int y = ay; y <= by; ++y)
      for (int x = ax; x <= bx; ++x) {
        const std::size_t c = index(x, y);
        for (std::size_t k = start_[c]; k < start_[c + 1]; ++k)
          if ((pts_[order_[k]] - q).squaredNorm() <= r * r) return true;
      }
    return false;
  }

 private:
  int cell_x(float x) const { return std::clamp(static_cast<int>(std::floor((x - lo_.x()) / cell_)), 0, nx_ - 1); }
  int cell_y(float y) const { return std::clamp(static_cast<int>(std::floor((y - lo_.y()) / cell_)), 0, ny_ - 1); }
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * nx_ + x; }

  const std::vector<Vec2f>& pts_;
  float cell_;
  Vec2f lo_ = Vec2f::Zero(), hi_ = Vec2f::Zero();
  int nx_ = 1, ny_ = 1;
  std::vector<std::size_t> start_;
  std::vector<std::size_t> order_;
};

double fraction_matched(const std::vector<Vec2f>& queries, const std::vector<Vec2f>& targets, float tolerance) {
  if (queries.empty()) return 0;
  const std::vector<bool> hit = matched_samples(queries, targets, tolerance);
  return static_cast<double>(std::count(hit.begin(), hit.end(), true)) / static_cast<double>(queries.size());
}

/// The faces around one edge of a mesh.
struct EdgeFaces {
  std::uint32_t u = 0, v = 0;        ///< its vertices, u < v
  std::vector<std::uint32_t> faces;  ///< in increasing order
};

/// Every edge of `mesh` with the faces around it, edges in increasing (u, v) order.
std::vector<EdgeFaces> edge_faces(const Mesh& mesh) {
  std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> incidences;
  incidences.reserve(3 * mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t u = mesh.faces[f][e], v = mesh.faces[f][(e + 1) % 3];
      incidences.emplace_back(std::min(u, v), std::max(u, v), static_cast<std::uint32_t>(f));
    }
  std::sort(incidences.begin(), incidences.end());
  std::vector<EdgeFaces> out;
  for (const auto& [u, v, f] : incidences) {
    if (out.empty() || out.back().u != u || out.back().v != v) out.push_back({u, v, {}});
    out.back().faces.push_back(f);
  }
  return out;
}

/// Samples `edges` in the image every `options.sample_step_px` and sorts the samples by the z-buffer test (see
/// MeshContourOptions); samples outside the image, or behind a perspective eye, are dropped.
EdgeSamples sample_edges(const std::vector<std::array<Vec3f, 2>>& edges, const DepthBuffer& buffer,
                         const view::Camera& camera, const MeshContourOptions& options) {
  EdgeSamples out;
  for (const auto& [a, b] : edges) {
    const Vec3f pa = camera.project(a), pb = camera.project(b);
    const float length_px = (pb.head<2>() - pa.head<2>()).norm();
    const int steps = std::max(1, static_cast<int>(std::ceil(length_px / options.sample_step_px)));
    for (int s = 0; s <= steps; ++s) {
      const Vec3f p = a + (b - a) * (static_cast<float>(s) / static_cast<float>(steps));
      const Vec3f q = camera.project(p);
      const int x = static_cast<int>(std::floor(q.x())), y = static_cast<int>(std::floor(q.y()));
      if (x < 0 || y < 0 || x >= camera.width || y >= camera.height) continue;
      if (camera.projection == view::Projection::Perspective && q.z() <= 0) continue;
      const float tolerance = options.depth_tolerance_px * camera.units_per_pixel(q.z());
      bool seen = false;
      for (int dy = -options.depth_window; dy <= options.depth_window && !seen; ++dy)
        for (int dx = -options.depth_window; dx <= options.depth_window && !seen; ++dx) {
          const int xx = std::clamp(x + dx, 0, camera.width - 1), yy = std::clamp(y + dy, 0, camera.height - 1);
          seen = buffer.at(xx, yy) >= q.z() - tolerance;
        }
      (seen ? out.visible : out.hidden).push_back(q.head<2>());
    }
  }
  return out;
}

/// Unnormalised normal of face `f`: (b - a) × (c - a).
Vec3f face_normal(const Mesh& mesh, std::size_t f) {
  const Vec3f& a = mesh.vertices[mesh.faces[f][0]];
  return (mesh.vertices[mesh.faces[f][1]] - a).cross(mesh.vertices[mesh.faces[f][2]] - a);
}

}  // namespace

std::vector<std::uint8_t> mesh_silhouette(const Mesh& mesh, const view::Camera& camera) {
  const DepthBuffer buffer = rasterise(mesh, camera);
  std::vector<std::uint8_t> covered(buffer.depth.size());
  for (std::size_t i = 0; i < covered.size(); ++i) covered[i] = std::isfinite(buffer.depth[i]);
  return covered;
}

std::vector<Vec2f> mesh_outline(const Mesh& mesh, const view::Camera& camera) {
  const std::vector<std::uint8_t> covered = mesh_silhouette(mesh, camera);
  const int w = camera.width, h = camera.height;
  const auto inside = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && covered[y * w + x] != 0; };
  std::vector<Vec2f> out;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (inside(x, y) && !(inside(x - 1, y) && inside(x + 1, y) && inside(x, y - 1) && inside(x, y + 1)))
        out.emplace_back(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
  return out;
}

MeshContours mesh_contours(const Mesh& mesh, const view::Camera& camera, const MeshContourOptions& options) {
  // Facing of every face: front when its normal points toward the viewer.
  std::vector<char> front(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Vec3f centre =
        (mesh.vertices[mesh.faces[f][0]] + mesh.vertices[mesh.faces[f][1]] + mesh.vertices[mesh.faces[f][2]]) / 3.f;
    front[f] = face_normal(mesh, f).dot(camera.ray_direction(centre)) < 0 ? 1 : 0;
  }
  MeshContours out;
  for (const EdgeFaces& edge : edge_faces(mesh)) {
    const auto fronts = static_cast<std::size_t>(
        std::count_if(edge.faces.begin(), edge.faces.end(), [&](std::uint32_t f) { return front[f] != 0; }));
    if (edge.faces.size() == 1 || (fronts > 0 && fronts < edge.faces.size()))
      out.edges.push_back({mesh.vertices[edge.u], mesh.vertices[edge.v]});
  }
  EdgeSamples samples = sample_edges(out.edges, rasterise(mesh, camera), camera, options);
  out.visible = std::move(samples.visible);
  out.hidden = std::move(samples.hidden);
  return out;
}

SharpEdges sharp_edges(const Mesh& mesh, float degrees) {
  const float cos_limit = std::cos(degrees * std::numbers::pi_v<float> / 180.f);
  SharpEdges out;
  for (const EdgeFaces& edge : edge_faces(mesh)) {
    if (edge.faces.size() != 2) continue;
    const Vec3f n0 = face_normal(mesh, edge.faces[0]).normalized(), n1 = face_normal(mesh, edge.faces[1]).normalized();
    if (n0.dot(n1) > cos_limit) continue;
    std::uint32_t far = 0;
    for (std::uint32_t v : mesh.faces[edge.faces[1]])
      if (v != edge.u && v != edge.v) far = v;
    const std::array<Vec3f, 2> segment{mesh.vertices[edge.u], mesh.vertices[edge.v]};
    ((mesh.vertices[far] - segment[0]).dot(n0) < 0.f ? out.convex : out.concave).push_back(segment);
  }
  return out;
}

MeshSharpEdges mesh_sharp_edges(const Mesh& mesh, const view::Camera& camera, float degrees,
                                const MeshContourOptions& options) {
  MeshSharpEdges out{.edges = sharp_edges(mesh, degrees)};
  const DepthBuffer buffer = rasterise(mesh, camera);
  out.convex = sample_edges(out.edges.convex, buffer, camera, options);
  out.concave = sample_edges(out.edges.concave, buffer, camera, options);
  return out;
}

std::vector<bool> matched_samples(const std::vector<Vec2f>& queries, const std::vector<Vec2f>& targets,
                                  float tolerance_px) {
  const SampleGrid grid(targets, std::max(tolerance_px, 1e-3f));
  std::vector<bool> hit(queries.size());
  for (std::size_t i = 0; i < queries.size(); ++i) hit[i] = grid.any_within(queries[i], tolerance_px);
  return hit;
}

LineMatch match_lines(const std::vector<Vec2f>& drawn, const std::vector<Vec2f>& truth, float tolerance_px) {
  LineMatch m;
  m.drawn = drawn.size();
  m.truth = truth.size();
  m.precision = fraction_matched(drawn, truth, tolerance_px);
  m.recall = fraction_matched(truth, drawn, tolerance_px);
  return m;
}

std::vector<Vec2f> sample_polyline(const std::vector<Vec2f>& points, bool closed, float step_px) {
  std::vector<Vec2f> out;
  const std::size_t n = points.size();
  if (n == 0) return out;
  const std::size_t segments = closed && n > 2 ? n : n - 1;
  out.push_back(points[0]);
  for (std::size_t s = 0; s < segments; ++s) {
    const Vec2f a = points[s], b = points[(s + 1) % n];
    const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step_px)));
    for (int k = 1; k <= steps; ++k) out.push_back(a + (b - a) * (static_cast<float>(k) / static_cast<float>(steps)));
  }
  return out;
}

std::vector<Vec2f> sample_visible_strokes(const Drawing& drawing, LineKind kind, float step_px) {
  std::vector<Vec2f> out;
  for (const Stroke& s : drawing.strokes) {
    if (s.kind != kind || !s.visible) continue;
    const std::vector<Vec2f> samples = sample_polyline(s.image_points, s.closed, step_px);
    out.insert(out.end(), samples.begin(), samples.end());
  }
  return out;
}

std::vector<Vec2f> sample_view_lines(const std::vector<view::ViewLine>& lines, LineKind kind, bool visible,
                                     float step_px) {
  std::vector<Vec2f> out;
  for (const view::ViewLine& line : lines) {
    if (line.line.kind != kind) continue;
    for (const view::LineRun& run : line.runs) {
      if (run.visible != visible) continue;
      std::vector<Vec2f> image(run.projected.size());
      for (std::size_t i = 0; i < image.size(); ++i) image[i] = run.projected[i].head<2>();
      const std::vector<Vec2f> samples = sample_polyline(image, false, step_px);
      out.insert(out.end(), samples.begin(), samples.end());
    }
  }
  return out;
}

}  // namespace pcsketch::test
