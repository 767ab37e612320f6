#include "pcsketch/io/read_cloud.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>

#include "columns.h"
#include "mapped_file.h"
#include "point_stream.h"
#include "raw_cloud.h"

namespace pcsketch::io {
namespace {

using detail::RawCloud;
using detail::Source;
using detail::Want;

bool sniff_las(std::string_view head) { return head.starts_with("LASF"); }

bool sniff_ply(std::string_view head) { return head.starts_with("ply\n") || head.starts_with("ply\r\n"); }

// "OFF", and its variants "COFF", "NOFF", "STOFF", … : the first token ends in OFF.
bool sniff_off(std::string_view head) {
  std::size_t i = 0;
  while (i < head.size() && i < 8 && std::isalpha(static_cast<unsigned char>(head[i]))) ++i;
  if (i < 3 || head.substr(i - 3, 3) != "OFF") return false;
  return i == head.size() || std::isspace(static_cast<unsigned char>(head[i]));
}

struct Reader {
  std::string_view name;
  std::array<std::string_view, 5> extensions;  ///< lower case, with the dot; unused entries empty
  bool (*sniff)(std::string_view head);        ///< nullptr: a text format without magic, chosen by extension
  RawCloud (*parse)(const Source&, Want);
  bool has_faces;
};

// The dispatch table: magic first (a PLY named .xyz is still read as PLY), then extension.
constexpr std::array kReaders{
    Reader{"PLY", {".ply"}, sniff_ply, detail::parse_ply, true},
    Reader{"LAS", {".las", ".laz"}, sniff_las, detail::parse_las, false},
    Reader{"OFF", {".off"}, sniff_off, detail::parse_off, true},
    Reader{"PCD", {".pcd"}, detail::sniff_pcd, detail::parse_pcd, false},
    Reader{"OBJ", {".obj"}, nullptr, detail::parse_obj, true},
    Reader{"XYZ", {".xyz", ".pts", ".txt", ".csv", ".asc"}, nullptr, detail::parse_xyz, false},
};

std::string printable_head(std::string_view bytes) {
  std::string out;
  for (const char c : bytes.substr(0, 8)) {
    if (std::isprint(static_cast<unsigned char>(c))) {
      out += c;
    } else {
      static constexpr char kHex[] = "0123456789abcdef";
      const auto u = static_cast<unsigned char>(c);
      out += "\\x";
      out += kHex[u >> 4];
      out += kHex[u & 15];
    }
  }
  return out;
}

const Reader& choose_reader(const Source& source) {
  if (source.bytes.empty()) source.fail("empty file");
  for (const Reader& r : kReaders)
    if (r.sniff != nullptr && r.sniff(source.bytes)) return r;
  std::string ext = std::filesystem::path(source.path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](char c) { return static_cast<char>(std::tolower(c)); });
  for (const Reader& r : kReaders) {
    if (ext.empty() || std::find(r.extensions.begin(), r.extensions.end(), ext) == r.extensions.end()) continue;
    if (r.sniff != nullptr)
      source.fail_at_byte(
          0, std::string(r.name) + ": wrong magic: the file starts with \"" + printable_head(source.bytes) + "\"");
    return r;
  }
  source.fail("unknown format: extension " + quote(ext) +
              " is none of .ply .las .off .pcd .obj .xyz .pts .txt .csv .asc" + " and the first bytes \"" +
              printable_head(source.bytes) + "\" are no known magic");
}

// Lowest and highest corner of the bounding box of a non-empty set.
std::pair<Vec3d, Vec3d> bounds(const std::vector<Vec3d>& positions) {
  Vec3d lo = positions.front(), hi = positions.front();
  for (const Vec3d& p : positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

Vec3d choose_origin(const std::vector<Vec3d>& positions, const ReadOptions& options) {
  if (positions.empty()) return Vec3d::Zero();
  const auto [lo, hi] = bounds(positions);
  return detail::choose_origin(lo, hi, options);
}

std::vector<Vec3f> relative(const std::vector<Vec3d>& positions, const Vec3d& origin, const Source& source) {
  std::vector<Vec3f> out(positions.size());
  const bool finite = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, positions.size(), 16384), true,
      [&](const tbb::blocked_range<std::size_t>& r, bool all) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          out[i] = (positions[i] - origin).cast<float>();
          all = all && out[i].allFinite();
        }
        return all;
      },
      std::logical_and<>());
  if (finite) return out;
  // 1e39 is a finite double but an infinite float: the first such point is named.
  const std::size_t i = static_cast<std::size_t>(
      std::find_if(out.begin(), out.end(), [](const Vec3f& p) { return !p.allFinite(); }) - out.begin());
  source.fail("point " + std::to_string(i) + " lies " + number((positions[i] - origin).cwiseAbs().maxCoeff()) +
              " units from the origin, beyond float range");
}

