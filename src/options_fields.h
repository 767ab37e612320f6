#pragma once
// Building the option table (options_table.h): each entry names a DrawOptions member once, and its JSON reader and
// writer are made from the member's type.

#include <charconv>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "pcsketch/core/error.h"
#include "pcsketch/core/point_cloud.h"
#include "pcsketch/options_table.h"
#include "pcsketch/pipeline.h"

// The JSON key is the member path spelled in the accessor, so the two cannot drift apart: a macro is the one way to
// have both from one spelling.
// clang-format off
#define PCSKETCH_OPTION(path) #path, [](DrawOptions& o) -> auto& { return o.path; }
// clang-format on

namespace pcsketch::options::detail {

template <class T>
struct Optional : std::false_type {
  using type = T;
};
template <class T>
struct Optional<std::optional<T>> : std::true_type {
  using type = T;
};

template <class T>
constexpr bool is_vec3 = std::is_same_v<T, Vec3d> || std::is_same_v<T, Vec3f>;

/// The table's Type of a member of type T (the optional stripped).
template <class T>
constexpr Type type_of() {
  if constexpr (std::is_same_v<T, bool>)
    return Type::Bool;
  else if constexpr (std::is_integral_v<T>)
    return Type::Integer;
  else if constexpr (std::is_floating_point_v<T>)
    return Type::Number;
  else if constexpr (std::is_same_v<T, std::vector<float>>)
    return Type::List;
  else if constexpr (is_vec3<T>)
    return Type::Vector;
  else
    return Type::Custom;
}

[[noreturn]] inline void wrong(const std::string& key, const char* expected, const nlohmann::json& j) {
  throw Error(key + ": expected " + expected + ", got " + quote(j.dump()));
}

inline double to_number(const std::string& key, const nlohmann::json& j) {
  if (!j.is_number()) wrong(key, "a number", j);
  return j.get<double>();
}

/// A JSON value into a plain (not optional) member of type T.
template <class T>
T read_value(const std::string& key, const nlohmann::json& j) {
  if constexpr (std::is_same_v<T, bool>) {
    if (!j.is_boolean()) wrong(key, "true or false", j);
    return j.get<bool>();
  } else if constexpr (std::is_integral_v<T>) {
    if (j.is_number_unsigned() && std::in_range<T>(j.get<std::uint64_t>()))
      return static_cast<T>(j.get<std::uint64_t>());
    if (j.is_number_integer() && std::in_range<T>(j.get<std::int64_t>())) return static_cast<T>(j.get<std::int64_t>());
    wrong(key, "a whole number in the member's type", j);
  } else if constexpr (std::is_floating_point_v<T>) {
    return static_cast<T>(to_number(key, j));
  } else if constexpr (std::is_same_v<T, std::vector<float>>) {
    if (!j.is_array()) wrong(key, "a list of numbers", j);
    T out;
    for (const nlohmann::json& item : j) out.push_back(static_cast<float>(to_number(key, item)));
    return out;
  } else {
    static_assert(is_vec3<T>);
    if (!j.is_array() || j.size() != 3) wrong(key, "three numbers [x, y, z]", j);
    return T(static_cast<typename T::Scalar>(to_number(key, j[0])),
             static_cast<typename T::Scalar>(to_number(key, j[1])),
             static_cast<typename T::Scalar>(to_number(key, j[2])));
  }
}

/// A float as the double of its shortest decimal form: 0.2f is written 0.2 (not 0.200000003), and reads back as 0.2f.
inline double float_value(float v) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, v).ptr;
  return std::strtod(std::string(text, end).c_str(), nullptr);
}

template <class T>
nlohmann::json write_value(const T& v) {
  if constexpr (std::is_same_v<T, float>) {
    return float_value(v);
  } else if constexpr (std::is_same_v<T, std::vector<float>>) {
    nlohmann::json out = nlohmann::json::array();
    for (const float x : v) out.push_back(float_value(x));
    return out;
  } else if constexpr (std::is_same_v<T, Vec3f>) {
    return nlohmann::json::array({float_value(v.x()), float_value(v.y()), float_value(v.z())});
  } else if constexpr (is_vec3<T>) {
    return nlohmann::json::array({v.x(), v.y(), v.z()});
  } else {
    return nlohmann::json(v);
  }
}

