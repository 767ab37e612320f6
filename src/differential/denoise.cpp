#include "pcsketch/differential/denoise.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>

#include "common.h"
#include "core/ordered_key.h"
#include "core/parallel_chunks.h"
#include "core/smallest_eigenpair.h"
#include "pcsketch/core/buffer.h"
#include "pcsketch/differential/curvature.h"
#include "pcsketch/differential/normals.h"

namespace pcsketch::differential {

namespace {

constexpr double kBrokenShare = 0.05;  // unreachable_share over which the normals are taken wider (denoise)

/// The distance part of the bilateral weights, #P·k: a Gaussian of the distance, its width the distance to the
/// point's farthest neighbour. Fixed within a round (the points do not move while their normals are filtered).
/// Written over `w`, a Buffer: a fresh std::vector's serial zero fill and page faults were a quarter of the
/// denoising's time, and the refresh reuses the same memory.
void spatial_weights(const neighbourhood::Neighbourhoods& nbh, Buffer<float>& w) {
  const std::size_t k = nbh.k;
  w.resize(nbh.distances.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nbh.size(), 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const float reach = std::max(nbh.distances[i * k + k - 1], 1e-30f);
      for (std::size_t m = 0; m < k; ++m) {
        const float x = nbh.distances[i * k + m] / reach;
        w[i * k + m] = std::exp(-x * x);
      }
    }
  });
}

/// The normal part of the bilateral weights: Tukey's biweight of t = 1 − |n_i·n_j| (`dot` = n_i·n_j), zero from
/// t = cutoff on. Clamped rather than branched: the signs of unoriented normals are random, so branches mispredict.
float normal_weight(float dot, float inv_cutoff) {
  float t = (1.f - std::abs(dot)) * inv_cutoff;
  t = t < 1.f ? t : 1.f;  // NaN too: weight 0
  const float s = 1.f - t * t;
  return s * s;
}

/// Four floats in one SSE register (GCC's vector extension): the filter and the projection take a point's neighbours
/// four at a time, where one at a time each neighbour's weight waited on the previous sum.
using Quad = float __attribute__((vector_size(16)));
using QuadMask = std::int32_t __attribute__((vector_size(16)));

constexpr std::int32_t kSignBit = std::numeric_limits<std::int32_t>::min();

/// normal_weight of four dots at once.
Quad normal_weights(Quad dot, float inv_cutoff) {
  Quad t = (1.f - reinterpret_cast<Quad>(reinterpret_cast<QuadMask>(dot) & ~kSignBit)) * inv_cutoff;
  t = t < 1.f ? t : 1.f;  // NaN too: weight 0
  const Quad s = 1.f - t * t;
  return s * s;
}

/// normal_weights signed as the dots (`copysign`).
Quad signed_normal_weights(Quad dot, float inv_cutoff) {
  const QuadMask sign = reinterpret_cast<QuadMask>(dot) & kSignBit;
  return reinterpret_cast<Quad>(reinterpret_cast<QuadMask>(normal_weights(dot, inv_cutoff)) | sign);
}

/// Coordinates of four neighbours' vectors, side by side.
struct Quads {
  Quad x, y, z;
  Quads(const std::vector<Vec3f>& v, const std::uint32_t* j)
      : x{v[j[0]].x(), v[j[1]].x(), v[j[2]].x(), v[j[3]].x()},
        y{v[j[0]].y(), v[j[1]].y(), v[j[2]].y(), v[j[3]].y()},
        z{v[j[0]].z(), v[j[1]].z(), v[j[2]].z(), v[j[3]].z()} {}
  Quad dot(const Vec3f& a) const { return x * a.x() + y * a.y() + z * a.z(); }
};

float lane_sum(Quad q) { return (q[0] + q[1]) + (q[2] + q[3]); }

/// A quad of spatial weights (unaligned load).
Quad load_quad(const float* at) {
  Quad q;
  std::memcpy(&q, at, sizeof q);
  return q;
}

