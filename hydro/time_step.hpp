#pragma once
// Time-step control. Pressure is explicit, so the step resolves sound crossing of the
// narrowest cell (the closure's adiabatic sound speed); the Lagrangian mesh must not compress
// or stretch any cell by more than a set fraction per step, which is what lets the run follow
// a density peak towards the flow-by-inertia singularity (n ~ 1/(tau - t)) in a bounded number
// of steps per decade of density.
// The viscosity and the conduction are implicit and set no limit; nor does the inelastic heat
// flux -mu dn/dx, explicit but bounded by the implicit conduction (hydro/lagrangian_operator.hpp).
// What the heat fluxes do to a cell's temperature counts in the heating limit
// (max_temperature_change).
#include <string>
#include <vector>

#include "hydro/closure.hpp"
#include "hydro/lagrangian_state.hpp"

namespace granvv::hydro {

// All > 0 (run_hydro checks); their defaults are those of the case schema (hydro.cfl, ...).
struct TimeStepControl {
  double cfl = 0.0;
  double max_compression = 0.0;         // largest |dv| dt / dx per cell and step
  double max_temperature_change = 0.0;  // largest |dT/T| per step from work and conduction
  double dt_max = 0.0;
};

struct TimeStepLimit {
  double dt = 0.0;
  std::string
      limited_by;  // "sound", "compression", "dt_max" (the driver adds "heating", "output time")
};

class TimeStepLimiter {
 public:
  // The closure must outlive the limiter.
  TimeStepLimiter(const Closure& closure, const TimeStepControl& control);
  // cells: the widths and densities of s (measure_cells).
  TimeStepLimit limit(const LagrangianState& s, const CellGeometry& cells);

 private:
  const Closure& closure_;
  TimeStepControl control_;
  std::vector<double> sound_speed_;
};

}  // namespace granvv::hydro