/// Adds entries to the table, each in the current group.
class Builder {
 public:
  explicit Builder(std::vector<Option>& out) : out_(out) {}
  void group(std::string name) { group_ = std::move(name); }

  /// A bool, number, list or vector member (or an optional one), reached by `access`.
  template <class Access>
  void add(const std::string& key, Access access, Option meta) {
    using Member = std::remove_reference_t<decltype(access(std::declval<DrawOptions&>()))>;
    using T = typename Optional<Member>::type;
    meta.type = type_of<T>();
    meta.nullable = Optional<Member>::value;
    meta.get = [access](const DrawOptions& o) {
      // The accessor only reads here; one accessor serves get and set.
      const Member& m = access(const_cast<DrawOptions&>(o));
      if constexpr (Optional<Member>::value)
        return m ? write_value(*m) : nlohmann::json();
      else
        return write_value(m);
    };
    meta.set = [access, k = key](DrawOptions& o, const nlohmann::json& j) {
      if constexpr (Optional<Member>::value) {
        if (j.is_null()) return void(access(o).reset());
      }
      access(o) = read_value<T>(k, j);
    };
    push(key, std::move(meta));
  }

  /// An enum member (or an optional one), spelled as one of `names` (in enum order: name i is value i).
  template <class Access>
  void choice(const std::string& key, Access access, std::vector<std::string> names, Option meta) {
    using Member = std::remove_reference_t<decltype(access(std::declval<DrawOptions&>()))>;
    using E = typename Optional<Member>::type;
    meta.type = Type::Choice;
    meta.nullable = Optional<Member>::value;
    meta.choices = names;
    meta.get = [access, names](const DrawOptions& o) {
      const Member& m = access(const_cast<DrawOptions&>(o));
      if constexpr (Optional<Member>::value) {
        if (!m) return nlohmann::json();
        return nlohmann::json(names.at(static_cast<std::size_t>(*m)));
      } else {
        return nlohmann::json(names.at(static_cast<std::size_t>(m)));
      }
    };
    meta.set = [access, names, k = key](DrawOptions& o, const nlohmann::json& j) {
      if constexpr (Optional<Member>::value) {
        if (j.is_null()) return void(access(o).reset());
      }
      for (std::size_t i = 0; i < names.size() && j.is_string(); ++i)
        if (names[i] == j.get<std::string>()) return void(access(o) = static_cast<E>(i));
      std::string listed;
      for (const std::string& n : names) listed += (listed.empty() ? "" : ", ") + n;
      wrong(k, ("one of " + listed).c_str(), j);
    };
    push(key, std::move(meta));
  }

  /// A member with its own JSON form (get/set given in `meta`).
  void custom(const std::string& key, Option meta) {
    meta.type = Type::Custom;
    push(key, std::move(meta));
  }

 private:
  void push(const std::string& key, Option meta) {
    meta.key = key;
    meta.group = group_;
    out_.push_back(std::move(meta));
  }
  std::vector<Option>& out_;
  std::string group_;
};

/// Ranges: [lo, hi], (lo, hi], (lo, hi), [0, inf), (0, inf).
constexpr Range closed(double lo, double hi) { return {lo, hi}; }
constexpr Range above(double lo, double hi = std::numeric_limits<double>::max()) { return {lo, hi, true}; }
constexpr Range open(double lo, double hi) { return {lo, hi, true, true}; }
constexpr Range non_negative(double hi = std::numeric_limits<double>::max()) { return {0, hi}; }
constexpr Range positive(double hi = std::numeric_limits<double>::max()) { return {0, hi, true}; }

/// The entries of the view-independent stages (surface, features, boundary, scene) and of the camera and view.
void add_analysis_options(Builder& b);
/// The entries of the drawing stages (finish, thickness, fusion, shadow, render, plotter, lines, limits).
void add_drawing_options(Builder& b);
/// The entries of the camera, contours and visibility.
void add_view_options(Builder& b);

}  // namespace pcsketch::options::detail