/// One pass of bilateral normal filtering: each normal becomes the weighted mean of its own and its neighbours'
/// (signs aligned to its own), normalised. Neighbours four at a time, the last k mod 4 one at a time.
std::vector<Vec3f> filter_normals(const std::vector<Vec3f>& normals, const neighbourhood::Neighbourhoods& nbh,
                                  const Buffer<float>& spatial, float inv_cutoff) {
  std::vector<Vec3f> out(normals.size());
  const std::size_t k = nbh.k, quads = k / 4 * 4;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, normals.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        const Vec3f& ni = normals[i];
                        Quad sx{}, sy{}, sz{};
                        for (std::size_t m = 0; m < quads; m += 4) {
                          const Quads nj(normals, &nbh.indices[i * k + m]);
                          const Quad w = load_quad(&spatial[i * k + m]) * signed_normal_weights(nj.dot(ni), inv_cutoff);
                          sx += w * nj.x, sy += w * nj.y, sz += w * nj.z;
                        }
                        Vec3f sum = ni + Vec3f(lane_sum(sx), lane_sum(sy), lane_sum(sz));
                        for (std::size_t m = quads; m < k; ++m) {
                          const Vec3f& nj = normals[nbh.indices[i * k + m]];
                          const float dot = ni.dot(nj);
                          sum += std::copysign(spatial[i * k + m] * normal_weight(dot, inv_cutoff), dot) * nj;
                        }
                        const float length = sum.norm();
                        out[i] = length > 0 ? Vec3f(sum / length) : ni;
                      }
                    });
  return out;
}

/// Moves each point towards the tangent planes of its neighbours (bilateral weights): the displacement is the
/// weighted mean of ½ (n_j n_jᵀ + n_i n_iᵀ) (p_j − p_i), which at a crease only the point's own side contributes to.
/// The neighbours' planes alone lift a point off a sphere of radius R by about d²/2R, its own plane through the
/// neighbours lowers it by as much: their mean cancels the bias.
std::vector<Vec3f> project_to_planes(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                                     const neighbourhood::Neighbourhoods& nbh, const Buffer<float>& spatial,
                                     float inv_cutoff) {
  std::vector<Vec3f> out(points.size());
  const std::size_t k = nbh.k, quads = k / 4 * 4;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        const Vec3f& pi = points[i];
                        const Vec3f& ni = normals[i];
                        Quad mx{}, my{}, mz{}, weights{};
                        for (std::size_t m = 0; m < quads; m += 4) {
                          const std::uint32_t* j = &nbh.indices[i * k + m];
                          const Quads nj(normals, j), pj(points, j);
                          const Quad w = load_quad(&spatial[i * k + m]) * normal_weights(nj.dot(ni), inv_cutoff);
                          const Quad dx = pj.x - pi.x(), dy = pj.y - pi.y(), dz = pj.z - pi.z();
                          const Quad along_j = w * (nj.x * dx + nj.y * dy + nj.z * dz);
                          const Quad along_i = w * (dx * ni.x() + dy * ni.y() + dz * ni.z());
                          mx += along_j * nj.x + along_i * ni.x();
                          my += along_j * nj.y + along_i * ni.y();
                          mz += along_j * nj.z + along_i * ni.z();
                          weights += w;
                        }
                        Vec3f move = 0.5f * Vec3f(lane_sum(mx), lane_sum(my), lane_sum(mz));
                        float total = 1.f + lane_sum(weights);  // 1: the point's own plane, zero displacement
                        for (std::size_t m = quads; m < k; ++m) {
                          const std::uint32_t j = nbh.indices[i * k + m];
                          const float w = spatial[i * k + m] * normal_weight(ni.dot(normals[j]), inv_cutoff);
                          const Vec3f d = points[j] - pi;
                          move += 0.5f * w * (normals[j].dot(d) * normals[j] + ni.dot(d) * ni);
                          total += w;
                        }
                        out[i] = pi + move / total;
                      }
                    });
  return out;
}

/// Distances of every list recomputed for the moved points and each list re-sorted (nearest first, ties by index).
void refresh_distances(const std::vector<Vec3f>& points, neighbourhood::Neighbourhoods& nbh) {
  const std::size_t k = nbh.k;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 512),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      thread_local std::vector<std::pair<float, std::uint32_t>> list;
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        list.clear();
                        for (std::size_t m = 0; m < k; ++m) {
                          const std::uint32_t j = nbh.indices[i * k + m];
                          list.emplace_back((points[j] - points[i]).norm(), j);
                        }
                        std::sort(list.begin(), list.end());
                        for (std::size_t m = 0; m < k; ++m) {
                          nbh.distances[i * k + m] = list[m].first;
                          nbh.indices[i * k + m] = list[m].second;
                        }
                      }
                    });
}

