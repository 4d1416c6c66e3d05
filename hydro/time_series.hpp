#pragma once
// The hydro's time series: one row per recorded step, one column per whole-mesh quantity.
// The columns are declared once, in time_series_columns() (name, meaning, storage, value):
// the driver records a row through it and the results writer stores each column as
// /hydro/timeseries/<name>, in this order (docs/outputs.md). A column whose value is not
// defined for the run (NaN: the area fraction without phi0) is not recorded and not written.
#include <array>
#include <vector>

#include "hydro/diagnostics.hpp"
#include "hydro/validity_monitors.hpp"

namespace granvv::hydro {

// What one row is made of.
struct TimeSeriesSample {
  double t = 0.0;
  double dt = 0.0;  // the step that ended at t (0 for the initial and a repeated final row)
  Diagnostics diagnostics;
  double energy_cooled = 0.0;  // energy removed by cooling since t = 0
  double haff_T = 0.0;         // Haff's law T_H(t) of the closure
  ValidityMeasures validity;   // the validity monitors (hydro/validity_monitors.hpp)
  bool area_fraction_known = false;
};

struct TimeSeries {
  std::vector<double> t, dt, n_max, x_peak, dvdx_peak, T_min, T_mean, energy, energy_thermal,
      energy_kinetic, energy_kinetic_y, energy_cooled, momentum, haff_T, phi_max, knudsen_n_max,
      knudsen_v_max, knudsen_T_max, collision_flow_max;
  void record(const TimeSeriesSample& sample);
};

struct TimeSeriesColumn {
  const char* name;
  const char* meaning;
  std::vector<double> TimeSeries::*values;
  double (*value)(const TimeSeriesSample&);
};

constexpr int kTimeSeriesColumns = 14 + kMonitors;
const std::array<TimeSeriesColumn, kTimeSeriesColumns>& time_series_columns();

}  // namespace granvv::hydro
