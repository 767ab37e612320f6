// PDF and PNG through cairo, painting the same layers as the SVG writer; the PNG is encoded by libpng.

#include <cairo-pdf.h>
#include <cairo.h>
#include <png.h>

#include <algorithm>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <string>

#include "pcsketch/core/error.h"
#include "pcsketch/render/pdf.h"
#include "pcsketch/render/png.h"
#include "paint.h"

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

/// How ink of grey level g (0 black … 1 white) is put on the surface.
enum class Ink {
  Rgb,   ///< colour surfaces (PDF): source colour (g, g, g) over the page
  Alpha  ///< A8 surfaces (PNG): the alpha channel holds the grey level, painted with OPERATOR_SOURCE
};

void set_ink(cairo_t* cr, Ink ink, double grey) {
  if (ink == Ink::Rgb) cairo_set_source_rgb(cr, grey, grey, grey);
  else cairo_set_source_rgba(cr, 0, 0, 0, grey);
}

/// The page's scale bar, north arrow and view names, black, over the model's lines.
void paint_annotations(cairo_t* cr, const Annotations& a, Ink ink) {
  set_ink(cr, ink, 0.0);
  cairo_set_line_width(cr, a.width);
  cairo_set_dash(cr, nullptr, 0, 0);
  for (const auto& line : a.lines) {
    trace(cr, line, false);
    cairo_stroke(cr);
  }
  for (const auto& fill : a.fills) {
    trace(cr, fill, true);
    cairo_fill(cr);
  }
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  for (const Label& label : a.labels) {
    cairo_set_font_size(cr, label.size);
    cairo_text_extents_t extents;
    cairo_text_extents(cr, label.text.c_str(), &extents);
    const double shift = label.anchor == Label::Anchor::Start ? 0.0
                         : label.anchor == Label::Anchor::Middle ? 0.5 * extents.x_advance
                                                                 : extents.x_advance;
    cairo_move_to(cr, label.position.x() - shift, label.position.y());
    cairo_show_text(cr, label.text.c_str());
  }
}

/// Paints every layer in image pixels onto `cr` (already scaled to the page).
void paint(cairo_t* cr, const Drawing& d, const RenderOptions& o, Ink ink) {
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const detail::PaintLayer& layer : detail::paint_layers(d, o)) {
    for (std::size_t r : layer.regions) {
      const ShadeRegion& region = d.regions[r];
      trace(cr, region.polygon, true);
      set_ink(cr, ink, std::clamp(region.grey, 0.f, 1.f));
      cairo_fill(cr);
    }
    for (const detail::PaintStroke& stroke : layer.strokes) {
      for (const detail::Run& run : stroke.runs) {
        trace(cr, run.points, run.closed);
        set_ink(cr, ink, run.grey);
        cairo_set_line_width(cr, run.width);
        const double dash = o.hidden_dash;
        cairo_set_dash(cr, &dash, run.dashed ? 1 : 0, 0);
        cairo_stroke(cr);
      }
    }
  }
  paint_annotations(cr, d.annotations, ink);
}

/// The PDF's creation and modification date, ISO 8601 UTC: SOURCE_DATE_EPOCH (seconds, the reproducible-builds
/// convention) when set, else the epoch itself. Never the clock: the same drawing gives the same bytes. (cairo 1.16
/// writes a date given this way without the "D:" prefix of its own dates; poppler reads it, pdf.js shows none.)
std::string pdf_date() {
  std::time_t t = 0;
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH"); epoch && *epoch) {
    char* end = nullptr;
    const long long seconds = std::strtoll(epoch, &end, 10);
    if (*end == '\0' && seconds >= 0 && seconds < 253402300800) t = static_cast<std::time_t>(seconds);  // < 10000 AD
  }
  std::tm utc{};
  gmtime_r(&t, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace

void write_pdf(const Drawing& d, const std::filesystem::path& path, const RenderOptions& o) {
  const auto page = detail::page_size_pt(d, o);
  SurfacePtr surface(cairo_pdf_surface_create(path.c_str(), page[0], page[1]));
  check(cairo_surface_status(surface.get()), path, "PDF");
  const std::string date = pdf_date();
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, date.c_str());
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_MOD_DATE, date.c_str());
  ContextPtr cr(cairo_create(surface.get()));
  cairo_scale(cr.get(), page[0] / d.width, page[1] / d.height);
  paint(cr.get(), d, o, Ink::Rgb);
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
  // A drawing is grey: an 8-bit surface (cairo writes A8 as a grey PNG, the alpha value being the grey level) is a
  // third of the bytes of RGB, so PNG compression, the costly part, takes about a third of the time.
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_A8, d.width, d.height));
  check(cairo_surface_status(surface.get()), path, "PNG");
  ContextPtr cr(cairo_create(surface.get()));
  // SOURCE with anti-aliasing coverage c gives grey·c + previous·(1 − c): ink laid over what is there, as OVER does
  // for opaque colours.
  cairo_set_operator(cr.get(), CAIRO_OPERATOR_SOURCE);
  set_ink(cr.get(), Ink::Alpha, 1.0);
  cairo_paint(cr.get());
  paint(cr.get(), d, o, Ink::Alpha);
  check(cairo_status(cr.get()), path, "PNG");
  cr.reset();
  cairo_surface_flush(surface.get());
  // libpng's fast mode rather than cairo_surface_write_to_png: that one compresses at zlib's default level with
  // adaptive row filters, the largest serial step of a bunny drawing (14 ms of 150); mostly white, a drawing
  // compresses well either way.
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(d.width);
  image.height = static_cast<png_uint_32>(d.height);
  image.format = PNG_FORMAT_GRAY;
  image.flags = PNG_IMAGE_FLAG_FAST;
  if (!png_image_write_to_file(&image, path.c_str(), 0, cairo_image_surface_get_data(surface.get()),
                               cairo_image_surface_get_stride(surface.get()), nullptr))
    throw Error(path.string() + ": PNG: " + image.message);
}

}  // namespace pcsketch::render
