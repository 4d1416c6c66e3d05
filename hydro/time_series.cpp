#include "hydro/time_series.hpp"

#include <cmath>
#include <limits>

namespace granvv::hydro {

// Every member of TimeSeries is a column of the table.
static_assert(sizeof(TimeSeries) == kTimeSeriesColumns * sizeof(std::vector<double>));

namespace {

double monitor(const TimeSeriesSample& s, Monitor m) {
  return s.validity[static_cast<int>(m)].value;
}
TimeSeriesColumn monitor_column(Monitor m, std::vector<double> TimeSeries::*values,
                                double (*value)(const TimeSeriesSample&)) {
  const MonitorDefinition& d = monitor_definitions()[static_cast<int>(m)];
  return {d.column, d.meaning, values, value};
}

}  // namespace

const std::array<TimeSeriesColumn, kTimeSeriesColumns>& time_series_columns() {
  using S = TimeSeriesSample;
  static const std::array<TimeSeriesColumn, kTimeSeriesColumns> columns{{
      {"t", "time", &TimeSeries::t, [](const S& s) { return s.t; }},
      {"dt", "step that ended at t", &TimeSeries::dt, [](const S& s) { return s.dt; }},
      {"n_max", "largest cell density", &TimeSeries::n_max,
       [](const S& s) { return s.diagnostics.n_max; }},
      {"x_peak", "centre of the densest cell, in [-1/2, 1/2)", &TimeSeries::x_peak,
       [](const S& s) { return s.diagnostics.x_peak; }},
      {"dvdx_peak", "velocity gradient across the densest cell", &TimeSeries::dvdx_peak,
       [](const S& s) { return s.diagnostics.dvdx_peak; }},
      {"T_min", "lowest cell temperature", &TimeSeries::T_min,
       [](const S& s) { return s.diagnostics.T_min; }},
      {"T_mean", "mass-weighted mean temperature", &TimeSeries::T_mean,
       [](const S& s) { return s.diagnostics.T_mean; }},
      {"energy", "total energy (thermal + kinetic)", &TimeSeries::energy,
       [](const S& s) { return s.diagnostics.energy(); }},
      {"energy_thermal", "thermal energy sum m T", &TimeSeries::energy_thermal,
       [](const S& s) { return s.diagnostics.energy_thermal; }},
      {"energy_kinetic", "kinetic energy sum mu v_x^2/2", &TimeSeries::energy_kinetic,
       [](const S& s) { return s.diagnostics.energy_kinetic; }},
      {"energy_kinetic_y", "transverse kinetic energy sum mu v_y^2/2",
       &TimeSeries::energy_kinetic_y, [](const S& s) { return s.diagnostics.energy_kinetic_y; }},
      {"energy_cooled", "energy removed by cooling since t = 0", &TimeSeries::energy_cooled,
       [](const S& s) { return s.energy_cooled; }},
      {"momentum", "total momentum sum mu v_x", &TimeSeries::momentum,
       [](const S& s) { return s.diagnostics.momentum; }},
      {"haff_T", "Haff's law T_H(t) of the closure", &TimeSeries::haff_T,
       [](const S& s) { return s.haff_T; }},
      // The validity monitors (hydro/validity_monitors.hpp), named there.
      monitor_column(Monitor::area_fraction, &TimeSeries::phi_max,
                     [](const S& s) {
                       return s.area_fraction_known ? monitor(s, Monitor::area_fraction)
                                                    : std::numeric_limits<double>::quiet_NaN();
                     }),
      monitor_column(Monitor::knudsen_density, &TimeSeries::knudsen_n_max,
                     [](const S& s) { return monitor(s, Monitor::knudsen_density); }),
      monitor_column(Monitor::knudsen_velocity, &TimeSeries::knudsen_v_max,
                     [](const S& s) { return monitor(s, Monitor::knudsen_velocity); }),
      monitor_column(Monitor::knudsen_temperature, &TimeSeries::knudsen_T_max,
                     [](const S& s) { return monitor(s, Monitor::knudsen_temperature); }),
      monitor_column(Monitor::collision_flow, &TimeSeries::collision_flow_max,
                     [](const S& s) { return monitor(s, Monitor::collision_flow); }),
  }};
  return columns;
}

void TimeSeries::record(const TimeSeriesSample& sample) {
  for (const auto& column : time_series_columns()) {
    const double value = column.value(sample);
    if (!std::isnan(value)) (this->*column.values).push_back(value);
  }
}

}  // namespace granvv::hydro
