// Streamed read with voxel thinning (PLY, LAS, ascii and binary PCD, the XYZ family): two passes over the mapped file,
// never a whole RawCloud. The first finds the bounding box (and the robust box for the resolution rule), the second
// keeps per occupied cell the point nearest its centre in a hash map. The rule, the grid and the tie-breaks are
// decimate()'s, computed on the same float positions, so the kept points are exactly those of the in-memory read
// followed by decimate().

#include <sys/mman.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "cell_table.h"
#include "columns.h"
#include "point_stream.h"

namespace pcsketch::io::detail {
namespace {

// The filters of the whole read (read_cloud.cpp filter()): --classes, --drop-classes, --crop.
bool filtered_in(const ReadOptions& options, const PointChunk& c, std::size_t i) {
  if (!c.classes.empty() && !class_kept(options, c.classes[i])) return false;
  const Vec3d& p = c.positions[i];
  return !options.crop ||
         ((p.array() >= options.crop->min.array()).all() && (p.array() <= options.crop->max.array()).all());
}

/// Pass 1: counts, bounding box and a sample of positions.
class Survey final : public PointSink {
 public:
  /// `count`: the points expected, for progress; `most`: the most there can be, so that the sample stays bounded.
  Survey(const ReadOptions& options, std::uint64_t count, std::uint64_t most, const ProgressReporter& report)
      : options_(options), count_(count), stride_(std::max<std::uint64_t>(1, most / kSurveySample)), report_(report) {}

  void points(const PointChunk& c) override {
    colour_max = std::max(colour_max, c.colour_max);
    for (std::size_t i = 0; i < c.positions.size(); ++i) {
      const Vec3d& p = c.positions[i];
      if (!p.allFinite()) {
        ++non_finite;
        continue;
      }
      if (!filtered_in(options_, c, i)) {
        ++filtered;
        continue;
      }
      lo = kept == 0 ? p : lo.cwiseMin(p);
      hi = kept == 0 ? p : hi.cwiseMax(p);
      ++kept;
      if ((c.first + i) % stride_ == 0) sample.push_back(p);
    }
    seen = c.first + c.positions.size();
    // A text format's count is an estimate: the fraction may overrun.
    report_(std::min(0.5, 0.5 * static_cast<double>(seen) / static_cast<double>(count_)));
  }

  std::uint64_t seen = 0;  ///< points handed over
  std::uint64_t non_finite = 0, filtered = 0, kept = 0;
  std::uint16_t colour_max = 0;  ///< PointChunk::colour_max over the file
  Vec3d lo = Vec3d::Zero(), hi = Vec3d::Zero();
  std::vector<Vec3d> sample;

 private:
  const ReadOptions& options_;
  std::uint64_t count_, stride_;
  const ProgressReporter& report_;
};

/// Pass 2: per occupied cell, the candidate decimate() would keep; the normals' statistics (of the points pass 1
/// kept: the whole read checks them after the filters).
class Voxeliser final : public PointSink {
 public:
  Voxeliser(const ReadOptions& options, const Vec3d& origin, const Vec3d& lo, double cell, std::uint64_t count,
            bool normals, bool colors, bool intensity, const ProgressReporter& report)
      : cells(normals, colors, intensity),
        options_(options),
        origin_(origin),
        lo_(lo),
        cell_(cell),
        count_(count),
        report_(report) {}

