// Renderers on synthetic drawings: SVG structure and layers, JSON ↔ SVG agreement, PNG pixels, PDF header.

#include <cairo.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "pcsketch/core/error.h"
#include "pcsketch/render/json.h"
#include "pcsketch/render/pdf.h"
#include "pcsketch/render/png.h"
#include "pcsketch/render/svg.h"
#include "pcsketch/render/write.h"

namespace pcsketch::render {
namespace {

namespace fs = std::filesystem;

/// A minimal XML element tree; parse() fails the test on malformed input (unbalanced tags, bad attributes).
struct Element {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::vector<Element> children;

  std::vector<const Element*> layers() const {
    std::vector<const Element*> out;
    for (const Element& c : children)
      if (c.name == "g" && c.attributes.count("inkscape:groupmode")) out.push_back(&c);
    return out;
  }
  const Element* layer(std::string_view label) const {
    for (const Element* l : layers())
      if (l->attributes.at("inkscape:label") == label) return l;
    return nullptr;
  }
};

class XmlParser {
 public:
  explicit XmlParser(std::string text) : s_(std::move(text)) {}

  Element parse() {
    skip_prolog();
    Element root = element();
    skip_space();
    EXPECT_EQ(pos_, s_.size()) << "content after the root element";
    return root;
  }

 private:
  void skip_space() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  void skip_prolog() {
    skip_space();
    if (s_.compare(pos_, 5, "<?xml") == 0) pos_ = s_.find("?>", pos_) + 2;
    skip_space();
  }
  std::string name() {
    const std::size_t start = pos_;
    while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == ':' ||
                                s_[pos_] == '-' || s_[pos_] == '_'))
      ++pos_;
    EXPECT_GT(pos_, start) << "expected a name at " << start;
    return s_.substr(start, pos_ - start);
  }
  Element element() {
    Element e;
    EXPECT_EQ(s_[pos_], '<');
    ++pos_;
    e.name = name();
    for (;;) {
      skip_space();
      if (s_.compare(pos_, 2, "/>") == 0) {
        pos_ += 2;
        return e;
      }
      if (s_[pos_] == '>') {
        ++pos_;
        break;
      }
      std::string key = name();
      EXPECT_EQ(s_[pos_], '=');
      EXPECT_EQ(s_[pos_ + 1], '"');
      const std::size_t end = s_.find('"', pos_ + 2);
      EXPECT_EQ(s_.substr(pos_ + 2, end - pos_ - 2).find('<'), std::string::npos);
      EXPECT_FALSE(e.attributes.count(key)) << "duplicate attribute " << key;
      e.attributes[key] = s_.substr(pos_ + 2, end - pos_ - 2);
      pos_ = end + 1;
      if (::testing::Test::HasFailure()) throw std::runtime_error("malformed XML");
    }
    for (;;) {
      const std::size_t lt = s_.find('<', pos_);
      if (lt == std::string::npos) throw std::runtime_error("unterminated element " + e.name);
      pos_ = lt;
      if (s_.compare(pos_, 2, "</") == 0) {
        pos_ += 2;
        EXPECT_EQ(name(), e.name) << "mismatched closing tag";
        EXPECT_EQ(s_[pos_], '>');
        ++pos_;
        return e;
      }
      e.children.push_back(element());
    }
  }

  std::string s_;
  std::size_t pos_ = 0;
};

/// Points of an SVG path "M x,y L x,y … [Z]" as written by svg_string().
std::vector<Vec2f> path_points(const std::string& d) {
  std::vector<Vec2f> out;
  std::istringstream in(d);
  std::string token;
  while (in >> token) {
    if (token == "Z") continue;
    const std::size_t comma = token.find(',');
    out.emplace_back(std::stof(token.substr(1, comma - 1)), std::stof(token.substr(comma + 1)));
  }
  return out;
}

