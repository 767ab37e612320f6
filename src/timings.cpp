#include <array>
#include <string_view>
#include <utility>

#include "pcsketch/pipeline.h"

namespace pcsketch {

namespace {

/// Every stage of Timings in pipeline order with its row name (the paper's Table 2 name where it has one): the one
/// list that total(), all_rows() and += walk.
constexpr std::array<std::pair<std::string_view, double Timings::*>, 17> kTimingRows{{
    {"read", &Timings::read},
    {"reorder", &Timings::reorder},
    {"neighbourhoods", &Timings::neighbourhoods},
    {"scan lines", &Timings::scan_lines},
    {"outliers", &Timings::outliers},
    {"denoise", &Timings::denoise},
    {"normals", &Timings::normals},
    {"curvature", &Timings::curvature},
    {"ridge-valley points extraction", &Timings::ridge_valley_points},
    {"ridge-valley points connection", &Timings::ridge_valley_connection},
    {"boundary", &Timings::boundary},
    {"scene", &Timings::scene},
    {"contour points extraction", &Timings::contour_points},
    {"contour line connection", &Timings::contour_connection},
    {"visibility", &Timings::visibility},
    {"shadows", &Timings::shadows},
    {"drawing", &Timings::drawing},
}};

}  // namespace

double Timings::total() const {
  double sum = 0;
  for (const auto& [name, field] : kTimingRows) sum += this->*field;
  return sum;
}

std::vector<std::pair<std::string_view, double>> Timings::table_rows() const {
  return {{"ridge-valley points extraction", ridge_valley_points},
          {"ridge-valley points connection", ridge_valley_connection},
          {"contour points extraction", contour_points},
          {"contour line connection", contour_connection},
          {"drawing", drawing},
          {"total", total()}};
}

std::vector<std::pair<std::string_view, double>> Timings::all_rows() const {
  std::vector<std::pair<std::string_view, double>> rows;
  for (const auto& [name, field] : kTimingRows) rows.emplace_back(name, this->*field);
  rows.emplace_back("total", total());
  return rows;
}

Timings& Timings::operator+=(const Timings& o) {
  for (const auto& [name, field] : kTimingRows) this->*field += o.*field;
  return *this;
}

}  // namespace pcsketch
