#include "pcsketch/render/json.h"

#include <charconv>
#include <cmath>
#include <fstream>

#include "pcsketch/core/error.h"

namespace pcsketch::render {

namespace {

/// The double nearest to the shortest decimal that reads back as `v`: JSON shows 0.1 for 0.1f, not
/// 0.10000000149011612.
double tidy(float v) {
  if (!std::isfinite(v)) return v;
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, v).ptr;
  double out = v;
  std::from_chars(buf, end, out);
  return out;
}

nlohmann::json floats(const std::vector<float>& values) {
  nlohmann::json a = nlohmann::json::array();
  for (float v : values) a.push_back(tidy(v));
  return a;
}

nlohmann::json points2(const std::vector<Vec2f>& points) {
  nlohmann::json a = nlohmann::json::array();
  for (const Vec2f& p : points) a.push_back({tidy(p.x()), tidy(p.y())});
  return a;
}

nlohmann::json annotations_json(const Annotations& a) {
  nlohmann::json lines = nlohmann::json::array(), fills = nlohmann::json::array(), labels = nlohmann::json::array();
  for (const auto& line : a.lines) lines.push_back(points2(line));
  for (const auto& fill : a.fills) fills.push_back(points2(fill));
  for (const Label& l : a.labels)
    labels.push_back({{"position", {tidy(l.position.x()), tidy(l.position.y())}}, {"text", l.text}, {"size", tidy(l.size)}});
  return {{"lines", std::move(lines)}, {"fills", std::move(fills)}, {"labels", std::move(labels)}, {"width", tidy(a.width)}};
}

}  // namespace

nlohmann::json to_json(const Drawing& d) {
  nlohmann::json polylines = nlohmann::json::array();
  const bool at_zero = d.origin.isZero();
  for (const Stroke& s : d.strokes) {
    nlohmann::json points = nlohmann::json::array();
    for (const Vec3f& p : s.points) {
      // world = origin + point, in double: a scan's large origin keeps its precision.
      if (at_zero) points.push_back({tidy(p.x()), tidy(p.y()), tidy(p.z())});
      else points.push_back({d.origin.x() + p.x(), d.origin.y() + p.y(), d.origin.z() + p.z()});
    }
    polylines.push_back({{"kind", to_string(s.kind)},
                         {"visible", s.visible},
                         {"closed", s.closed},
                         {"grey", tidy(s.grey)},
                         {"points", std::move(points)},
                         {"image_points", points2(s.image_points)},
                         {"widths", floats(s.widths)},
                         {"half_widths", floats(s.half_widths)}});
    if (s.fused_into) polylines.back()["fused_into"] = *s.fused_into;
  }
  nlohmann::json regions = nlohmann::json::array();
  for (const ShadeRegion& r : d.regions) regions.push_back({{"grey", tidy(r.grey)}, {"polygon", points2(r.polygon)}});
  nlohmann::json j = {{"image", {{"width", d.width}, {"height", d.height}}},
                      {"origin", {d.origin.x(), d.origin.y(), d.origin.z()}},
                      {"camera", d.camera},
                      {"parameters", d.parameters},
                      {"polylines", std::move(polylines)},
                      {"regions", std::move(regions)}};
  if (!d.plotter.is_null()) j["plotter"] = d.plotter;
  if (!d.input.is_null()) j["input"] = d.input;
  if (d.page_mm_per_pixel) j["page"] = {{"mm_per_pixel", *d.page_mm_per_pixel}};
  if (!d.annotations.empty()) j["annotations"] = annotations_json(d.annotations);
  return j;
}

void write_json(const Drawing& drawing, const std::filesystem::path& path) {
  const std::string text = to_json(drawing).dump() + "\n";
  std::ofstream file(path, std::ios::binary);
  file.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!file.flush()) throw Error(path.string() + ": JSON: cannot write the file");
}

}  // namespace pcsketch::render
