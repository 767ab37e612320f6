#include "pcsketch/differential/orient_normals.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <span>

#include "common.h"

namespace pcsketch::differential {

namespace {

constexpr std::uint32_t kLevels = 4096;     // quantisation of the edge weights
constexpr std::uint16_t kNoEdge = 0xffff;   // slot whose edge is listed by the other endpoint
constexpr std::size_t kBlockPoints = 8192;  // points per block of the first, parallel Kruskal pass
constexpr float kStackedNoise = 3;          // σ̂ within which stacked neighbours lie on one sheet

/// Union-find whose every node stores whether its normal must flip relative to its parent.
class SignedUnionFind {
 public:
  explicit SignedUnionFind(std::size_t n) : parent_(n), flip_(n, 0), size_(n, 1) {
    for (std::size_t i = 0; i < n; ++i) parent_[i] = static_cast<std::uint32_t>(i);
  }

  /// Root of x and whether x flips relative to it; compresses the path.
  std::pair<std::uint32_t, std::uint8_t> find(std::uint32_t x) {
    std::uint32_t root = x;
    std::uint8_t flip = 0;
    while (parent_[root] != root) {
      flip ^= flip_[root];
      root = parent_[root];
    }
    for (std::uint8_t to_root = flip; parent_[x] != root;) {
      const std::uint32_t next = parent_[x];
      const std::uint8_t next_to_root = to_root ^ flip_[x];
      parent_[x] = root;
      flip_[x] = to_root;
      x = next;
      to_root = next_to_root;
    }
    return {root, flip};
  }

  /// Root of x and whether x flips relative to it, read without compressing: valid once find(x) has run and no join
  /// since (find leaves x pointing at its root).
  std::pair<std::uint32_t, std::uint8_t> found(std::uint32_t x) const { return {parent_[x], flip_[x]}; }

  /// Joins the sets of a and b so that flip(a) xor flip(b) = disagree; false if already joined.
  bool join(std::uint32_t a, std::uint32_t b, std::uint8_t disagree) {
    auto [ra, fa] = find(a);
    auto [rb, fb] = find(b);
    if (ra == rb) return false;
    if (size_[ra] < size_[rb]) std::swap(ra, rb);
    parent_[rb] = ra;
    flip_[rb] = fa ^ fb ^ disagree;
    size_[ra] += size_[rb];
    return true;
  }

 private:
  std::vector<std::uint32_t> parent_;
  std::vector<std::uint8_t> flip_;
  std::vector<std::uint32_t> size_;
};

/// How far the normal of q is, as seen from p, from agreeing with the normal of p, as a cosine in [−1, 1]: its sign
/// says whether the two agree, its magnitude how sure that is.
/// Reflect: n_q mirrored in the plane bisecting p and q, against n_p. A smooth arc through p and q, a circle's or
/// a sharp edge's, maps one normal onto the other under that mirror (König and Gumhold 2009), so the pair two faces
/// of a 90° edge give is as sure as a pair on one face, where n_p·n_q is 0 and says nothing. Coincident points fall
/// back to n_p·n_q.
/// `stacked`: the offset along the normals within which a pair stacked along them is taken for one sheet
/// (orient_normals' noise_sigma).
/// Inlined by force: the compiler kept it a call, and the orientation makes one per edge (9M at 1M points).
[[gnu::always_inline]] inline float agreement(const Vec3f& p, const Vec3f& np, const Vec3f& q, const Vec3f& nq,
                                              OrientCriterion criterion, float stacked = 0) {
  const Vec3f e = q - p;
  const float length2 = e.squaredNorm();
  if (criterion == OrientCriterion::Parallel || !(length2 > 0.f)) return np.dot(nq);
  constexpr float kStackedCos2 = 0.64f;  // cos² 37°
  const float ep = np.dot(e), eq = nq.dot(e);
  if (std::abs(ep) <= stacked && std::abs(eq) <= stacked && ep * ep > kStackedCos2 * length2 &&
      eq * eq > kStackedCos2 * length2)
    return np.dot(nq);
  return np.dot(nq - (2.f * eq / length2) * e);
}

/// Weight level of an edge of agreement c: 0 for a sure one, growing as |c| falls (sqrt(1−|c|) ≈ angle/√2 spreads
/// the many nearly sure pairs over many levels).
std::uint16_t level(float c) {
  const float sure = std::min(1.f, std::abs(c));
  return static_cast<std::uint16_t>(std::min<float>(kLevels - 1, std::sqrt(1.f - sure) * float(kLevels)));
}

/// A graph edge with its weight level and whether its endpoints' normals disagree in sign.
struct Edge {
  std::uint32_t from, to;
  std::uint16_t level;
  std::uint8_t disagree;
};

/// The edges of `lists`, one list after the other, stably sorted by level, by counting (no concatenated copy).
std::vector<Edge> sort_by_level(std::span<const std::vector<Edge>> lists) {
  std::vector<std::size_t> start(kLevels + 1, 0);
  for (const std::vector<Edge>& edges : lists)
    for (const Edge& e : edges) ++start[e.level + 1];
  for (std::uint32_t l = 0; l < kLevels; ++l) start[l + 1] += start[l];
  std::vector<Edge> sorted(start[kLevels]);
  for (const std::vector<Edge>& edges : lists)
    for (const Edge& e : edges) sorted[start[e.level]++] = e;
  return sorted;
}

}  // namespace

double sign_disagreement(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                         const neighbourhood::Neighbourhoods& neighbourhoods, OrientCriterion criterion,
                         float noise_sigma) {
  const std::size_t n = points.size();
  detail::check_neighbourhoods("sign disagreement", n, neighbourhoods);
  if (normals.size() != n)
    throw Error("sign disagreement: " + std::to_string(normals.size()) + " normals for " + std::to_string(n) + " points");
  const std::size_t edges = n * neighbourhoods.k;
  if (edges == 0) return 0.0;
  const std::size_t disagreeing = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n), std::size_t{0},
      [&](const tbb::blocked_range<std::size_t>& range, std::size_t count) {
        for (std::size_t i = range.begin(); i != range.end(); ++i)
          for (const std::uint32_t j : neighbourhoods.of(i))
            count += agreement(points[i], normals[i], points[j], normals[j], criterion, kStackedNoise * noise_sigma) <
                     -0.5f;
        return count;
      },
      std::plus<>());
  return static_cast<double>(disagreeing) / static_cast<double>(edges);
}