  void points(const PointChunk& c) override {
    const std::size_t n = c.positions.size();
    candidates_.resize(n);
    part_.resize(n);
    // Keys first, in parallel, with the normals' counts (integer sums: the same in any order).
    using Counts = std::pair<std::uint64_t, std::uint64_t>;  // bad, unit
    const Counts counts = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n, 4096), Counts{0, 0},
        [&](const tbb::blocked_range<std::size_t>& r, Counts sum) {
          for (std::size_t i = r.begin(); i != r.end(); ++i) {
            part_[i] = kNoPart;
            if (!candidate(c, i, candidates_[i])) continue;
            part_[i] = static_cast<std::uint8_t>(CellTables::part_of(candidates_[i].key));
            if (c.normals.empty()) continue;
            const Vec3f& normal = c.normals[i];
            sum.first += !(normal.allFinite() && normal.norm() > 0.f);
            sum.second += std::abs(normal.norm() - 1.f) <= kUnitTolerance;
          }
          return sum;
        },
        [](const Counts& a, const Counts& b) { return Counts{a.first + b.first, a.second + b.second}; });
    bad_normals += counts.first;
    unit_normals += counts.second;
    tbb::parallel_for(std::size_t{0}, CellTables::kParts, [&](std::size_t p) { offer_part(c, p); });
    report_(std::min(1.0, 0.5 + 0.5 * static_cast<double>(c.first + n) / static_cast<double>(count_)));
  }

  CellTables cells;
  std::uint64_t bad_normals = 0, unit_normals = 0;

 private:
  struct Candidate {
    CellTable::Key key;
    double distance2;
    std::array<float, 3> position;
  };
  static constexpr std::uint8_t kNoPart = 0xff;

  /// Table p's offers of the chunk, in file order and in batches: keys' slots prefetched, then the offers.
  void offer_part(const PointChunk& c, std::size_t p) {
    constexpr std::size_t kBatch = 32;
    std::array<std::uint32_t, kBatch> batch;
    CellTable& table = cells.part(p);
    for (std::size_t i = 0; i < part_.size();) {
      std::size_t m = 0;
      for (; i < part_.size() && m < kBatch; ++i)
        if (part_[i] == p) batch[m++] = static_cast<std::uint32_t>(i);
      table.reserve_for(m);
      for (std::size_t k = 0; k < m; ++k) table.prefetch(candidates_[batch[k]].key);
      for (std::size_t k = 0; k < m; ++k) {
        const std::uint32_t j = batch[k];
        const Candidate& a = candidates_[j];
        table.offer(a.key, a.distance2, a.position, c.first + j, c.normals.empty() ? Vec3f::Zero() : c.normals[j],
                    c.colors.empty() ? Rgb8{} : c.colors[j], c.intensity.empty() ? 0.f : c.intensity[j]);
      }
    }
  }

  // decimate()'s cell and distance for `p`, on the float position the whole read would store; false: not kept.
  bool candidate(const PointChunk& c, std::size_t i, Candidate& out) const {
    const Vec3d& p = c.positions[i];
    if (!p.allFinite() || !filtered_in(options_, c, i)) return false;
    const Vec3f f = (p - origin_).cast<float>();
    const Vec3d q = (f.cast<double>() - lo_) / cell_;
    for (int a = 0; a < 3; ++a) out.key[static_cast<std::size_t>(a)] = static_cast<std::int32_t>(std::floor(q[a]));
    const Vec3d centre{double(out.key[0]) + 0.5, double(out.key[1]) + 0.5, double(out.key[2]) + 0.5};
    out.distance2 = (q - centre).squaredNorm();
    out.position = {f.x(), f.y(), f.z()};
    return true;
  }

  const ReadOptions& options_;
  Vec3d origin_, lo_;
  double cell_;
  std::uint64_t count_;
  const ProgressReporter& report_;
  std::vector<Candidate> candidates_;  ///< per point of the chunk
  std::vector<std::uint8_t> part_;     ///< per point of the chunk: its table, or kNoPart if not kept
};

// check_normals() of the in-memory read, from pass 2's counts over the `kept` points.
bool normals_usable(const Voxeliser& s, std::uint64_t kept, ReadResult& result, const Source& source) {
  if (s.bad_normals > 0) {
    result.warnings.push_back(source.path + ": " + std::to_string(s.bad_normals) +
                              " normals are zero or not finite; normals ignored");
    return false;
  }
  const double unit = static_cast<double>(s.unit_normals) / static_cast<double>(kept);
  if (unit < kUnitShare) {
    result.warnings.push_back(source.path + ": the file's normals are not unit vectors (only " +
                              std::to_string(static_cast<int>(unit * 100.0)) +
                              "% are); they are recomputed from the points");
    return false;
  }
  return true;
}

