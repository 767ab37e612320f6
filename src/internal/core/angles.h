#pragma once
// Options give angles in degrees; the tests that read them work in radians.

#include <numbers>

namespace pcsketch::detail {

inline constexpr float kDegToRad = std::numbers::pi_v<float> / 180.f;

}  // namespace pcsketch::detail
