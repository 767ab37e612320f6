#pragma once
// Every option checked in one place, before any work starts: the library (prepare, draw_view) and the CLI (right
// after parsing, before reading the input) call the same function, so a bad value fails at once with the flag named.

#include <cstddef>
#include <string>

#include "pcsketch/core/error.h"

namespace pcsketch {

struct DrawOptions;
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

/// Checks every field of `options` (NaN and Inf are refused everywhere; each value within its documented range;
/// image size and memory within the limits above). @throws OptionError for the first bad value.
void validate(const DrawOptions& options);

/// The camera part of validate(), for a camera passed apart from the options (draw_view).
void validate(const DrawOptions& options, const view::CameraOptions& camera);

}  // namespace pcsketch
