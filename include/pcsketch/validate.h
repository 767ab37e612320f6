#pragma once
// Every option checked in one place, before any work starts: the library (prepare, draw_view) and the CLI (right
// after parsing, before reading the input) call the same function, so a bad value fails at once with the flag named.
// Each option's range is its entry in the option table (options_table.h), which the CLI also checks while parsing;
// validate() adds what one range cannot say (relations between options, directions, image memory).

#include <cstddef>
#include <optional>
#include <string>

#include "pcsketch/core/error.h"

namespace pcsketch {

struct DrawOptions;
namespace differential {
struct SurfaceOptions;
}
namespace view {
struct CameraOptions;
}

/// A bad option value. `flag` is the CLI flag that sets it (or the option field when no flag does); the message
/// reads "--flag: why".
class OptionError : public Error {
 public:
  OptionError(const std::string& flag, const std::string& why) : Error(flag + ": " + why), flag_(flag) {}
  const std::string& flag() const { return flag_; }

 private:
  std::string flag_;
};

/// Largest image side: cairo's limit for PNG, kept for every format so that one --size works for all of them.
inline constexpr int kMaxImageSide = 32767;
/// Most memory the image-sized buffers (raster, attached-shadow grid) may take, estimated before anything is
/// allocated: beyond it a drawing is refused rather than left to exhaust the machine.
inline constexpr double kMaxImageBytes = 2.0 * (1ull << 30);
/// Smallest attached hatch spacing, px: closer lines are solid ink and only make the output huge.
inline constexpr float kMinHatchSpacingPx = 1.0f;

/// Estimated bytes of the buffers sized by the image of `options` (A8 raster plus attached-shadow grid).
double image_bytes(const DrawOptions& options, const view::CameraOptions& camera);

/// Memory a point costs the analysis and the drawing beyond the image buffers, at most: kBytesPerPoint plus
/// kBytesPerNeighbour for each of its `--neighbours` k. Measured as the growth of peak RSS of `pcsketch draw
/// --size 64x64 --full-resolution` (2 threads) on area-uniform samples of fandisk, 50k to 400k points: 338 bytes a
/// point at k = 16 and 677 at k = 64 on clean samples (the k-NN lists hold an index and a distance: 8 a neighbour;
/// about 210 besides: positions, normals, curvature, Embree's discs, …). A noisy cloud costs more, and the estimate
/// is made before the analysis knows: denoising adds its weights (4 a neighbour) and, where the wider normals fire
/// (docs/geometry.md, "Noise", item 9), their lists of 4k indices (16 a neighbour). Samples at σ = 0.2%: 690 bytes a
/// point at k = 16 (430 before the wider normals), 682 at k = 32 (where they do not fire). So 256 + 28 a neighbour:
/// 704 at k = 16, about twice a clean cloud's cost, which a limit set by --max-memory can override.
inline constexpr double kBytesPerPoint = 256;
inline constexpr double kBytesPerNeighbour = 28;

/// Estimated bytes of the analysis of `points` points with `surface` (kBytesPerPoint, kBytesPerNeighbour).
double point_bytes(const differential::SurfaceOptions& surface, std::size_t points);

/// The machine's physical memory in bytes: the memory limit when `--max-memory` is not given.
double physical_memory_bytes();

/// Refuses work estimated at `bytes` when that exceeds `max_memory_gb` GB (1e9 bytes) or, unset, the physical
/// memory. @throws OptionError naming --max-memory, the message starting with `what` (the input and its size).
void validate_memory(double bytes, const std::optional<double>& max_memory_gb, const std::string& what);

/// validate_memory() for a drawing of `points` points from `source` (the input file, or "the cloud"): the image
/// buffers of options.camera plus point_bytes().
void validate_memory(const DrawOptions& options, std::size_t points, const std::string& source);

/// Checks every field of `options` (NaN and Inf are refused everywhere; each value within its documented range;
/// image size and memory within the limits above). @throws OptionError for the first bad value.
void validate(const DrawOptions& options);

/// The camera part of validate(), for a camera passed apart from the options (draw_view).
void validate(const DrawOptions& options, const view::CameraOptions& camera);

}  // namespace pcsketch
