// PDF and PNG through cairo, painting the same layers as the SVG writer.

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <memory>

#include "pcsketch/core/error.h"
#include "pcsketch/render/pdf.h"
#include "pcsketch/render/png.h"
#include "render/paint.h"

namespace pcsketch::render {

namespace {

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};
using SurfacePtr = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using ContextPtr = std::unique_ptr<cairo_t, ContextDeleter>;

void check(cairo_status_t status, const std::filesystem::path& path, const char* format) {
  if (status != CAIRO_STATUS_SUCCESS)
    throw Error(path.string() + ": " + format + ": " + cairo_status_to_string(status));
}

void trace(cairo_t* cr, const std::vector<Vec2f>& points, bool closed) {
  cairo_new_path(cr);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i == 0) cairo_move_to(cr, points[i].x(), points[i].y());
    else cairo_line_to(cr, points[i].x(), points[i].y());
  }
  if (closed) cairo_close_path(cr);
}

/// Paints every layer in image pixels onto `cr` (already scaled to the page).
void paint(cairo_t* cr, const Drawing& d, const RenderOptions& o) {
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const detail::PaintLayer& layer : detail::paint_layers(d, o)) {
    for (std::size_t r : layer.regions) {
      const ShadeRegion& region = d.regions[r];
      trace(cr, region.polygon, true);
      const double g = std::clamp(region.grey, 0.f, 1.f);
      cairo_set_source_rgb(cr, g, g, g);
      cairo_fill(cr);
    }
    for (const detail::PaintStroke& stroke : layer.strokes) {
      for (const detail::Run& run : stroke.runs) {
        trace(cr, run.points, run.closed);
        cairo_set_source_rgb(cr, run.grey, run.grey, run.grey);
        cairo_set_line_width(cr, run.width);
        const double dash = o.hidden_dash;
        cairo_set_dash(cr, &dash, run.dashed ? 1 : 0, 0);
        cairo_stroke(cr);
      }
    }
  }
}

}  // namespace

void write_pdf(const Drawing& d, const std::filesystem::path& path, const RenderOptions& o) {
  const auto page = detail::page_size_pt(d, o);
  SurfacePtr surface(cairo_pdf_surface_create(path.c_str(), page[0], page[1]));
  check(cairo_surface_status(surface.get()), path, "PDF");
  ContextPtr cr(cairo_create(surface.get()));
  cairo_scale(cr.get(), page[0] / d.width, page[1] / d.height);
  paint(cr.get(), d, o);
  cairo_show_page(cr.get());
  check(cairo_status(cr.get()), path, "PDF");
  cr.reset();
  cairo_surface_finish(surface.get());
  check(cairo_surface_status(surface.get()), path, "PDF");
}

void write_png(const Drawing& d, const std::filesystem::path& path, const RenderOptions& o) {
  // cairo's image surfaces are limited to 32767 pixels a side.
  if (d.width <= 0 || d.height <= 0 || d.width > 32767 || d.height > 32767)
    throw Error(path.string() + ": PNG: image size must be within 1..32767 pixels");
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, d.width, d.height));
  check(cairo_surface_status(surface.get()), path, "PNG");
  ContextPtr cr(cairo_create(surface.get()));
  cairo_set_source_rgb(cr.get(), 1, 1, 1);
  cairo_paint(cr.get());
  paint(cr.get(), d, o);
  check(cairo_status(cr.get()), path, "PNG");
  cr.reset();
  check(cairo_surface_write_to_png(surface.get(), path.c_str()), path, "PNG");
}

}  // namespace pcsketch::render
