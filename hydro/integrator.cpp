#include "hydro/integrator.hpp"

#include <algorithm>

namespace granvv::hydro {

double HydroIntegrator::cool_cells(LagrangianState& s, double dt) {
  const int cells = s.cells();
  density_.resize(cells);
  for (int i = 0; i < cells; ++i) density_[i] = s.cell_mass[i] / cell_width(s, i);
  closure_.cool(density_, s.cell_T, dt, cooled_T_);
  double removed = 0.0;
  for (int i = 0; i < cells; ++i) {
    removed += s.cell_mass[i] * (s.cell_T[i] - cooled_T_[i]);
    s.cell_T[i] = cooled_T_[i];
  }
  return removed;
}

HydroIntegrator::HydroIntegrator(const Closure& closure, int cells)
    : closure_(closure), op_(closure, cells) {}

StepOutcome HydroIntegrator::step(LagrangianState& s, double dt) {
  StepOutcome out;
  start_ = s;
  out.energy_cooled = cool_cells(start_, 0.5 * dt);

  // Predictor: coefficients at the start of the step.
  cell_widths(start_, widths_);
  op_.freeze(start_.cell_mass, widths_, start_.cell_T, dt, {}, coefficients_);
  if (!op_.advance(start_, coefficients_, dt, predicted_)) return out;

  // Corrector: coefficients at the mean of start and predicted states, the pressure
  // linearised about the predictor's compression.
  cell_widths(predicted_, widths_mid_);
  T_mid_.resize(widths_.size());
  for (size_t i = 0; i < widths_.size(); ++i) {
    widths_mid_[i] = 0.5 * (widths_[i] + widths_mid_[i]);
    T_mid_[i] = 0.5 * (start_.cell_T[i] + predicted_.cell_T[i]);
  }
  op_.freeze(start_.cell_mass, widths_mid_, T_mid_, dt, op_.last_velocity_differences(),
             coefficients_);
  if (!op_.advance(start_, coefficients_, dt, corrected_)) return out;
  out.relative_heating = op_.last_relative_temperature_change();

  out.energy_cooled += cool_cells(corrected_, 0.5 * dt);
  std::swap(s, corrected_);
  out.accepted = true;
  return out;
}

}  // namespace granvv::hydro
