#include "pcsketch/differential/curvature.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "common.h"
#include "core/nth_value.h"
#include "core/ordered_key.h"
#include "core/parallel_chunks.h"
#include "group_fit.h"
#include "quadric_fit.h"

namespace pcsketch::differential {

namespace {

constexpr double kPi = 3.14159265358979323846;

using detail::fit_point, detail::kInnerFit, detail::PointFit, detail::sample_stride, detail::Want;

/// Median of χ²_ν/ν, ≈ (1 − 2/(9ν))³ (Wilson–Hilferty): the median squared residual of a fit with ν degrees of
/// freedom on pure noise, relative to σ².
double chi_square_median(double dof) { return std::pow(1 - 2 / (9 * dof), 3); }

/// The points the noise estimates fit: every `stride`-th; none (count 0) without `min_k` neighbours or normals.
struct Sampling {
  std::size_t stride = 1, count = 0;
};
Sampling sampling(const char* stage, const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                  const neighbourhood::Neighbourhoods& neighbourhoods, std::size_t max_samples, std::size_t min_k) {
  const std::size_t n = points.size();
  detail::check_neighbourhoods(stage, n, neighbourhoods);
  if (n == 0 || neighbourhoods.k < std::max<std::size_t>(min_k, 1) || normals.size() != n) return {};
  const std::size_t stride = sample_stride(n, max_samples);
  return {stride, (n + stride - 1) / stride};
}

/// Median of `values` (reordered).
double median(std::vector<double>& values) {
  if (values.empty()) return 0;
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

/// Points per unit area: median over points of k / (π d_k²), d_k the distance of the k-th neighbour.
double density(const neighbourhood::Neighbourhoods& neighbourhoods) {
  const std::size_t k = neighbourhoods.k;
  const std::vector<float> farthest = detail::farthest_distances(neighbourhoods);
  // The density falls as the distance grows: its median over the m points at a distance is the density of the
  // distance of rank m − 1 − m/2 among theirs, which follow the zero ones.
  const auto zero = static_cast<std::size_t>(std::count(farthest.begin(), farthest.end(), 0.f));
  const std::size_t m = farthest.size() - zero;
  if (m == 0) return 0;
  const double r = pcsketch::detail::nth_value(farthest, zero + m - 1 - m / 2);
  return static_cast<double>(k) / (kPi * r * r);
}

/// Noise σ̂ from the first-pass residuals. A residual mixes noise, the same at any fit size, with the misfit of
/// the shape beyond a quadric (cubic terms ~ r³, so its square grows as k³ at fixed density). The median squared
/// residuals over the shared k and over the nearest kInnerFit neighbours, normalised by their ratio on pure noise
/// (medians of χ²_ν/ν), give the noise share f of the outer one: q = c + (1 − c)·f with c = (kInnerFit/k)³.
/// σ̂ = √f · median residual: on pure noise as before, on clean coarse meshes near 0 (see docs/geometry.md).
/// `inner_residual` holds the smaller fit's residual at every `stride`-th point.
double noise_estimate(const std::vector<double>& residual, std::vector<double>& inner_residual, std::size_t stride,
                      std::size_t k) {
  std::vector<double> outer = residual;
  const double outer_median = median(outer);
  if (inner_residual.empty() || !(outer_median > 0)) return outer_median;
  std::vector<double> sampled_outer(inner_residual.size());
  for (std::size_t j = 0; j < inner_residual.size(); ++j) sampled_outer[j] = residual[j * stride];
  const double sampled_outer_median = median(sampled_outer);
  if (!(sampled_outer_median > 0)) return outer_median;
  const double inner_median = median(inner_residual);
  // On pure noise the ratio is that of the medians of χ²_ν/ν, ν = points − 6.
  const double pure_noise_ratio = chi_square_median(static_cast<double>(kInnerFit) - 5) /
                                  chi_square_median(static_cast<double>(k) - 5);
  const double q = (inner_median * inner_median) / (sampled_outer_median * sampled_outer_median) / pure_noise_ratio;
  const double c = std::pow(static_cast<double>(kInnerFit) / static_cast<double>(k), 3);
  const double noise_share = std::clamp((q - c) / (1 - c), 0.0, 1.0);
  return std::sqrt(noise_share) * outer_median;
}

Curvature estimate(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                   const neighbourhood::Neighbourhoods& neighbourhoods, const neighbourhood::KdTree* given_tree,
                   const CurvatureOptions& options, const DenoisedCopy& denoised) {
  const std::size_t n = points.size();
  detail::check_neighbourhoods("curvature", n, neighbourhoods);
  if (normals.size() != n)
    throw Error("curvature: " + std::to_string(normals.size()) + " normals for " + std::to_string(n) + " points");
  Curvature result;
  result.dir1.resize(n);  // Eigen vectors: left unset, no page touched
  result.dir2.resize(n);
  // The curvatures and residuals (16 B a point) are zeroed as their fresh pages fault in: side by side, not in turn.
  std::vector<double> residual;
  tbb::parallel_invoke([&] { result.k1.resize(n); }, [&] { result.k2.resize(n); }, [&] { residual.resize(n); });
  // First pass only: residual of the fit over the nearest kInnerFit neighbours at every stride-th point (points are
  // in space-filling-curve order, so the sample spreads over the surface); its median needs no more than ~16k.
  std::vector<double> inner_residual;
  const std::size_t stride = sample_stride(n, 16384);

  std::optional<neighbourhood::KdTree> own_tree;
  // A second pass reports under its own name: one stage's fraction never starts again at 0.
  std::string_view wide_stage = "curvature";
  const auto store = [&](std::size_t i, const PointFit& fit) {
    result.k1[i] = fit.k1;
    result.k2[i] = fit.k2;
    result.dir1[i] = fit.dir1;
    result.dir2[i] = fit.dir2;
    residual[i] = fit.residual;
  };
  // Fits over the shared neighbourhoods (the first pass also takes the inner residuals).
  const auto run_shared = [&](std::size_t k) {
    result.fit_neighbours = k;
    wide_stage = "curvature, wider fits";
    pcsketch::detail::parallel_chunks(n, options.progress, "curvature", [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        const bool sampled = !inner_residual.empty() && i % stride == 0;
        store(i, fit_point(points, i, normals[i], neighbourhoods.indices.data() + i * neighbourhoods.k, k,
                           sampled ? &inner_residual[i / stride] : nullptr, Want::both));
      }
    });
  };
  // Fits over k neighbours from the tree (wider than the shared lists), one per group of nearby points.
  const auto run_wide = [&](std::size_t k) {
    result.fit_neighbours = k;
    const neighbourhood::KdTree& tree = given_tree ? *given_tree : own_tree.emplace(points);
    const bool copy = denoised.points != nullptr;
    const std::vector<Vec3f>& fit_points = copy ? *denoised.points : points;
    const std::vector<Vec3f>& fit_normals = copy ? *denoised.normals : normals;
    const detail::PointFitFn point_fit = [&](std::size_t i, const std::uint32_t* nb, std::size_t count) {
      store(i, fit_point(fit_points, i, fit_normals[i], nb, count, nullptr, Want::shape));
    };
    result.point_fits = detail::fit_groups(points, normals, neighbourhoods, tree,
                                           {.fit = k,
                                            .noise_sigma = result.noise_sigma,
                                            .shared_at_creases = copy,
                                            .progress = options.progress,
                                            .stage = wide_stage},
                                           point_fit, result);
  };

  const std::size_t shared = neighbourhoods.k;
  const std::size_t available = n == 0 ? 0 : n - 1;
  if (options.k != 0) {
    const std::size_t k = std::min(options.k, available);
    if (k > shared) run_wide(k);
    else run_shared(k);
  } else {
    const bool adapt = options.adapt_to_noise && options.noise_tolerance > 0 && shared > 0;
    const double rho = adapt ? density(neighbourhoods) : 0;
    const auto wanted_for = [&](double sigma) { return 8.0 * sigma * std::sqrt(kPi * rho) / options.noise_tolerance; };
    const auto fit_size = [&](double wanted) {
      return std::min({static_cast<std::size_t>(std::ceil(wanted)), options.max_k, available});
    };
    // The fit over the shared neighbourhoods at every point only serves σ̂ where the wide fit follows, and that
    // replaces every one of its fits. Where a sample of 16k fits already calls for the wide fit, σ̂ is the sample's
    // (within about 1% of the full median's): the full pass was a third of a noisy cloud's curvature time.
    const float sampled = adapt ? estimate_noise(points, normals, neighbourhoods) : 0.f;
    if (adapt && 4 * fit_size(wanted_for(sampled)) > 5 * shared) {
      result.noise_sigma = sampled;
    } else {
      if (shared >= kInnerFit + 4) inner_residual.resize((n + stride - 1) / stride);
      run_shared(shared);
      result.noise_sigma = static_cast<float>(noise_estimate(residual, inner_residual, stride, shared));
    }
    if (adapt) {
      const double wanted = wanted_for(result.noise_sigma);
      const std::size_t k = fit_size(wanted);
      // The fit's curvature noise falls as 1/√k: under 1.25·shared (< 11% less noise) the refit is not worth it.
      if (4 * k > 5 * shared) run_wide(k);
      if (wanted > static_cast<double>(options.max_k) && options.max_k < available)
        result.warnings.push_back("curvature: the noise (σ ≈ " + std::to_string(result.noise_sigma) +
                                  ") calls for fits over " + std::to_string(static_cast<std::size_t>(wanted)) +
                                  " neighbours; capped at max_k = " + std::to_string(options.max_k));
    }
  }
  if (result.fit_neighbours < 5 && n > 0)
    result.warnings.push_back("curvature: only " + std::to_string(result.fit_neighbours + 1) +
                              " points per fit (6 needed); unseen curvature components are set to 0");
  return result;
}

}  // namespace

float estimate_noise(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                     const neighbourhood::Neighbourhoods& neighbourhoods, std::size_t max_samples) {
  const Sampling sampled = sampling("noise estimate", points, normals, neighbourhoods, max_samples, 1);
  const std::size_t stride = sampled.stride, samples = sampled.count;  // lambdas capture variables, not bindings
  if (samples == 0) return 0.f;
  const std::size_t k = neighbourhoods.k;
  std::vector<double> residual(samples), inner(k >= kInnerFit + 4 ? samples : 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples, 256), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t j = r.begin(); j != r.end(); ++j) {
      const std::size_t i = j * stride;
      const std::uint32_t* nb = neighbourhoods.indices.data() + i * k;
      double* inner_fit = inner.empty() ? nullptr : &inner[j];
      residual[j] = fit_point(points, i, normals[i], nb, k, inner_fit, Want::residual).residual;
    }
  });
  return static_cast<float>(noise_estimate(residual, inner, 1, k));
}

