#pragma once
// A hydro RunControl for tests that call run_hydro directly. The values are those a case gets
// by default, written out so that the tests do not depend on the case schema's defaults.
#include "hydro/driver.hpp"

namespace granvv::testing {

inline hydro::RunControl run_control(double t_end, double cfl = 2.0) {
  hydro::RunControl control;
  control.t_end = t_end;
  control.time_step.cfl = cfl;
  control.time_step.max_compression = 0.1;
  control.time_step.max_temperature_change = 0.2;
  control.time_step.dt_max = 0.05;
  control.stop_density = 1e6;
  control.min_cell_width = 1e-14;
  control.series_every = 1;
  return control;
}

}  // namespace granvv::testing