/// Lists of the `k` nearest of each point's neighbours and their neighbours (no tree: the ring of two steps holds
/// about four times the shared lists' area), for PCA normals over a wider scale than the shared lists. Indices only,
/// in no order (the PCA and the vote sum over them): no distances, and a selection instead of a sort.
neighbourhood::Neighbourhoods wider_lists(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& nbh,
                                          std::size_t k) {
  neighbourhood::Neighbourhoods wide;
  wide.k = k;
  wide.indices.resize(points.size() * k);
  tbb::enumerable_thread_specific<std::vector<std::uint8_t>> flags(std::vector<std::uint8_t>(points.size(), 0));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 256), [&](const auto& r) {
    std::vector<std::uint64_t> keys;
    std::vector<std::uint8_t>& seen = flags.local();
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      detail::two_step_ring(points, nbh, i, seen, keys);
      if (keys.empty()) keys.push_back(pcsketch::detail::ordered_key(0.f, static_cast<std::uint32_t>(i)));
      const std::size_t kept = std::min(k, keys.size());
      std::nth_element(keys.begin(), keys.begin() + static_cast<std::ptrdiff_t>(kept - 1), keys.end());
      for (std::size_t m = 0; m < k; ++m)
        wide.indices[i * k + m] = pcsketch::detail::key_index(keys[std::min(m, kept - 1)]);
    }
  });
  return wide;
}

/// True when vote(i) would find nothing, shown without the tensor's eigenproblem. For a unit n = given[i], the tensor
/// T's Rayleigh quotient q = nᵀTn = Σ (n·n_j)² is at most λ₁c² + λ₂(1 − c²), c the cosine of n with T's dominant
/// direction and λ₂ ≤ t − λ₁ (t its trace). A vote needs λ₁ > consensus·t and c² < (1 − cutoff)² = s, and over those
/// q/t stays under max((1 − consensus) + (2·consensus − 1)·s, s); at or over it (most points: their normals agree
/// with their neighbours') no vote can be. The margin covers the float sums.
bool agrees_with_neighbours(std::size_t i, const std::vector<Vec3f>& given, const neighbourhood::Neighbourhoods& nbh,
                            double consensus, float cutoff) {
  const double s = (1.0 - cutoff) * (1.0 - cutoff);
  const double bound = std::max((1 - consensus) + (2 * consensus - 1) * s, s) + 1e-3;
  const Vec3f& n = given[i];
  float q = 0, t = 0;
  for (const std::uint32_t j : nbh.of(i)) {
    const float d = n.dot(given[j]);
    q += d * d;
    t += given[j].squaredNorm();
  }
  return static_cast<double>(q) >= bound * static_cast<double>(t);
}

/// The consensus of point i's neighbours if `given[i]` lies beyond the filter's cutoff from it, else nothing: the
/// dominant eigenvector of Σ n_j n_jᵀ over its list (a normal voting tensor, sign free), signed as `given[i]`, where
/// one direction holds most of it.
std::optional<Vec3f> vote(std::size_t i, const std::vector<Vec3f>& given, const neighbourhood::Neighbourhoods& nbh,
                          float cutoff) {
  constexpr double kConsensus = 0.7;  // share of the tensor's trace along its dominant direction
  if (agrees_with_neighbours(i, given, nbh, kConsensus, cutoff)) return std::nullopt;
  Eigen::Matrix3d tensor = Eigen::Matrix3d::Zero();
  for (const std::uint32_t j : nbh.of(i)) {
    const Vec3d nj = given[j].cast<double>();
    tensor.noalias() += nj * nj.transpose();
  }
  // The dominant pair of the tensor is the smallest of trace·I − tensor, whose solver needs no trigonometry.
  const double trace = tensor.trace();
  double least = 0;
  Vec3d dominant;
  if (!pcsketch::detail::smallest_eigenpair(trace * Eigen::Matrix3d::Identity() - tensor, least, dominant)) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
    eigen.computeDirect(tensor);
    least = trace - eigen.eigenvalues()[2];
    dominant = eigen.eigenvectors().col(2);
  }
  const Vec3f major = dominant.cast<float>();
  if (!(trace - least > kConsensus * trace) || !major.allFinite()) return std::nullopt;
  const float dot = given[i].dot(major);
  if (!(1.f - std::abs(dot) > cutoff)) return std::nullopt;
  return dot < 0 ? Vec3f(-major) : major;
}

/// Each normal that the bilateral weights cannot reach (farther than the cutoff from its neighbours' consensus)
/// replaced by that consensus (vote).
std::vector<Vec3f> voted_normals(const std::vector<Vec3f>& given, const neighbourhood::Neighbourhoods& nbh,
                                 float cutoff) {
  std::vector<Vec3f> normals = given;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, given.size(), 1024), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      if (const std::optional<Vec3f> voted = vote(i, given, nbh, cutoff)) normals[i] = *voted;
  });
  return normals;
}

