#include "options.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "pcsketch/core/atomic_file.h"
#include "pcsketch/core/error.h"
#include "pcsketch/validate.h"

namespace pcsketch::cli {

namespace {

// "xmin,ymin,zmin,xmax,ymax,zmax" → box; throws CLI::ValidationError (exit 1) otherwise.
io::CropBox parse_crop(const std::string& text) {
  std::istringstream in(text);
  std::array<double, 6> v{};
  for (std::size_t i = 0; i < v.size(); ++i) {
    char comma = ',';
    if ((i > 0 && !(in >> comma)) || comma != ',' || !(in >> v[i]) || !std::isfinite(v[i]))
      throw CLI::ValidationError("--crop", "expected six numbers xmin,ymin,zmin,xmax,ymax,zmax, got '" + text + "'");
  }
  if (!(in >> std::ws).eof())
    throw CLI::ValidationError("--crop", "expected six numbers xmin,ymin,zmin,xmax,ymax,zmax, got '" + text + "'");
  const io::CropBox box{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
  if ((box.min.array() > box.max.array()).any())
    throw CLI::ValidationError("--crop", "each minimum must be at most its maximum, got '" + text + "'");
  return box;
}

/// Surface analysis and ridge/valley options: the flags `features` shares with `draw`.
bool analysis_option(const options::Option& opt) {
  return opt.key.starts_with("surface.") || opt.key.starts_with("features.") || opt.key.starts_with("boundary.");
}

}  // namespace

void add_read_options(CLI::App* cmd, io::ReadOptions& read) {
  const std::string group = "Input";
  cmd->add_option_function<std::string>(
         "--columns",
         [&read](const std::string& spec) {
           try {
             read.columns = io::parse_columns(spec);
           } catch (const Error& e) {
             throw CLI::ValidationError("--columns", e.what());
           }
         },
         "Text files: what each column holds, e.g. x,y,z,r,g,b (names: x y z r g b i nx ny nz skip); default: "
         "the header row, else guessed from the values")
      ->group(group);
  cmd->add_option("--classes", read.classes, "LAS: keep only these classifications, e.g. 2,6 (ground, building)")
      ->delimiter(',')
      ->check(CLI::Range(0, 255))
      ->group(group);
  cmd->add_option("--drop-classes", read.drop_classes, "LAS: remove these classifications, e.g. 7 (noise)")
      ->delimiter(',')
      ->check(CLI::Range(0, 255))
      ->group(group);
  cmd->add_option_function<std::string>(
         "--crop", [&read](const std::string& s) { read.crop = parse_crop(s); },
         "Keep only the points in this box, in the file's coordinates: xmin,ymin,zmin,xmax,ymax,zmax")
      ->group(group);
  cmd->add_option("--voxel", read.decimate.voxel,
                  "Thin to one point per cube of this edge (model units), the one nearest its centre")
      ->check(CLI::PositiveNumber)
      ->group(group);
  cmd->add_option("--max-points", read.decimate.max_points,
                  "Thin to at most this many points with the smallest voxel that gets there (at least 8)")
      ->check(CLI::Range(std::size_t{8}, std::numeric_limits<std::size_t>::max()))
      ->group(group);
  // Thinning to the output's resolution is the default; the commands set the image (for_image) before reading.
  read.decimate.resolution = io::OutputResolution{};
  cmd->add_flag_callback(
         "--full-resolution", [&read] { read.decimate.resolution.reset(); },
         "Keep every point of a cloud larger than the image needs (by default one per cell of about a pixel is kept); "
         "refused at once when the estimated memory exceeds what the machine has available")
      ->group(group);
}

void for_image(io::ReadOptions& read, const view::CameraOptions& camera) {
  if (!read.decimate.resolution) return;
  // A perspective eye placed by hand may stand anywhere near the cloud: no pixel size bounds its nearest depth.
  if (camera.projection == view::Projection::Perspective && camera.eye) {
    read.decimate.resolution.reset();
    return;
  }
  io::OutputResolution& r = *read.decimate.resolution;
  r.width = camera.width;
  r.height = camera.height;
  r.perspective = camera.projection == view::Projection::Perspective;
  r.fov_deg = camera.fov_deg;
}

double available_memory_bytes() {
  // Tests inject a small figure; the machine's MemAvailable otherwise.
  if (const char* given = std::getenv("PCSKETCH_MEM_AVAILABLE")) return std::strtod(given, nullptr);
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kb = 0;
  while (meminfo >> key >> kb) {
    if (key == "MemAvailable:") return kb * 1024.0;
    meminfo.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  return physical_memory_bytes();
}

void check_full_resolution(const io::ReadOptions& read, const std::string& input, double bytes_per_point) {
  if (read.decimate.resolution || read.decimate.active()) return;
  std::optional<std::uint64_t> count = io::points_in_header(input);
  const bool estimated = !count;
  if (estimated) count = io::estimated_text_rows(input);
  if (!count) return;
  const double need = static_cast<double>(*count) * (kReadBytesPerPoint + bytes_per_point);
  const double available = available_memory_bytes();
  if (need <= available) return;
  char text[320];
  std::snprintf(text, sizeof text,
                "%s holds %s%llu points%s, estimated to need %.3g GB (%.0f bytes a point: docs/geometry.md), over the "
                "%.3g GB available (MemAvailable); leave out --full-resolution to thin it to the image's resolution",
                one_line(input).c_str(), estimated ? "about " : "", static_cast<unsigned long long>(*count),
                estimated ? " (from its line lengths)" : "", need / 1e9, kReadBytesPerPoint + bytes_per_point,
                available / 1e9);
  throw OptionError("--full-resolution", text);
}

std::string describe_reduction(const io::ReadResult& read) {
  std::string out;
  if (read.dropped_by_filter > 0)
    out += std::to_string(read.dropped_by_filter) + " outside the crop box or of classes not kept";
  if (read.decimation) {
    const io::DecimateReport& d = *read.decimation;
    char text[160];
    std::snprintf(text, sizeof text, "voxel thinning %zu -> %zu points (cell %.6g, %.3f s%s)", d.points_before,
                  d.points_after, d.cell, d.seconds, d.streamed ? ", streamed" : "");
    out += (out.empty() ? "" : "; ") + std::string(text);
    if (!d.reason.empty()) out += " by " + d.reason;
  }
  return out;
}

nlohmann::json input_json(const io::ReadResult& read) {
  if (!read.decimation) return nullptr;
  const io::DecimateReport& d = *read.decimation;
  return {{"points_in_file", read.points_in_file},
          {"dropped_non_finite", read.dropped_non_finite},
          {"dropped_by_filter", read.dropped_by_filter},
          {"points_kept", d.points_after},
          {"thinning", {{"points_before", d.points_before},
                        {"cell", d.cell},
                        {"reason", d.reason},
                        {"streamed", d.streamed}}}};
}

void add_analysis_flags(CLI::App* cmd, DrawOptions& o) {
  add_table_flags(cmd, o, [](const options::Option& opt) { return analysis_option(opt); });
  // One flag, two fields: surface.orient_file_normals and surface.file_normal_disagreement.
  differential::SurfaceOptions& surface = o.surface;
  cmd->add_option_function<std::string>(
         "--file-normals",
         [&surface](const std::string& mode) {
           surface.orient_file_normals = mode == "orient";
           if (mode == "trust") surface.file_normal_disagreement = 1.0;
         },
         "Normals read from the file: auto (kept, but re-oriented when their signs disagree between neighbours), "
         "trust (kept as they are) or orient (always re-oriented)")
      ->check(CLI::IsMember({"auto", "trust", "orient"}))
      ->default_str("auto")
      ->group("Surface analysis");
}

void add_draw_options(CLI::App* cmd, DrawOptions& o) {
  add_analysis_flags(cmd, o);
  add_table_flags(cmd, o, [](const options::Option& opt) { return !analysis_option(opt); });
  cmd->get_option("--pen-width-px")->excludes("--pen-width-mm");
  add_scale_option(cmd, o.page);
}

void add_memory_option(CLI::App* cmd, std::optional<double>& target) {
  cmd->add_option("--max-memory", target,
                  "Refuse a cloud estimated to need more memory than this, GB, before the analysis starts (about "
                  "256 + 28 x --neighbours bytes a point, plus the image buffers); default: the machine's memory")
      ->check(CLI::PositiveNumber)
      ->group("Input");
}

std::filesystem::path same_file_key(const std::string& path) {
  // Without throwing: a name the file system refuses (too long) is refused by check_output_path, with a message.
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
  if (ec) return std::filesystem::path(path).lexically_normal();
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : canonical;
}

void check_output_path(const std::string& flag, const std::string& path) {
  try {
    check_writable(path);
  } catch (const Error& e) {
    throw OptionError(flag, e.what());
  }
}

}  // namespace pcsketch::cli