void check_survey(const Survey& s, const StreamHeader& header, const ReadOptions& options, ReadResult& result,
                  const Source& source) {
  if (header.count == 0) source.fail(header.format + ": the file holds no points");
  if (s.non_finite == header.count)
    source.fail(header.format + ": all " + std::to_string(header.count) + " points have a NaN or infinite coordinate");
  if (s.non_finite > 0)
    result.warnings.push_back(source.path + ": dropped " + std::to_string(s.non_finite) + " of " +
                              std::to_string(header.count) + " points with a NaN or infinite coordinate");
  if (s.kept == 0)
    source.fail(header.format + ": none of the " + std::to_string(header.count - s.non_finite) +
                " points is left by the " +
                filters_named(!options.classes.empty() || !options.drop_classes.empty(), options.crop.has_value()));
}

// The thinning's cell: --voxel, or the resolution rule's when larger (both: the larger of the two).
DecimateReport choose_cell(const Survey& survey, const DecimateOptions& d, bool by_resolution, std::uint64_t count) {
  DecimateReport thinning;
  thinning.streamed = true;
  thinning.points_before = survey.kept;
  thinning.cell = d.voxel.value_or(0.0);
  thinning.reason = d.voxel ? "--voxel" : "";
  if (by_resolution) {
    const double cell = resolution_cell(*d.resolution, robust_extent(survey.sample));
    if (cell > thinning.cell) {
      thinning.cell = cell;
      thinning.reason = resolution_reason(*d.resolution, count);
    }
  }
  // A box without extent (all points on a line or at one place): a cell far below any spacing.
  if (!(thinning.cell > 0.0)) thinning.cell = std::max((survey.hi - survey.lo).maxCoeff() * 1e-7, 1e-30);
  return thinning;
}

}  // namespace

Vec3d robust_extent(std::vector<Vec3d> sample) {
  Vec3d extent = Vec3d::Zero();
  if (sample.empty()) return extent;
  const std::size_t lo = sample.size() / 200, hi = sample.size() - 1 - sample.size() / 200;
  std::vector<double> axis(sample.size());
  for (int a = 0; a < 3; ++a) {
    for (std::size_t i = 0; i < sample.size(); ++i) axis[i] = sample[i][a];
    std::nth_element(axis.begin(), axis.begin() + static_cast<std::ptrdiff_t>(lo), axis.end());
    const double low = axis[lo];
    std::nth_element(axis.begin(), axis.begin() + static_cast<std::ptrdiff_t>(hi), axis.end());
    extent[a] = axis[hi] - low;
  }
  return extent;
}

std::string resolution_reason(const OutputResolution& r, std::uint64_t count) {
  char text[200];
  std::snprintf(text, sizeof text, "%llu points, over the %zu budget of a %dx%d %s image: cells of %.3g px",
                static_cast<unsigned long long>(count), r.budget(), r.width, r.height,
                r.perspective ? "perspective" : "orthographic", r.cell_pixels);
  return text;
}

std::size_t release_pages(std::string_view bytes, std::size_t from, std::size_t to) {
  static const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  const auto base = reinterpret_cast<std::uintptr_t>(bytes.data());
  const std::uintptr_t begin = (base + from + page - 1) / page * page, end = (base + to) / page * page;
  if (end <= begin) return from;
  // The mapping is private and read-only: dropped pages are read again from the file if touched.
  ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_DONTNEED);
  return end - base;
}

