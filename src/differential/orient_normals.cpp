#include "pcsketch/differential/orient_normals.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "differential/common.h"
#include "neighbourhood/parallel_chunks.h"

namespace pcsketch::differential {

namespace {

constexpr std::uint32_t kLevels = 4096;                    // quantisation of the edge weights
constexpr std::uint16_t kNoEdge = 0xffff;                  // slot whose edge is listed by the other endpoint
constexpr std::size_t kSortBlocks = 64;                    // fixed, so the sort does not depend on the thread count

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

/// Weight level of an edge: 0 for parallel normals, growing with the angle (sqrt(1−|cos|) ≈ angle/√2 spreads the
/// many nearly parallel pairs over many levels).
std::uint16_t level(const Vec3f& a, const Vec3f& b) {
  const float c = std::min(1.f, std::abs(a.dot(b)));
  return static_cast<std::uint16_t>(std::min<float>(kLevels - 1, std::sqrt(1.f - c) * float(kLevels)));
}

}  // namespace

OrientResult orient_normals(const std::vector<Vec3f>& points, std::vector<Vec3f>& normals,
                            const neighbourhood::Neighbourhoods& neighbourhoods, const OrientOptions& options) {
  const std::size_t n = points.size();
  detail::check_neighbourhoods("orient normals", n, neighbourhoods);
  if (normals.size() != n)
    throw Error("orient normals: " + std::to_string(normals.size()) + " normals for " + std::to_string(n) + " points");
  const ProgressReporter report(options.progress, "orientation");
  OrientResult result;
  if (n == 0) return result;
  const std::size_t stride = neighbourhoods.k;
  const std::size_t k = detail::neighbours_used(options.k, neighbourhoods);

  // 1. Weight level of every undirected edge, listed once: by its smaller endpoint, or by the endpoint whose list
  //    holds it when the other's does not (distance at or beyond that one's k-th neighbour; ties list it twice,
  //    which is harmless).
  std::vector<std::uint16_t> levels(n * k);
  pcsketch::detail::parallel_chunks(n, {}, "", [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      for (std::size_t m = 0; m < k; ++m) {
        const std::uint32_t j = neighbourhoods.indices[i * stride + m];
        const bool listed_by_j = neighbourhoods.distances[i * stride + m] < neighbourhoods.distances[j * stride + k - 1];
        const bool usable = normals[i].squaredNorm() > 0 && normals[j].squaredNorm() > 0;
        levels[i * k + m] = usable && (i < j || !listed_by_j) ? level(normals[i], normals[j]) : kNoEdge;
      }
    }
  });
  report(0.2);

  // 2. Counting sort of the edge slots by level, stable within a level: fixed blocks, per-block histograms.
  const std::size_t slots = n * k;
  const std::size_t block = (slots + kSortBlocks - 1) / kSortBlocks;
  std::vector<std::uint32_t> histogram(kSortBlocks * kLevels, 0);
  tbb::parallel_for(std::size_t{0}, kSortBlocks, [&](std::size_t b) {
    std::uint32_t* h = histogram.data() + b * kLevels;
    for (std::size_t s = b * block; s < std::min(slots, (b + 1) * block); ++s)
      if (levels[s] != kNoEdge) ++h[levels[s]];
  });
  std::size_t edges = 0;
  for (std::uint32_t l = 0; l < kLevels; ++l) {
    for (std::size_t b = 0; b < kSortBlocks; ++b) {
      const std::uint32_t count = histogram[b * kLevels + l];
      histogram[b * kLevels + l] = static_cast<std::uint32_t>(edges);
      edges += count;
    }
  }
  std::vector<std::uint32_t> sorted(edges);
  tbb::parallel_for(std::size_t{0}, kSortBlocks, [&](std::size_t b) {
    std::uint32_t* next = histogram.data() + b * kLevels;
    for (std::size_t s = b * block; s < std::min(slots, (b + 1) * block); ++s)
      if (levels[s] != kNoEdge) sorted[next[levels[s]]++] = static_cast<std::uint32_t>(s);
  });
  std::vector<std::uint16_t>().swap(levels);
  report(0.4);

  // 3. Kruskal: strongest agreement first; each join fixes the relative sign of two trees.
  SignedUnionFind forest(n);
  std::size_t joins = 0;
  for (const std::uint32_t s : sorted) {
    const std::uint32_t i = static_cast<std::uint32_t>(s / k);
    const std::uint32_t j = neighbourhoods.indices[i * stride + s % k];
    if (forest.join(i, j, normals[i].dot(normals[j]) < 0 ? 1 : 0) && ++joins == n - 1) break;
  }
  std::vector<std::uint32_t>().swap(sorted);
  report(0.8);

  // 4. Apply the propagated signs and gather each component's centroid.
  std::vector<std::uint32_t> component(n);
  std::vector<std::uint32_t> component_of_root(n, std::numeric_limits<std::uint32_t>::max());
  std::vector<Vec3d> centroid;
  std::vector<std::size_t> members;
  std::vector<std::uint8_t> flipped(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto [root, flip] = forest.find(static_cast<std::uint32_t>(i));
    if (component_of_root[root] == std::numeric_limits<std::uint32_t>::max()) {
      component_of_root[root] = static_cast<std::uint32_t>(centroid.size());
      centroid.push_back(Vec3d::Zero());
      members.push_back(0);
    }
    component[i] = component_of_root[root];
    flipped[i] = flip;
    centroid[component[i]] += points[i].cast<double>();
    ++members[component[i]];
  }
  result.components = centroid.size();
  for (std::size_t c = 0; c < centroid.size(); ++c) centroid[c] /= static_cast<double>(members[c]);

  // 5. Turn each component outward.
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
  for (std::size_t i = 0; i < n; ++i) {
    const bool flip = (flipped[i] != 0) != (vote[component[i]] < 0);
    if (flip) {
      normals[i] = -normals[i];
      ++result.flipped;
    }
  }
  if (result.components > 1)
    result.warnings.push_back("orientation: the neighbour graph has " + std::to_string(result.components) +
                              " connected components, each oriented on its own");
  report(1.0);
  return result;
}

}  // namespace pcsketch::differential