OrientResult orient_normals(const std::vector<Vec3f>& points, std::vector<Vec3f>& normals,
                            const neighbourhood::Neighbourhoods& neighbourhoods, const OrientOptions& options,
                            float noise_sigma) {
  const std::size_t n = points.size();
  detail::check_neighbourhoods("orient normals", n, neighbourhoods);
  if (normals.size() != n)
    throw Error("orient normals: " + std::to_string(normals.size()) + " normals for " + std::to_string(n) + " points");
  const ProgressReporter report(options.progress, "orientation");
  report(0.0);
  OrientResult result;
  if (n == 0) return result;
  const std::size_t stride = neighbourhoods.k;
  const std::size_t k = detail::neighbours_used(options.k, neighbourhoods);
  // Every undirected edge is listed once: by its smaller endpoint, or by the endpoint whose list holds it when the
  // other's does not (distance at or beyond that one's k-th neighbour; ties list it twice, which is harmless).
  // Its slot (i, m) gets the edge's level, or kNoEdge, and the agreement's sign in kDisagree: the one evaluation of
  // the agreement per edge.
  constexpr std::uint16_t kDisagree = 0x8000;
  const float stacked = kStackedNoise * std::max(0.f, noise_sigma);
  const auto edge_slot = [&](std::size_t i, std::size_t m) -> std::uint16_t {
    const std::uint32_t j = neighbourhoods.indices[i * stride + m];
    // j's row is read only when i ≥ j, half the slots.
    if (i >= j && neighbourhoods.distances[i * stride + m] < neighbourhoods.distances[j * stride + k - 1])
      return kNoEdge;
    if (!(normals[i].squaredNorm() > 0 && normals[j].squaredNorm() > 0)) return kNoEdge;
    const float c = agreement(points[i], normals[i], points[j], normals[j], options.criterion, stacked);
    return static_cast<std::uint16_t>(level(c) | (c < 0 ? kDisagree : 0));
  };

  // 1. Kruskal inside fixed blocks of consecutive (spatially sorted) points, in parallel and in cache: each point
  //    gets its block tree's root and its sign relative to that root; edges leaving the block are kept for step 2.
  //    The agreements, the costly part, are evaluated in a nested parallel loop so that few blocks still use every
  //    core.
  const std::size_t blocks = (n + kBlockPoints - 1) / kBlockPoints;
  std::vector<std::uint32_t> block_root(n);
  std::vector<std::uint8_t> block_flip(n);
  std::vector<std::vector<Edge>> crossing(blocks);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    const std::size_t first = b * kBlockPoints, last = std::min(n, first + kBlockPoints);
    std::vector<std::uint16_t> slots((last - first) * k);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(first, last, 512), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i < r.end(); ++i)
        for (std::size_t m = 0; m < k; ++m) slots[(i - first) * k + m] = edge_slot(i, m);
    });
    std::vector<Edge> inside;
    for (std::size_t i = first; i < last; ++i) {
      for (std::size_t m = 0; m < k; ++m) {
        const std::uint16_t slot = slots[(i - first) * k + m];
        if (slot == kNoEdge) continue;
        const std::uint32_t j = neighbourhoods.indices[i * stride + m];
        const Edge e{static_cast<std::uint32_t>(i), j, static_cast<std::uint16_t>(slot & ~kDisagree),
                     static_cast<std::uint8_t>((slot & kDisagree) != 0)};
        (j >= first && j < last ? inside : crossing[b]).push_back(e);
      }
    }
    SignedUnionFind forest(last - first);
    const auto local = [&](std::uint32_t i) { return static_cast<std::uint32_t>(i - first); };
    for (const Edge& e : sort_by_level({&inside, 1})) forest.join(local(e.from), local(e.to), e.disagree);
    for (std::size_t i = first; i < last; ++i) {
      const auto [root, flip] = forest.find(local(static_cast<std::uint32_t>(i)));
      block_root[i] = static_cast<std::uint32_t>(root + first);
      block_flip[i] = flip;
    }
  });
  report(0.5);

  // 2. Kruskal over the crossing edges (block order, then stably by level) joining the block trees by their roots.
  //    Each edge is first restated between its endpoints' block roots, in parallel: the serial joins then touch
  //    only the few roots, in cache, instead of two random points.
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    for (Edge& e : crossing[b])
      e = {block_root[e.from], block_root[e.to], e.level,
           static_cast<std::uint8_t>(e.disagree ^ block_flip[e.from] ^ block_flip[e.to])};
  });
  SignedUnionFind trees(n);
  for (const Edge& e : sort_by_level(crossing)) trees.join(e.from, e.to, e.disagree);
  crossing = {};
  report(0.8);

  // 3. Apply the propagated signs and gather each component's centroid. The block roots are resolved serially (find
  //    compresses their paths), every point then in parallel; the centroids are summed serially, in point order.
  for (std::uint32_t r = 0; r < n; ++r)
    if (block_root[r] == r) trees.find(r);
  std::vector<std::uint8_t> flipped(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const auto [root, tree_flip] = trees.found(block_root[i]);
      block_root[i] = root;
      flipped[i] = tree_flip ^ block_flip[i];
    }
  });
  std::vector<std::uint32_t> component(n);
  std::vector<std::uint32_t> component_of_root(n, std::numeric_limits<std::uint32_t>::max());
  std::vector<Vec3d> centroid;
  std::vector<std::size_t> members;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t root = block_root[i];
    if (component_of_root[root] == std::numeric_limits<std::uint32_t>::max()) {
      component_of_root[root] = static_cast<std::uint32_t>(centroid.size());
      centroid.push_back(Vec3d::Zero());
      members.push_back(0);
    }
    component[i] = component_of_root[root];
    centroid[component[i]] += points[i].cast<double>();
    ++members[component[i]];
  }
  result.components = centroid.size();
  for (std::size_t c = 0; c < centroid.size(); ++c) centroid[c] /= static_cast<double>(members[c]);

  // 4. Turn each component outward.
  std::vector<double> vote(centroid.size(), 0.0);
  std::vector<double> farthest(centroid.size(), -1.0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t c = component[i];
    const Vec3d offset = points[i].cast<double>() - centroid[c];
    const double facing = (flipped[i] ? -1.0 : 1.0) * normals[i].cast<double>().dot(offset);
    if (options.outward == OutwardRule::Volume) {
      vote[c] += facing;
    } else if (options.outward == OutwardRule::FarthestPoint && offset.squaredNorm() > farthest[c]) {
      farthest[c] = offset.squaredNorm();
      vote[c] = facing;
    }
  }
  result.flipped = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, 16384), std::size_t{0},
      [&](const tbb::blocked_range<std::size_t>& r, std::size_t count) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          if ((flipped[i] != 0) == (vote[component[i]] < 0)) continue;
          normals[i] = -normals[i];
          ++count;
        }
        return count;
      },
      std::plus<>());
  if (result.components > 1)
    result.warnings.push_back("orientation: the neighbour graph has " + std::to_string(result.components) +
                              " connected components, each oriented on its own");
  report(1.0);
  return result;
}

}  // namespace pcsketch::differential