std::optional<ReadResult> read_streamed(const Source& source, const ReadOptions& options, std::size_t chunk_points) {
  const DecimateOptions& d = options.decimate;
  if (!d.voxel && !d.resolution) return std::nullopt;  // no thinning asked for: the whole read, headers unread
  // Each streaming reader recognises its own magic; another format or layout is read whole.
  std::optional<StreamHeader> header = ply_stream_header(source);
  if (!header) header = las_stream_header(source);
  if (!header) header = pcd_stream_header(source);
  if (!header) header = xyz_stream_header(source);
  if (!header) return std::nullopt;
  // Class filters on a file without classes: the whole read gives its error.
  if ((!options.classes.empty() || !options.drop_classes.empty()) && !header->has_classes) return std::nullopt;
  // A text format's count is an estimate that may fall short: a file that may be over the budget is surveyed, never
  // read whole on the estimate's word.
  bool by_resolution = d.resolution && header->most() > d.resolution->budget();
  if (!d.voxel && !by_resolution) return std::nullopt;

  const auto start = std::chrono::steady_clock::now();
  const ProgressReporter report(options.progress, "read");
  report(0.0);
  Survey survey(options, header->count, header->most(), report);
  header->stream(source, chunk_points, survey);
  if (header->surveyed) {
    header->surveyed(*header, survey.seen);
    // The cloud is within the budget after all: it reads exactly as before.
    by_resolution = d.resolution && header->count > d.resolution->budget();
    if (!d.voxel && !by_resolution) return std::nullopt;
  }
  ReadResult result;
  result.warnings = header->warnings;
  result.columns = header->columns;
  result.points_in_file = header->count;
  result.dropped_non_finite = survey.non_finite;
  result.dropped_by_filter = survey.filtered;
  check_survey(survey, *header, options, result, source);

  PointCloud& cloud = result.cloud;
  cloud.origin = choose_origin(survey.lo, survey.hi, options);
  // decimate()'s grid is anchored at the float box, and rounding to float keeps the order: the float box is the
  // double box rounded.
  const Vec3f lo = (survey.lo - cloud.origin).cast<float>(), hi = (survey.hi - cloud.origin).cast<float>();
  if (!lo.allFinite() || !hi.allFinite())
    source.fail("the points lie " + number((survey.hi - survey.lo).cwiseAbs().maxCoeff()) +
                " units apart, beyond float range");
  DecimateReport thinning = choose_cell(survey, d, by_resolution, header->count);
  // A grid of more than 2^30 cells a side (a --voxel far below the box): decimate() in memory has 64-bit cells.
  if (((survey.hi - survey.lo) / thinning.cell).maxCoeff() >= CellTable::kMaxIndex - 2) return std::nullopt;
  const bool normals = header->has_normals && options.keep_normals;
  const bool colors = header->has_colors && options.keep_colors;
  Voxeliser voxels(options, cloud.origin, lo.cast<double>(), thinning.cell, header->count, normals,
                   colors && header->read_kept == nullptr, header->has_intensity, report);
  header->stream(source, chunk_points, voxels);
  std::vector<float> intensity;
  const std::vector<std::uint64_t> kept = voxels.cells.take(cloud.positions, cloud.normals, cloud.colors, &intensity);
  if (normals && !normals_usable(voxels, survey.kept, result, source)) cloud.normals.clear();
  if (header->has_intensity) cloud.attributes.push_back({"intensity", std::move(intensity)});
  if (header->read_kept != nullptr) header->read_kept(source, kept, survey.colour_max, colors, cloud);
  for (Vec3f& n : cloud.normals) n.normalize();
  thinning.points_after = cloud.size();
  thinning.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.format = header->format;
  result.other_attributes = header->other_attributes;
  result.decimation = thinning;
  if (d.max_points && cloud.size() > *d.max_points) {
    const DecimateReport more = decimate(cloud, {.max_points = d.max_points});
    result.decimation->points_after = more.points_after;
    result.decimation->cell = more.cell;
    result.decimation->reason += ", then --max-points";
  }
  report(1.0);
  return result;
}

}  // namespace pcsketch::io::detail
