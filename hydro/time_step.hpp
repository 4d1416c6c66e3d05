#pragma once
// Time-step control. Pressure is explicit, so the step resolves sound crossing of the
// narrowest cell (c^2 = 2T in 2D); the Lagrangian mesh must not compress or stretch any
// cell by more than a set fraction per step, which is what lets the run follow a density
// peak towards the flow-by-inertia singularity (n ~ 1/(tau - t)) in a bounded number of
// steps per decade of density.
#include <string>

#include "hydro/lagrangian_state.hpp"

namespace granvv::hydro {

struct TimeStepControl {
  double cfl = 2.0;
  double max_compression = 0.1;         // largest |dv| dt / dx per cell and step
  double max_temperature_change = 0.2;  // largest |dT/T| per step from work and conduction
  double dt_max = 0.05;
};

struct TimeStepLimit {
  double dt = 0.0;
  std::string
      limited_by;  // "sound", "compression", "dt_max" (the driver adds "heating", "output time")
};

TimeStepLimit time_step_limit(const LagrangianState& s, const TimeStepControl& control);

}  // namespace granvv::hydro
