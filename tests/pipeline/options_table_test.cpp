// The option table (options_table.h): every field of DrawOptions has an entry, and the JSON record replays exactly.

#include "pcsketch/options_table.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <utility>

#include "pcsketch/core/error.h"
#include "pcsketch/pipeline.h"
#include "pcsketch/validate.h"

namespace pcsketch {
namespace field_probe {

/// Converts to any type (outside the anonymous namespace: its conversion is declared only, never defined or called):
/// `T{Any{}, Any{}, …}` compiles for as many initialisers as the aggregate T has members.
struct Any {
  template <class T>
  operator T&() const;  // never defined: only used in unevaluated requires-expressions
};

template <class T, class... A>
constexpr std::size_t field_count() {
  if constexpr (requires { T{std::declval<A>()..., Any{}}; })
    return field_count<T, A..., Any>();
  else
    return sizeof...(A);
}

}  // namespace field_probe

namespace {

using field_probe::field_count;

/// The distinct member names directly under `prefix` among the table's keys (leaves and nested structs).
std::size_t table_children(const std::string& prefix) {
  std::set<std::string> names;
  for (const options::Option& o : options::table()) {
    if (!o.key.starts_with(prefix + ".")) continue;
    const std::string rest = o.key.substr(prefix.size() + 1);
    names.insert(rest.substr(0, rest.find('.')));
  }
  return names.size();
}

// A field added to an options struct without a table entry fails here: each struct's member count (aggregate
// initialisation probes it) must equal the members the table names under its key, plus its progress callback
// where it has one (- 1).
TEST(OptionsTable, EveryMemberOfEveryOptionsStructHasAnEntry) {
  const std::pair<std::string, std::size_t> counted[] = {
      {"surface", field_count<differential::SurfaceOptions>() - 1},  // - progress
      {"surface.neighbourhood", field_count<neighbourhood::NeighbourhoodOptions>() - 1},
      {"surface.outliers", field_count<clean::OutlierOptions>() - 1},
      {"surface.denoise", field_count<differential::DenoiseOptions>() - 1},
      {"surface.normals", field_count<differential::NormalOptions>() - 1},
      {"surface.orientation", field_count<differential::OrientOptions>() - 1},
      {"surface.curvature", field_count<differential::CurvatureOptions>() - 1},
      {"features", field_count<features::RidgeValleyOptions>() - 1},
      {"features.detection", field_count<features::DetectionOptions>()},
      {"features.tracing", field_count<features::TraceOptions>()},
      {"features.joining", field_count<features::JoinOptions>()},
      {"boundary", field_count<features::BoundaryOptions>() - 1},
      {"boundary.tracing", field_count<features::TraceOptions>()},
      {"boundary.joining", field_count<features::JoinOptions>()},
      {"scene", field_count<view::SurfaceSceneOptions>() - 1},
      {"view", field_count<view::ViewOptions>() - 1},
      {"view.contours", field_count<view::ContourOptions>() - 1},
      {"view.visibility", field_count<view::VisibilityOptions>() - 1},
      {"finish", field_count<stylize::FinishOptions>()},
      {"thickness", field_count<stylize::ThicknessOptions>()},
      {"fusion", field_count<stylize::FusionOptions>()},
      {"shadow", field_count<stylize::ShadowOptions>() - 1},
      {"render", field_count<render::RenderOptions>()},
      {"plotter", field_count<plotter::PlotterOptions>()},
      {"page", field_count<page::PageOptions>()},
      {"lines", field_count<LineSelection>()},
  };
  for (const auto& [prefix, members] : counted) EXPECT_EQ(table_children(prefix), members) << prefix;
  // Eigen's constructors cannot be probed: CameraOptions and LightOptions are counted by hand.
  EXPECT_EQ(table_children("camera"), 12u);
  EXPECT_EQ(table_children("shadow.light"), 4u);
  std::set<std::string> top;
  for (const options::Option& o : options::table()) top.insert(o.key.substr(0, o.key.find('.')));
  EXPECT_EQ(top.size(), field_count<DrawOptions>() - 1);  // - progress
}

/// A value of `option` in its range that differs from `current` (every entry can be moved off its default).
nlohmann::json other_value(const options::Option& option, const nlohmann::json& current) {
  using options::Type;
  const auto valid = [&](const nlohmann::json& v) {
    try {
      options::check(option, v);
      return v != current;
    } catch (const OptionError&) {
      return false;
    }
  };
  if (option.type == Type::Bool) return !current.get<bool>();
  if (option.type == Type::Choice) return option.choices.at(current == option.choices.front() ? 1 : 0);
  if (option.type == Type::Vector) return current.is_null() ? nlohmann::json{0.5, -1, 2} : nlohmann::json{3, 0.25, -2};
  if (option.type == Type::Custom) return nlohmann::json{{"near", 1.5}, {"far", 4.0}};
  const double base = current.is_number() ? current.get<double>() : current.is_array() ? current[0].get<double>() : 1;
  const options::Range& r = option.range;
  for (const double candidate : {base * 0.5, base + 1, base - 1, 0.5, 2.0, r.hi, r.lo, (r.lo + r.hi) / 2}) {
    const nlohmann::json v = option.type == Type::Integer ? nlohmann::json(static_cast<std::int64_t>(candidate))
                             : option.type == Type::List  ? nlohmann::json{candidate, candidate / 2}
                                                          : nlohmann::json(candidate);
    if (valid(v)) return v;
  }
  ADD_FAILURE() << option.key << ": no other value in range";
  return current;
}

TEST(OptionsTable, EveryFieldRoundTripsThroughJson) {
  const DrawOptions defaults;
  DrawOptions changed;
  for (const options::Option& o : options::table()) o.set(changed, other_value(o, o.get(defaults)));
  const nlohmann::json recorded = options::to_json(changed);
  DrawOptions replayed;
  options::from_json(nlohmann::json::parse(recorded.dump()), replayed);
  EXPECT_EQ(options::to_json(replayed), recorded);
  for (const options::Option& o : options::table()) {
    EXPECT_NE(o.get(changed), o.get(defaults)) << o.key << " kept its default";
    EXPECT_EQ(o.get(replayed), o.get(changed)) << o.key;
  }
  // Spot checks through the members themselves, not the table's accessors.
  EXPECT_EQ(replayed.surface.curvature.max_k, changed.surface.curvature.max_k);
  EXPECT_EQ(replayed.camera.up, changed.camera.up);
  EXPECT_EQ(replayed.shadow.k_set, changed.shadow.k_set);
  ASSERT_TRUE(replayed.thickness.depth_range.has_value());
  EXPECT_EQ(replayed.thickness.depth_range->far, 4.0f);
}

std::size_t leaves(const nlohmann::json& j) {
  if (!j.is_object() || j.contains("near")) return 1;  // thickness.depth_range is one option
  std::size_t n = 0;
  for (const auto& item : j) n += leaves(item);
  return n;
}

TEST(OptionsTable, TheRecordHoldsOneLeafPerEntryAndTheDriftedOptions) {
  const nlohmann::json j = DrawOptions{}.to_json();
  EXPECT_EQ(leaves(j), options::table().size());
  for (const char* key : {"/surface/orientation/k", "/surface/curvature/adapt_to_noise",
                          "/surface/curvature/noise_tolerance", "/surface/curvature/max_k"})
    EXPECT_TRUE(j.contains(nlohmann::json::json_pointer(key))) << key;
  EXPECT_EQ(j["thickness"]["rho_min"], 0.8);  // floats written in their shortest form
}

TEST(OptionsTable, BadJsonNamesTheKey) {
  DrawOptions o;
  const auto message = [&](const char* text) {
    try {
      options::from_json(nlohmann::json::parse(text), o);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(R"({"thickness": {"rho_mix": 1}})").find("thickness.rho_mix: no such option"), std::string::npos);
  EXPECT_NE(message(R"({"thickness": {"rho_min": "thin"}})").find("thickness.rho_min: expected a number"),
            std::string::npos);
  EXPECT_NE(message(R"({"shadow": {"mode": "sometimes"}})").find("shadow.mode: expected one of none, paper"),
            std::string::npos);
  EXPECT_NE(message(R"({"surface": {"neighbourhood": {"k": -3}}})").find("surface.neighbourhood.k"), std::string::npos);
  EXPECT_EQ(message(R"({"resolved": {"points": 3}, "lines": {"ridges": false}})"), "no error");
  EXPECT_FALSE(o.lines.ridges);
}

TEST(OptionsTable, ValidateUsesTheTableRanges) {
  DrawOptions o;
  o.features.detection.ridge_threshold_alpha = 0;
  try {
    validate(o);
    ADD_FAILURE() << "alpha 0 accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(std::string(e.what()), "--alpha: must be in (0, 1), got 0");
  }
  o = {};
  o.surface.curvature.noise_tolerance = -1;  // no flag: named by its key
  EXPECT_THROW(validate(o), OptionError);
}

}  // namespace
}  // namespace pcsketch
