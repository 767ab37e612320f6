// One way of choosing the direction of sight, never along up (validate.h): each refusal names the flags involved.

#include <gtest/gtest.h>

#include <string>

#include "pcsketch/pipeline.h"
#include "pcsketch/validate.h"

namespace pcsketch {
namespace {

/// The flag and message validate() refuses `camera` with; empty when it passes.
std::string refusal(const view::CameraOptions& camera) {
  try {
    validate(DrawOptions{}, camera);
  } catch (const OptionError& e) {
    return e.what();
  }
  return "";
}

TEST(ValidateView, ConflictingViewFlagsAreRefused) {
  EXPECT_EQ(refusal({.direction = Vec3d(1, 0, 0), .azimuth_deg = 30.0}).rfind("--view: conflicts with --azimuth", 0),
            0u);
  EXPECT_EQ(refusal({.direction = Vec3d(1, 0, 0), .named = view::NamedView::Top}).rfind("--view: conflicts with", 0),
            0u);
  EXPECT_NE(refusal({.named = view::NamedView::Iso, .elevation_deg = 10.0}).find("--elevation"), std::string::npos);
  EXPECT_NE(refusal({.azimuth_deg = 10.0, .eye = Vec3d(0, 0, -5), .target = Vec3d::Zero()}).find("--eye/--target"),
            std::string::npos);
  // Each alone is a view; an eye without a target only places a perspective camera.
  EXPECT_EQ(refusal({.direction = Vec3d(1, 0, 0)}), "");
  EXPECT_EQ(refusal({.named = view::NamedView::Left}), "");
  EXPECT_EQ(refusal({.azimuth_deg = 30.0, .elevation_deg = 10.0}), "");
  EXPECT_EQ(refusal({.projection = view::Projection::Perspective, .direction = Vec3d(1, 0, 0), .eye = Vec3d(-5, 0, 0)}),
            "");
}

TEST(ValidateView, SightParallelToUpIsRefused) {
  EXPECT_EQ(refusal({.direction = Vec3d(0, 0, -2), .up = Vec3d(0, 0, 1)})
                .rfind("--view: the direction of sight is "
                       "parallel to --up 0,0,1",
                       0),
            0u);
  // The default +z sight with a z up: the CLI gives the three-quarter view instead; the library names --up.
  EXPECT_EQ(refusal({.up = Vec3d(0, 0, 1)}).rfind("--up:", 0), 0u);
  EXPECT_EQ(refusal({.projection = view::Projection::Perspective,
                     .up = Vec3d(0, 1, 0),
                     .eye = Vec3d(0, 5, 0),
                     .target = Vec3d(0, -1, 0)})
                .rfind("--eye/--target:", 0),
            0u);
  // Named views and elevations of ±90 define the image's up: looking along up is what they mean.
  EXPECT_EQ(refusal({.named = view::NamedView::Top, .up = Vec3d(0, 0, 1)}), "");
  EXPECT_EQ(refusal({.up = Vec3d(0, 0, 1), .elevation_deg = -90.0}), "");
  EXPECT_EQ(refusal({.direction = Vec3d(0, 0.001, 1), .up = Vec3d(0, 0, 1)}), "");  // nearly, not exactly
}

}  // namespace
}  // namespace pcsketch