/// Share of the normals that voted_normals would replace: beyond the filter's cutoff from their neighbours'
/// consensus. A global share, so every s-th point is asked, at most about 20k: an eigen solve at each of 200k points
/// cost every noisy draw. 200k samples at σ = 0.1%: 25 meshes 0.001–0.031, the blade 0.08; at σ = 0.2% 23 of 26
/// meshes 0.08–0.14 (docs/geometry.md, "Noise", item 9).
double unreachable_share(const std::vector<Vec3f>& normals, const neighbourhood::Neighbourhoods& nbh, float cutoff) {
  constexpr std::size_t kAsked = 20000;
  const std::size_t stride = std::max<std::size_t>(1, (normals.size() + kAsked - 1) / kAsked);
  const std::size_t asked = (normals.size() + stride - 1) / stride;
  const std::size_t replaced = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, asked, 512), std::size_t{0},
      [&](const tbb::blocked_range<std::size_t>& r, std::size_t count) {
        for (std::size_t m = r.begin(); m != r.end(); ++m) count += vote(m * stride, normals, nbh, cutoff).has_value();
        return count;
      },
      std::plus<>());
  return static_cast<double>(replaced) / static_cast<double>(std::max<std::size_t>(1, asked));
}

/// `normals` after `passes` rounds of bilateral filtering with the spatial weights of this round.
std::vector<Vec3f> filtered_normals(std::vector<Vec3f> normals, const neighbourhood::Neighbourhoods& nbh,
                                    const Buffer<float>& spatial, const DenoiseOptions& options) {
  for (std::size_t pass = 0; pass < options.normal_passes; ++pass)
    normals = filter_normals(normals, nbh, spatial, 1.f / options.normal_cutoff);
  return normals;
}

}  // namespace

DenoiseResult denoise(std::vector<Vec3f>& points, neighbourhood::Neighbourhoods& neighbourhoods, float spacing,
                      const std::vector<Vec3f>& normals, const DenoiseOptions& options) {
  detail::check_neighbourhoods("denoise", points.size(), neighbourhoods);
  if (normals.size() != points.size())
    throw Error("denoise: " + std::to_string(normals.size()) + " normals for " + std::to_string(points.size()) +
                " points");
  DenoiseResult result;
  if (!options.enabled || neighbourhoods.k < 6 || !(spacing > 0)) return result;
  result.noise_before = estimate_noise(points, normals, neighbourhoods);
  result.noise_estimated = true;
  const float trigger = options.min_noise_factor * spacing;
  // A coarse mesh's vertices leave a misfit that σ̂'s two fit sizes can take for noise; what stays when the fit
  // widens further is noise (docs/geometry.md, "Noise", item 1).
  if (!(result.noise_before > trigger) ||
      !(std::sqrt(noise_share(points, normals, neighbourhoods)) * result.noise_before > trigger))
    return result;
  const ProgressReporter report(options.progress, "denoise");
  Buffer<float> spatial;
  spatial_weights(neighbourhoods, spatial);
  // PCA normals over 16 neighbours break down once the noise nears half their radius (Mitra & Nguyen 2003: the
  // tilt grows as σ/r). On the held-out blade, a plate 5σ thick, half of them lay over 30° off, beyond the filter's
  // cutoff from all their neighbours, so it could not average them back. Where many lie beyond the cutoff from a
  // clear consensus of their neighbours, the normals are taken over twice the radius and the outliers voted back.
  // σ̂ does not tell: fitted in the broken normals' frames it reads low (0.65 of the true σ on the blade).
  const bool broken = unreachable_share(normals, neighbourhoods, options.normal_cutoff) > kBrokenShare;
  const neighbourhood::Neighbourhoods wide =
      broken ? wider_lists(points, neighbourhoods, 4 * neighbourhoods.k) : neighbourhood::Neighbourhoods{};
  const auto pca = [&] {
    if (!broken) return estimate_normals(points, neighbourhoods).normals;
    return voted_normals(estimate_normals(points, wide).normals, wide, options.normal_cutoff);
  };
  for (std::size_t round = 0; round < options.iterations; ++round) {
    report(static_cast<double>(round) / static_cast<double>(options.iterations));
    // The first round filters the normals it was given; later ones the PCA normals of the moved points.
    const std::vector<Vec3f> filtered =
        filtered_normals(round == 0 && !broken ? normals : pca(), neighbourhoods, spatial, options);
    points = project_to_planes(points, filtered, neighbourhoods, spatial, 1.f / options.normal_cutoff);
    ++result.iterations;
  }
  // The moved points' distances (and so the spatial weights) change by about σ: refreshed once, at the end.
  refresh_distances(points, neighbourhoods);
  spatial_weights(neighbourhoods, spatial);
  result.normals = filtered_normals(pca(), neighbourhoods, spatial, options);
  result.applied = true;
  report(1.0);
  return result;
}

}  // namespace pcsketch::differential
