#include "fields/field_series.hpp"

#include <algorithm>
#include <cmath>
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

bool same_time(double t, double reference) {
  return std::abs(t - reference) <= kSameTimeTolerance * std::max(1.0, std::abs(reference));
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
      {"n", &FieldSnapshot::n, &FieldSnapshot::n_stderr, true},
      {"v_x", &FieldSnapshot::v_x, &FieldSnapshot::v_x_stderr, true},
      {"v_y", &FieldSnapshot::v_y, &FieldSnapshot::v_y_stderr, true},
      {"T", &FieldSnapshot::T, &FieldSnapshot::T_stderr, true},
      {"count", &FieldSnapshot::count, &FieldSnapshot::count_stderr},
      {"P_xx", &FieldSnapshot::P_xx, &FieldSnapshot::P_xx_stderr},
      {"P_yy", &FieldSnapshot::P_yy, &FieldSnapshot::P_yy_stderr},
      {"kinetic_energy", &FieldSnapshot::kinetic_energy, &FieldSnapshot::kinetic_energy_stderr},
      {"energy_flux_x", &FieldSnapshot::energy_flux_x, &FieldSnapshot::energy_flux_x_stderr},
      {"contact_energy_flux_x", &FieldSnapshot::contact_energy_flux_x,
       &FieldSnapshot::contact_energy_flux_x_stderr},
  };
  return columns;
}

const std::vector<std::string>& hydrodynamic_fields() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const FieldColumn& c : field_columns()) {
      if (c.hydrodynamic) out.emplace_back(c.name);
    }
    return out;
  }();
  return names;
}

const FieldColumn& field_column(const std::string& name) {
  for (const FieldColumn& c : field_columns()) {
    if (name == c.name) return c;
  }
  throw std::invalid_argument("FieldSeries has no column \"" + name + "\"");
}

}  // namespace granvv::fields