// Keeps the points `keep(i)` says, in place, with every per-point array aligned; returns how many were kept.
template <class Keep>
std::size_t compact(RawCloud& raw, Keep keep) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < raw.positions.size(); ++i) {
    if (!keep(i)) continue;
    raw.positions[kept] = raw.positions[i];
    if (!raw.normals.empty()) raw.normals[kept] = raw.normals[i];
    if (!raw.colors.empty()) raw.colors[kept] = raw.colors[i];
    for (PointAttribute& a : raw.attributes) a.values[kept] = a.values[i];
    ++kept;
  }
  raw.positions.resize(kept);
  if (!raw.normals.empty()) raw.normals.resize(kept);
  if (!raw.colors.empty()) raw.colors.resize(kept);
  for (PointAttribute& a : raw.attributes) a.values.resize(kept);
  return kept;
}

void drop_non_finite(RawCloud& raw, ReadResult& result, const Source& source) {
  const std::size_t all = raw.positions.size();
  if (all == 0) source.fail(raw.format + ": the file holds no points");
  // Checked in parallel first: most files have no such point, and then nothing moves.
  const bool finite = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, all, 16384), true,
      [&](const tbb::blocked_range<std::size_t>& r, bool ok) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) ok = ok && raw.positions[i].allFinite();
        return ok;
      },
      std::logical_and<>());
  if (finite) return;
  const std::size_t kept = compact(raw, [&](std::size_t i) { return raw.positions[i].allFinite(); });
  result.dropped_non_finite = all - kept;
  if (kept == 0) source.fail(raw.format + ": all " + std::to_string(all) + " points have a NaN or infinite coordinate");
  if (result.dropped_non_finite > 0)
    result.warnings.push_back(source.path + ": dropped " + std::to_string(result.dropped_non_finite) + " of " +
                              std::to_string(all) + " points with a NaN or infinite coordinate");
}

// --classes, --drop-classes and --crop, all in one pass over the file's own coordinates.
void filter(RawCloud& raw, ReadResult& result, const Source& source, const ReadOptions& options) {
  const bool by_class = !options.classes.empty() || !options.drop_classes.empty();
  if (!by_class && !options.crop) return;
  const PointAttribute* classification = nullptr;
  for (const PointAttribute& a : raw.attributes)
    if (a.name == "classification") classification = &a;
  if (by_class && classification == nullptr)
    source.fail(raw.format + ": the file has no classification to keep or drop classes by (LAS files have one)");
  const std::size_t all = raw.positions.size();
  const std::size_t kept = compact(raw, [&](std::size_t i) {
    if (by_class && !detail::class_kept(options, static_cast<int>(classification->values[i]))) return false;
    const Vec3d& p = raw.positions[i];
    return !options.crop ||
           ((p.array() >= options.crop->min.array()).all() && (p.array() <= options.crop->max.array()).all());
  });
  result.dropped_by_filter = all - kept;
  if (kept == 0) {
    source.fail(raw.format + ": none of the " + std::to_string(all) + " points is left by the " +
                detail::filters_named(by_class, options.crop.has_value()));
  }
}

