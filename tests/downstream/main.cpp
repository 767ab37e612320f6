// A program using the installed library: draws a sphere of points through the public API and checks the drawing.
// Built by scripts/downstream.sh with find_package(pcsketch) and with pkg-config.

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "pcsketch/pcsketch.h"

// The wrapped libraries are private: their include directories must not reach a user of pcsketch.
#if __has_include(<cairo.h>)
#error "cairo's include directory leaked into pcsketch's users"
#endif

int main() {
  // A Fibonacci sphere: evenly spread points, a closed surface with one outline contour in any view.
  pcsketch::PointCloud cloud;
  const int n = 3000;
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n;
    const double r = std::sqrt(1.0 - z * z);
    const double phi = i * std::numbers::pi * (3.0 - std::sqrt(5.0));
    cloud.positions.emplace_back(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
                                 static_cast<float>(z));
  }
  pcsketch::DrawOptions options;
  options.camera.width = options.camera.height = 256;
  const pcsketch::DrawResult result = pcsketch::draw(cloud, options);

  std::size_t contours = 0;
  for (const pcsketch::Stroke& stroke : result.drawing.strokes)
    if (stroke.kind == pcsketch::LineKind::Contour && stroke.visible) ++contours;
  const std::string svg = pcsketch::render::svg_string(result.drawing);
  if (contours == 0 || svg.find("inkscape:label=\"1 contours\"") == std::string::npos) {
    std::fprintf(stderr, "downstream: expected a visible contour in an SVG with layers (%zu contours)\n", contours);
    return 1;
  }
  std::printf("downstream: %zu strokes, %zu visible contours, %zu bytes of SVG\n", result.drawing.strokes.size(),
              contours, svg.size());
  return 0;
}
