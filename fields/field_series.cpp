#include "fields/field_series.hpp"

#include <stdexcept>

namespace granvv::fields {

std::string to_string(Geometry g) {
  return g == Geometry::cells ? "cells" : "bins";
}

Geometry geometry_from_string(const std::string& name) {
  if (name == "cells") return Geometry::cells;
  if (name == "bins") return Geometry::bins;
  throw std::invalid_argument("FieldSeries geometry \"" + name +
                              "\": expected \"cells\" or \"bins\"");
}

FieldSeries FieldSeries::on_bins(double x_lo, double length, int bins) {
  if (bins < 1) throw std::invalid_argument("FieldSeries::on_bins: bins must be >= 1");
  FieldSeries s;
  s.geometry = Geometry::bins;
  for (int b = 0; b <= bins; ++b) s.bin_edges.push_back(x_lo + length * b / bins);
  return s;
}

const std::vector<FieldColumn>& field_columns() {
  static const std::vector<FieldColumn> columns = {
      {"x", &FieldSnapshot::x, nullptr},
      {"n", &FieldSnapshot::n, &FieldSnapshot::n_stderr},
      {"v_x", &FieldSnapshot::v_x, &FieldSnapshot::v_x_stderr},
      {"v_y", &FieldSnapshot::v_y, &FieldSnapshot::v_y_stderr},
      {"T", &FieldSnapshot::T, &FieldSnapshot::T_stderr},
      {"count", &FieldSnapshot::count, &FieldSnapshot::count_stderr},
      {"P_xx", &FieldSnapshot::P_xx, &FieldSnapshot::P_xx_stderr},
      {"P_yy", &FieldSnapshot::P_yy, &FieldSnapshot::P_yy_stderr},
  };
  return columns;
}

const FieldColumn& field_column(const std::string& name) {
  for (const FieldColumn& c : field_columns()) {
    if (name == c.name) return c;
  }
  throw std::invalid_argument("FieldSeries has no column \"" + name + "\"");
}

}  // namespace granvv::fields