// Normals must be unit length: a file whose normals are zero, not finite or not unit vectors (colours read as
// normals, unnormalised exports) is treated as having none, and the pipeline estimates them.
void check_normals(RawCloud& raw, ReadResult& result, const Source& source) {
  if (raw.normals.empty()) return;
  std::size_t bad = 0;
  for (const Vec3f& n : raw.normals) bad += !(n.allFinite() && n.norm() > 0.f);
  if (bad > 0) {
    result.warnings.push_back(source.path + ": " + std::to_string(bad) +
                              " normals are zero or not finite; normals ignored");
    raw.normals.clear();
    return;
  }
  const double unit = detail::unit_fraction(raw.normals);
  if (unit < detail::kUnitShare) {
    result.warnings.push_back(source.path + ": the file's normals are not unit vectors (only " +
                              std::to_string(static_cast<int>(unit * 100.0)) +
                              "% are); they are recomputed from the points");
    raw.normals.clear();
    return;
  }
  for (Vec3f& n : raw.normals) n.normalize();
}

// The thinning asked for: --voxel and --max-points, and the resolution rule for a file of more points than its
// budget (a format read whole: OFF, OBJ, compressed PCD; the others are thinned while streamed, by the same rule).
void thin(ReadResult& result, const DecimateOptions& options) {
  PointCloud& cloud = result.cloud;
  DecimateOptions d = options;
  std::string reason = d.voxel && d.max_points ? "--voxel and --max-points" : d.voxel ? "--voxel" : "--max-points";
  if (d.resolution && result.points_in_file > d.resolution->budget() && !cloud.empty()) {
    const std::size_t stride = std::max<std::size_t>(1, cloud.size() / detail::kSurveySample);
    std::vector<Vec3d> sample;
    for (std::size_t i = 0; i < cloud.size(); i += stride) sample.push_back(cloud.positions[i].cast<double>());
    const double cell = resolution_cell(*d.resolution, detail::robust_extent(std::move(sample)));
    if (cell > d.voxel.value_or(0.0)) {
      d.voxel = cell;
      reason =
          detail::resolution_reason(*d.resolution, result.points_in_file) + (d.max_points ? ", then --max-points" : "");
    }
  }
  if (!d.active()) return;
  result.decimation = decimate(cloud, d);
  result.decimation->reason = reason;
}

ReadResult finish_points(RawCloud&& raw, const Source& source, const ReadOptions& options) {
  ReadResult result;
  result.points_in_file = raw.positions.size();
  result.warnings = std::move(raw.warnings);
  if (!options.keep_normals) raw.normals.clear();
  if (!options.keep_colors) raw.colors.clear();
  drop_non_finite(raw, result, source);
  if (options.collapse_duplicates) result.duplicates = detail::collapse_duplicates(raw);
  if (result.duplicates > 0)
    result.warnings.push_back(source.path + ": " + std::to_string(result.duplicates) +
                              " points repeat an earlier point exactly; one copy of each kept");
  filter(raw, result, source, options);
  check_normals(raw, result, source);

  PointCloud& cloud = result.cloud;
  cloud.origin = choose_origin(raw.positions, options);
  cloud.positions = relative(raw.positions, cloud.origin, source);
  cloud.normals = std::move(raw.normals);
  cloud.colors = std::move(raw.colors);
  cloud.attributes = std::move(raw.attributes);
  result.format = std::move(raw.format);
  result.columns = std::move(raw.columns);
  result.other_attributes = std::move(raw.other_attributes);
  thin(result, options.decimate);
  return result;
}

ReadResult read_points(const Source& source, const ReadOptions& options) {
  if (std::optional<ReadResult> streamed = detail::read_streamed(source, options, options.stream_chunk_points))
    return std::move(*streamed);
  const ProgressReporter report(options.progress, "read");
  report(0.0);
  ReadResult result = finish_points(choose_reader(source).parse(source, Want::Points), source, options);
  report(1.0);
  return result;
}

