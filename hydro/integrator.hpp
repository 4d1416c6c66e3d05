#pragma once
// Time integrator: Strang splitting of the exact cooling sink (paper Eq. 2, last term)
// around a predictor-corrector pass of the Lagrangian operator, second order in time:
//   C(dt/2) . H(dt) . C(dt/2),  H = corrector with coefficients at the mean of the
//   start state and the predictor's end state.
#include <vector>

#include "hydro/closure.hpp"
#include "hydro/lagrangian_operator.hpp"
#include "hydro/lagrangian_state.hpp"

namespace granvv::hydro {

struct StepOutcome {
  bool accepted = false;
  double energy_cooled = 0.0;     // energy removed by inelastic cooling in this step
  double relative_heating = 0.0;  // largest |dT/T| from work and conduction (not cooling)
};

class HydroIntegrator {
 public:
  // The closure must outlive the integrator.
  HydroIntegrator(const Closure& closure, int cells);
  // Advance s by dt; cells holds the widths and densities of s (measure_cells) and is
  // updated with it. On rejection (T <= 0, tangled mesh) s and cells are left unchanged.
  StepOutcome step(LagrangianState& s, double dt, CellGeometry& cells);
  // The same, measuring the cells of s first.
  StepOutcome step(LagrangianState& s, double dt);

 private:
  const Closure& closure_;
  LagrangianOperator op_;
  PassFields predicted_, corrected_;
  FrozenCoefficients coefficients_;
  CellGeometry cells_, end_cells_;
  std::vector<double> T_start_, T_end_, widths_mid_, T_mid_;
  std::vector<double> relative_change_;  // |T'_i / T_i - 1| of the corrector, per cell
};

}  // namespace granvv::hydro