Stroke stroke(LineKind kind, std::vector<Vec2f> image, bool closed = false, bool visible = true) {
  Stroke s;
  s.kind = kind;
  s.closed = closed;
  s.visible = visible;
  s.image_points = std::move(image);
  for (const Vec2f& p : s.image_points) s.points.emplace_back(p.x() / 100.f, -p.y() / 100.f, 0.5f);
  s.widths.assign(s.points.size(), 2.f);
  s.half_widths.assign(2 * s.segments(), 2.f);
  return s;
}

/// 100 × 100 px: a closed square contour, a ridge whose second segment is thick, a hidden valley, a grey hatch
/// stroke and a shade region.
Drawing sample_drawing() {
  Drawing d;
  d.width = 100;
  d.height = 100;
  d.origin = Vec3d(1000.0, -20.0, 3.0);
  d.camera = {{"projection", "orthographic"}};
  d.parameters = {{"test", true}};
  d.strokes.push_back(stroke(LineKind::Contour, {{20, 20}, {80, 20}, {80, 80}, {20, 80}}, true));
  Stroke ridge = stroke(LineKind::Ridge, {{30, 40}, {50, 40}, {70, 40}});
  ridge.half_widths = {1.f, 1.f, 4.f, 4.f};
  d.strokes.push_back(ridge);
  d.strokes.push_back(stroke(LineKind::Valley, {{30, 60}, {70, 60}}, false, /*visible=*/false));
  Stroke hatch = stroke(LineKind::Hatch, {{30, 70}, {70, 70}});
  hatch.grey = 0.5f;
  d.strokes.push_back(hatch);
  d.regions.push_back(ShadeRegion{{{85, 85}, {98, 85}, {98, 98}, {85, 98}}, 0.6f});
  return d;
}