Mesh read_faces(const Source& source, const ReadOptions& options) {
  const Reader& reader = choose_reader(source);
  if (!reader.has_faces)
    source.fail(std::string(reader.name) + ": the format holds no faces; a mesh must be PLY, OFF or OBJ");
  RawCloud raw = reader.parse(source, Want::Mesh);
  for (std::size_t i = 0; i < raw.positions.size(); ++i)
    if (!raw.positions[i].allFinite())
      source.fail(raw.format + ": vertex " + std::to_string(i) + " has a NaN or infinite coordinate");
  if (raw.faces.empty()) source.fail(raw.format + ": the file holds no faces with 3 or more vertices");
  Mesh mesh;
  mesh.origin = choose_origin(raw.positions, options);
  mesh.vertices = relative(raw.positions, mesh.origin, source);
  mesh.faces = std::move(raw.faces);
  return mesh;
}

}  // namespace

void check_scale(const PointCloud& cloud, const std::string& name) {
  const Box3f box = bounding_box(cloud.positions);
  if (box.empty()) return;
  const double extent = (box.max - box.min).cast<double>().maxCoeff();
  if (extent > kMaxCloudExtent || (extent > 0 && extent < kMinCloudExtent)) {
    char span[32];  // three digits: the extent comes from float positions, its last digits mean nothing
    std::snprintf(span, sizeof span, "%.3g", extent);
    throw Error(FileLoc{name, {}, {}}, "the points span " + std::string(span) + " units, outside the " +
                                           number(kMinCloudExtent) + " to " + number(kMaxCloudExtent) +
                                           " that float geometry handles (a stray point far away, or wrong units?)");
  }
}

ReadResult read_point_cloud(const std::string& path, const ReadOptions& options) {
  const detail::MappedFile file(path);
  return read_points(Source{file.bytes(), path, options.columns, &options.progress, true}, options);
}

std::optional<std::uint64_t> points_in_header(const std::string& path) {
  const detail::MappedFile file(path);
  const Source source{file.bytes(), path};
  if (const std::optional<detail::StreamHeader> las = detail::las_stream_header(source)) return las->count;
  if (const std::optional<std::uint64_t> pcd = detail::pcd_header_count(source)) return pcd;
  return detail::ply_header_count(source);
}

std::optional<Vec3d> conventional_up(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[4] = {};
  if (!in.read(head, sizeof head)) return std::nullopt;
  if (sniff_las(std::string_view(head, sizeof head))) return Vec3d(0, 0, 1);
  return std::nullopt;
}

std::optional<std::uint64_t> estimated_text_rows(const std::string& path) {
  const detail::MappedFile file(path);
  const Source source{file.bytes(), path};
  if (!detail::reads_as_xyz(source)) return std::nullopt;
  return detail::sampled_rows(source);
}

ReadResult read_point_cloud_from_memory(std::string_view bytes, const std::string& name_hint,
                                        const ReadOptions& options) {
  return read_points(Source{bytes, name_hint, options.columns, &options.progress}, options);
}

Mesh read_mesh(const std::string& path, const ReadOptions& options) {
  const detail::MappedFile file(path);
  return read_faces(Source{file.bytes(), path}, options);
}

Mesh read_mesh_from_memory(std::string_view bytes, const std::string& name_hint, const ReadOptions& options) {
  return read_faces(Source{bytes, name_hint}, options);
}

namespace detail {
bool reads_as_xyz(const Source& source) { return choose_reader(source).parse == parse_xyz; }

// Recentre far-away clouds on a whole-unit origin; keep origin 0 for clouds around the world origin, where float
// positions lose nothing worth keeping (at most 4 bits against a centred cloud).
Vec3d choose_origin(const Vec3d& lo, const Vec3d& hi, const ReadOptions& options) {
  if (!options.recentre) return Vec3d::Zero();
  const Vec3d centre = 0.5 * (lo + hi);
  const double extent = (hi - lo).maxCoeff();
  if (centre.cwiseAbs().maxCoeff() <= 8.0 * extent) return Vec3d::Zero();
  return centre.array().round().matrix();
}

void add_fan(std::span<const std::uint32_t> polygon, std::vector<std::array<std::uint32_t, 3>>& faces) {
  for (std::size_t i = 2; i < polygon.size(); ++i) faces.push_back({polygon[0], polygon[i - 1], polygon[i]});
}
}  // namespace detail

}  // namespace pcsketch::io