namespace {

/// Neighbours of the wider fit that tells noise from misfit (noise_share): the nearest of the neighbours'
/// neighbours, so no tree is needed.
constexpr std::size_t kWideFit = 40;

/// The kWideFit nearest of i's neighbours and their neighbours (i excluded), into `wide`, nearest first; false if
/// fewer. `seen`: two_step_ring's flags.
bool wide_neighbours(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& nbh, std::size_t i,
                     std::vector<std::uint8_t>& seen, std::vector<std::uint64_t>& keys,
                     std::vector<std::uint32_t>& wide) {
  detail::two_step_ring(points, nbh, i, seen, keys);
  if (keys.size() < kWideFit) return false;
  std::partial_sort(keys.begin(), keys.begin() + kWideFit, keys.end());
  wide.resize(kWideFit);
  for (std::size_t m = 0; m < kWideFit; ++m) wide[m] = pcsketch::detail::key_index(keys[m]);
  return true;
}

}  // namespace

float noise_share(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                  const neighbourhood::Neighbourhoods& neighbourhoods, std::size_t max_samples) {
  const Sampling sampled = sampling("noise share", points, normals, neighbourhoods, max_samples, kInnerFit);
  const std::size_t stride = sampled.stride, samples = sampled.count;
  if (samples == 0) return 1.f;
  const std::size_t k = neighbourhoods.k;
  std::vector<double> outer(samples, -1), wider(samples, -1);
  tbb::enumerable_thread_specific<std::vector<std::uint8_t>> flags(std::vector<std::uint8_t>(points.size(), 0));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples, 256), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<std::uint64_t> keys;
    std::vector<std::uint32_t> wide;
    std::vector<std::uint8_t>& seen = flags.local();
    for (std::size_t j = r.begin(); j != r.end(); ++j) {
      const std::size_t i = j * stride;
      if (!wide_neighbours(points, neighbourhoods, i, seen, keys, wide)) continue;
      const std::uint32_t* nb = neighbourhoods.indices.data() + i * k;
      outer[j] = fit_point(points, i, normals[i], nb, k, nullptr, Want::residual).residual;
      wider[j] = fit_point(points, i, normals[i], wide.data(), kWideFit, nullptr, Want::residual).residual;
    }
  });
  std::erase(outer, -1.0);
  std::erase(wider, -1.0);
  const double outer_median = median(outer), wider_median = median(wider);
  if (!(outer_median > 0)) return 1.f;
  // On pure noise the squared medians' ratio is that of the medians of χ²_ν/ν (ν = points − 6); misfit's square
  // grows as (kWideFit/k)³.
  const double pure_noise_ratio =
      chi_square_median(static_cast<double>(kWideFit) - 5) / chi_square_median(static_cast<double>(k) - 5);
  const double q = (wider_median * wider_median) / (outer_median * outer_median) / pure_noise_ratio;
  const double c = std::pow(static_cast<double>(kWideFit) / static_cast<double>(k), 3);
  return static_cast<float>(std::clamp((c - q) / (c - 1), 0.0, 1.0));
}

Curvature estimate_curvature(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                             const neighbourhood::Neighbourhoods& neighbourhoods, const neighbourhood::KdTree& tree,
                             const CurvatureOptions& options, const DenoisedCopy& denoised) {
  if (tree.size() != points.size())
    throw Error("curvature: the kd-tree holds " + std::to_string(tree.size()) + " points but the cloud has " +
                std::to_string(points.size()));
  const auto matches = [&](const std::vector<Vec3f>* v) { return v && v->size() == points.size(); };
  if (denoised.points && !(matches(denoised.points) && matches(denoised.normals)))
    throw Error("curvature: the denoised copy does not match the " + std::to_string(points.size()) + " points");
  return estimate(points, normals, neighbourhoods, &tree, options, denoised);
}

Curvature estimate_curvature(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                             const neighbourhood::Neighbourhoods& neighbourhoods, const CurvatureOptions& options) {
  return estimate(points, normals, neighbourhoods, nullptr, options, {});
}

}  // namespace pcsketch::differential
