#include "pcsketch/render/svg.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "pcsketch/core/error.h"
#include "paint.h"

namespace pcsketch::render {

namespace {

/// Appends numbers with a fixed number of decimals, trailing zeros trimmed ("12.5", "3", "-0.25").
class NumberWriter {
 public:
  NumberWriter(std::string& out, int decimals) : out_(out), decimals_(std::clamp(decimals, 0, 6)) {}
  void operator()(double v) {
    char buf[64];
    auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals_);
    if (ec != std::errc()) end = buf;
    if (decimals_ > 0) {
      while (end > buf && end[-1] == '0') --end;
      if (end > buf && end[-1] == '.') --end;
    }
    std::string_view s(buf, static_cast<std::size_t>(end - buf));
    if (s == "-0" || s.empty()) s = "0";
    out_.append(s);
  }

 private:
  std::string& out_;
  int decimals_;
};

std::string xml_escaped(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string grey_colour(float grey) {
  char buf[8];
  const int g = static_cast<int>(std::lround(std::clamp(grey, 0.f, 1.f) * 255.f));
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", g, g, g);
  return buf;
}

void append_points(std::string& out, NumberWriter& num, const std::vector<Vec2f>& points, bool closed) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    out += i == 0 ? "M" : " L";
    num(points[i].x());
    out += ',';
    num(points[i].y());
  }
  if (closed) out += " Z";
}

void append_run(std::string& out, NumberWriter& num, const detail::Run& run, const RenderOptions& o,
                const char* indent) {
  out += indent;
  out += "<path d=\"";
  append_points(out, num, run.points, run.closed);
  out += "\" stroke=\"" + grey_colour(run.grey) + "\" stroke-width=\"";
  num(run.width);
  out += '"';
  if (run.dashed) {
    out += " stroke-dasharray=\"";
    num(o.hidden_dash);
    out += "\"";
  }
  out += "/>\n";
}

/// The page's scale bar, north arrow and view names, in a layer after the model's.
void append_annotations(std::string& out, NumberWriter& num, const Annotations& a) {
  if (a.empty()) return;
  out += "  <g inkscape:groupmode=\"layer\" id=\"layer8\" inkscape:label=\"8 annotations\" fill=\"none\" "
         "stroke=\"#000000\" stroke-width=\"";
  num(a.width);
  out += "\">\n";
  for (const auto& line : a.lines) {
    out += "    <path d=\"";
    append_points(out, num, line, false);
    out += "\"/>\n";
  }
  for (const auto& fill : a.fills) {
    out += "    <path d=\"";
    append_points(out, num, fill, true);
    out += "\" fill=\"#000000\" stroke=\"none\"/>\n";
  }
  static constexpr const char* kAnchor[] = {"start", "middle", "end"};
  for (const Label& label : a.labels) {
    out += "    <text x=\"";
    num(label.position.x());
    out += "\" y=\"";
    num(label.position.y());
    out += "\" font-family=\"sans-serif\" font-size=\"";
    num(label.size);
    out += "\" text-anchor=\"";
    out += kAnchor[static_cast<int>(label.anchor)];
    out += "\" fill=\"#000000\" stroke=\"none\">" + xml_escaped(label.text) + "</text>\n";
  }
  out += "  </g>\n";
}

}  // namespace

std::string svg_string(const Drawing& d, const RenderOptions& o) {
  const auto page = detail::page_size_pt(d, o);
  std::string out;
  out.reserve(4096);
  NumberWriter num(out, o.decimals);
  NumberWriter page_num(out, 3);
  out += "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\"\n";
  out += "     xmlns:sodipodi=\"http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd\" version=\"1.1\"\n";
  out += "     width=\"";
  // Page size: CSS pixels (0.75 pt) or millimetres; the viewBox keeps every coordinate in image pixels.
  const bool in_mm = page_in_mm(d, o);
  const double to_unit = in_mm ? 25.4 / 72.0 : 1.0 / 0.75;
  const char* unit = in_mm ? "mm" : "px";
  page_num(page[0] * to_unit);
  out += unit;
  out += "\" height=\"";
  page_num(page[1] * to_unit);
  out += unit;
  out += "\" viewBox=\"0 0 " + std::to_string(d.width) + " " + std::to_string(d.height) + "\">\n";
  out += "  <title>pcsketch drawing</title>\n";
  nlohmann::json record = {{"camera", d.camera}, {"parameters", d.parameters}, {"render", o.to_json()}};
  if (!d.plotter.is_null()) record["plotter"] = d.plotter;
  out += "  <desc>" + xml_escaped(record.dump()) + "</desc>\n";
  out += "  <sodipodi:namedview inkscape:document-units=\"";
  out += unit;
  out += "\"/>\n";

  for (const detail::PaintLayer& layer : detail::paint_layers(d, o)) {
    out += "  <g inkscape:groupmode=\"layer\" id=\"layer" + std::to_string(layer.number) + "\" inkscape:label=\"";
    out += layer.label;
    out += "\"";
    if (!layer.regions.empty()) {
      out += " stroke=\"none\">\n";
      for (std::size_t r : layer.regions) {
        out += "    <path d=\"";
        append_points(out, num, d.regions[r].polygon, true);
        out += "\" fill=\"" + grey_colour(d.regions[r].grey) + "\"/>\n";
      }
    } else {
      out += " fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
    }
    for (const detail::PaintStroke& stroke : layer.strokes) {
      if (stroke.runs.size() == 1) {
        append_run(out, num, stroke.runs[0], o, "    ");
        continue;
      }
      out += "    <g>\n";
      for (const detail::Run& run : stroke.runs) append_run(out, num, run, o, "      ");
      out += "    </g>\n";
    }
    out += "  </g>\n";
  }
  append_annotations(out, num, d.annotations);
  out += "</svg>\n";
  return out;
}

void write_svg(const Drawing& drawing, const std::filesystem::path& path, const RenderOptions& options) {
  const std::string text = svg_string(drawing, options);
  std::ofstream file(path, std::ios::binary);
  file.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!file.flush()) throw Error(path.string() + ": SVG: cannot write the file");
}

}  // namespace pcsketch::render