fs::path temp_path(const std::string& name) {
  return fs::path(::testing::TempDir()) / ("pcsketch_render_" + name);
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(Svg, IsWellFormedWithEveryLayerInPaintOrder) {
  const Element svg = XmlParser(svg_string(sample_drawing())).parse();
  ASSERT_EQ(svg.name, "svg");
  EXPECT_EQ(svg.attributes.at("xmlns:inkscape"), "http://www.inkscape.org/namespaces/inkscape");
  EXPECT_EQ(svg.attributes.at("viewBox"), "0 0 100 100");
  EXPECT_EQ(svg.attributes.at("width"), "100px");
  std::vector<std::string> labels;
  for (const Element* l : svg.layers()) {
    EXPECT_EQ(l->attributes.at("inkscape:groupmode"), "layer");
    labels.push_back(l->attributes.at("inkscape:label"));
  }
  EXPECT_EQ(labels, (std::vector<std::string>{"5 shading", "6 hidden", "4 hatching", "3 valleys", "2 ridges",
                                              "7 boundaries", "1 contours"}));
}

TEST(Svg, XmllintAcceptsIt) {
  if (std::system("command -v xmllint > /dev/null 2>&1") != 0) GTEST_SKIP() << "xmllint not installed";
  RenderOptions o;
  o.hidden_lines = HiddenLines::Dashed;
  const fs::path path = temp_path("lint.svg");
  write_svg(sample_drawing(), path, o);
  EXPECT_EQ(std::system(("xmllint --noout '" + path.string() + "'").c_str()), 0);
}

TEST(Svg, OneWidthIsOnePathVariableWidthIsRunsGroupedByWidth) {
  const Element svg = XmlParser(svg_string(sample_drawing())).parse();
  const Element* contours = svg.layer("1 contours");
  ASSERT_NE(contours, nullptr);
  ASSERT_EQ(contours->children.size(), 1u);
  const Element& square = contours->children[0];
  EXPECT_EQ(square.name, "path");
  EXPECT_EQ(contours->attributes.at("fill"), "none");
  EXPECT_EQ(square.attributes.at("stroke-width"), "2");
  EXPECT_EQ(square.attributes.at("d"), "M20,20 L80,20 L80,80 L20,80 Z");

  const Element* ridges = svg.layer("2 ridges");
  ASSERT_EQ(ridges->children.size(), 1u);
  const Element& ridge = ridges->children[0];
  ASSERT_EQ(ridge.name, "g");
  ASSERT_EQ(ridge.children.size(), 2u);
  // Half-segment rule: the first segment is thin, the second thick; the width changes at (50, 40).
  EXPECT_EQ(ridge.children[0].attributes.at("d"), "M30,40 L50,40");
  EXPECT_EQ(ridge.children[0].attributes.at("stroke-width"), "1");
  EXPECT_EQ(ridge.children[1].attributes.at("d"), "M50,40 L70,40");
  EXPECT_EQ(ridge.children[1].attributes.at("stroke-width"), "4");

  const Element* hatching = svg.layer("4 hatching");
  ASSERT_EQ(hatching->children.size(), 1u);
  EXPECT_EQ(hatching->children[0].attributes.at("stroke"), "#808080");
  const Element* shading = svg.layer("5 shading");
  ASSERT_EQ(shading->children.size(), 1u);
  EXPECT_EQ(shading->children[0].attributes.at("fill"), "#999999");
}

TEST(Svg, HiddenLinesOnlyOnRequestDashedInTheirOwnLayer) {
  const Element plain = XmlParser(svg_string(sample_drawing())).parse();
  EXPECT_TRUE(plain.layer("6 hidden")->children.empty());
  EXPECT_TRUE(plain.layer("3 valleys")->children.empty());
  RenderOptions o;
  o.hidden_lines = HiddenLines::Dashed;
  const Element dashed = XmlParser(svg_string(sample_drawing(), o)).parse();
  const Element* hidden = dashed.layer("6 hidden");
  ASSERT_EQ(hidden->children.size(), 1u);
  EXPECT_TRUE(hidden->children[0].attributes.count("stroke-dasharray"));
  EXPECT_EQ(hidden->children[0].attributes.at("d"), "M30,60 L70,60");
}

TEST(Svg, PlotterModeDrawsSingleWidthCentreLinesWithoutShading) {
  RenderOptions o;
  o.plotter = true;
  o.pen_width = 0.75f;
  const Element svg = XmlParser(svg_string(sample_drawing(), o)).parse();
  EXPECT_TRUE(svg.layer("5 shading")->children.empty());
  for (const Element* layer : svg.layers())
    for (const Element& child : layer->children) {
      EXPECT_EQ(child.name, "path");
      EXPECT_EQ(child.attributes.at("stroke-width"), "0.75");
      EXPECT_EQ(child.attributes.at("stroke"), "#000000");
    }
  EXPECT_EQ(svg.layer("2 ridges")->children.at(0).attributes.at("d"), "M30,40 L50,40 L70,40");
}

TEST(Svg, PageInMillimetresKeepsPixelCoordinates) {
  RenderOptions o;
  o.page_width_mm = 200.0;
  const Element svg = XmlParser(svg_string(sample_drawing(), o)).parse();
  EXPECT_EQ(svg.attributes.at("width"), "200mm");
  EXPECT_EQ(svg.attributes.at("height"), "200mm");
  EXPECT_EQ(svg.attributes.at("viewBox"), "0 0 100 100");
}

TEST(Json, PolylinesMatchWhatTheSvgDraws) {
  // A larger drawing: every kind, open and closed, visible and hidden.
  Drawing d = sample_drawing();
  for (int i = 0; i < 20; ++i) {
    const float y = 5.f + 4.5f * static_cast<float>(i);
    d.strokes.push_back(stroke(static_cast<LineKind>(i % 5), {{5.f, y}, {50.f + 0.123f * static_cast<float>(i), y + 1.f}, {95.f, y}},
                               i % 3 == 0, i % 5 != 0));
  }
  RenderOptions o;
  o.plotter = true;  // centre-lines: one path per stroke with exactly the stroke's points
  o.hidden_lines = HiddenLines::Dashed;
  const Element svg = XmlParser(svg_string(d, o)).parse();
  const nlohmann::json json = to_json(d);
  ASSERT_EQ(json["polylines"].size(), d.strokes.size());

  const std::map<std::string, std::string> layer_of = {
      {"contour", "1 contours"}, {"ridge", "2 ridges"},          {"valley", "3 valleys"},
      {"hatch", "4 hatching"},   {"boundary", "7 boundaries"}};
  std::map<std::string, std::size_t> next;  // next unread child per layer: strokes keep their order
  for (const nlohmann::json& p : json["polylines"]) {
    const std::string kind = p["kind"];
    if (!p["visible"] && kind == "hatch") continue;
    const std::string label = p["visible"] ? layer_of.at(kind) : "6 hidden";
    const Element* layer = svg.layer(label);
    ASSERT_LT(next[label], layer->children.size()) << label;
    const Element& path = layer->children[next[label]++];
    const std::vector<Vec2f> drawn = path_points(path.attributes.at("d"));
    ASSERT_EQ(drawn.size(), p["image_points"].size());
    for (std::size_t i = 0; i < drawn.size(); ++i) {
      EXPECT_NEAR(drawn[i].x(), p["image_points"][i][0].get<double>(), 0.006);
      EXPECT_NEAR(drawn[i].y(), p["image_points"][i][1].get<double>(), 0.006);
    }
    EXPECT_EQ(path.attributes.at("d").ends_with("Z"), p["closed"].get<bool>());
  }
  for (const Element* layer : svg.layers()) EXPECT_EQ(next[layer->attributes.at("inkscape:label")], layer->children.size());
}

TEST(Json, RecordsWorldPointsImageAndCamera) {
  const Drawing d = sample_drawing();
  const nlohmann::json j = to_json(d);
  EXPECT_EQ(j["image"]["width"], 100);
  EXPECT_EQ(j["camera"]["projection"], "orthographic");
  EXPECT_EQ(j["parameters"]["test"], true);
  const nlohmann::json& square = j["polylines"][0];
  EXPECT_EQ(square["kind"], "contour");
  EXPECT_TRUE(square["closed"].get<bool>());
  // world = origin + point: (1000, -20, 3) + (0.2, -0.2, 0.5)
  EXPECT_NEAR(square["points"][0][0].get<double>(), 1000.2, 1e-5);
  EXPECT_NEAR(square["points"][0][1].get<double>(), -20.2, 1e-5);
  EXPECT_NEAR(square["points"][0][2].get<double>(), 3.5, 1e-6);
  EXPECT_EQ(square["image_points"][2], nlohmann::json::array({80.0, 80.0}));
  EXPECT_EQ(square["widths"].size(), 4u);
  EXPECT_EQ(square["half_widths"].size(), 8u);
  EXPECT_FALSE(j["polylines"][2]["visible"].get<bool>());
  EXPECT_EQ(j["regions"][0]["polygon"].size(), 4u);

  const fs::path path = temp_path("out.json");
  write_drawing(d, path);
  EXPECT_EQ(nlohmann::json::parse(read_text(path)), j);
}

struct Png {
  cairo_surface_t* surface = nullptr;
  explicit Png(const fs::path& path) : surface(cairo_image_surface_create_from_png(path.c_str())) {}
  ~Png() { cairo_surface_destroy(surface); }
  bool ok() const { return cairo_surface_status(surface) == CAIRO_STATUS_SUCCESS; }
  int width() const { return cairo_image_surface_get_width(surface); }
  /// Mean of the RGB channels at (x, y), 0 … 255.
  int grey(int x, int y) const {
    cairo_surface_flush(surface);
    const unsigned char* row = cairo_image_surface_get_data(surface) + y * cairo_image_surface_get_stride(surface);
    std::uint32_t px;
    std::memcpy(&px, row + 4 * x, 4);
    return static_cast<int>(((px >> 16) & 255) + ((px >> 8) & 255) + (px & 255)) / 3;
  }
};

TEST(Png, WhiteBackgroundDarkWhereALineIs) {
  const fs::path path = temp_path("out.png");
  write_png(sample_drawing(), path);
  Png png(path);
  ASSERT_TRUE(png.ok());
  EXPECT_EQ(png.width(), 100);
  EXPECT_EQ(png.grey(2, 2), 255);          // background
  EXPECT_EQ(png.grey(50, 50), 255);        // inside the square, between lines
  EXPECT_LT(png.grey(50, 20), 60);         // on the square contour
  EXPECT_LT(png.grey(80, 50), 60);
  EXPECT_LT(png.grey(60, 41), 60);         // thick half of the ridge, 1 px off its centre
  EXPECT_EQ(png.grey(40, 42), 255);        // thin half of the ridge is 1 px wide: 2 px off is blank
  EXPECT_EQ(png.grey(50, 60), 255);        // the hidden valley is not drawn by default
  EXPECT_NEAR(png.grey(50, 70), 128, 30);  // grey hatch stroke
  EXPECT_NEAR(png.grey(92, 92), 153, 3);   // shade region fill
}

TEST(Png, HiddenLinesDashedAndPlotterWithoutShading) {
  RenderOptions o;
  o.hidden_lines = HiddenLines::Dashed;
  o.plotter = true;
  const fs::path path = temp_path("hidden.png");
  write_png(sample_drawing(), path, o);
  Png png(path);
  ASSERT_TRUE(png.ok());
  int marked = 0;
  for (int x = 30; x < 70; ++x) marked += png.grey(x, 60) < 230;
  EXPECT_GT(marked, 10);  // dashes …
  EXPECT_LT(marked, 35);  // … with gaps
  EXPECT_EQ(png.grey(92, 92), 255);  // no shading for a plotter
}

TEST(Pdf, StartsWithHeaderAndHasContent) {
  const fs::path path = temp_path("out.pdf");
  write_drawing(sample_drawing(), path);
  const std::string pdf = read_text(path);
  EXPECT_EQ(pdf.substr(0, 5), "%PDF-");
  EXPECT_GT(pdf.size(), 800u);
  EXPECT_NE(pdf.find("/MediaBox [ 0 0 75 75 ]"), std::string::npos);  // 100 px at 0.75 pt
}

TEST(Write, RejectsUnknownExtensionAndUnwritablePath) {
  EXPECT_FALSE(is_supported_output("a.txt"));
  EXPECT_TRUE(is_supported_output("A.SVG"));
  EXPECT_THROW(write_drawing(sample_drawing(), temp_path("a.txt")), Error);
  EXPECT_THROW(write_drawing(sample_drawing(), "/nonexistent-dir/x.svg"), Error);
  EXPECT_THROW(write_drawing(sample_drawing(), "/nonexistent-dir/x.png"), Error);
  EXPECT_THROW(write_drawing(sample_drawing(), "/nonexistent-dir/x.pdf"), Error);
}

TEST(Write, SeveralOutputsInParallelEachAsWrittenAlone) {
  const Drawing d = sample_drawing();
  write_drawing(d, temp_path("alone.svg"));
  write_drawing(d, temp_path("alone.json"));
  write_drawings(d, {temp_path("both.svg"), temp_path("both.png"), temp_path("both.json")});
  EXPECT_EQ(read_text(temp_path("both.svg")), read_text(temp_path("alone.svg")));
  EXPECT_EQ(read_text(temp_path("both.json")), read_text(temp_path("alone.json")));
  EXPECT_TRUE(Png(temp_path("both.png")).ok());
  // One failing output is reported; the others are still written.
  fs::remove(temp_path("both.svg"));
  EXPECT_THROW(write_drawings(d, {temp_path("both.svg"), "/nonexistent-dir/x.png"}), Error);
  EXPECT_EQ(read_text(temp_path("both.svg")), read_text(temp_path("alone.svg")));
}

TEST(Render, EmptyDrawingGivesEmptyLayersAndABlankImage) {
  Drawing d;
  d.width = 64;
  d.height = 32;
  const Element svg = XmlParser(svg_string(d)).parse();
  EXPECT_EQ(svg.layers().size(), 7u);
  for (const Element* l : svg.layers()) EXPECT_TRUE(l->children.empty());
  const fs::path path = temp_path("empty.png");
  write_png(d, path);
  Png png(path);
  ASSERT_TRUE(png.ok());
  EXPECT_EQ(png.grey(10, 10), 255);
  Drawing zero;
  EXPECT_THROW(svg_string(zero), Error);
}

}  // namespace
}  // namespace pcsketch::render
