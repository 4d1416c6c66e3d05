#include "hydro/integrator.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "hydro/largest_value.hpp"
#include "hydro/wide_loops.hpp"

namespace granvv::hydro {

namespace {

// Energy sum m_i (T_i - T'_i) removed by cooling T to T', in four partial sums (independent
// chains of additions).
GRANVV_WIDE_LOOPS
double energy_removed(const std::vector<double>& cell_mass, const std::vector<double>& T,
                      const std::vector<double>& cooled) {
  std::array<double, 4> partial{};
  const size_t n = T.size();
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    for (size_t k = 0; k < 4; ++k) partial[k] += cell_mass[i + k] * (T[i + k] - cooled[i + k]);
  }
  for (; i < n; ++i) partial[0] += cell_mass[i] * (T[i] - cooled[i]);
  return (partial[0] + partial[1]) + (partial[2] + partial[3]);
}

// Largest |T'_i / T_i - 1|, the per-cell changes stored first (a loop that vectorises).
GRANVV_WIDE_LOOPS
double largest_relative_change(const std::vector<double>& T, const std::vector<double>& changed,
                               std::vector<double>& change) {
  change.resize(T.size());
  for (size_t i = 0; i < T.size(); ++i) change[i] = std::abs(changed[i] / T[i] - 1.0);
  return largest_value(change);
}

}  // namespace

HydroIntegrator::HydroIntegrator(const Closure& closure, int cells)
    : closure_(closure), op_(closure, cells) {}

GRANVV_WIDE_LOOPS
StepOutcome HydroIntegrator::step(LagrangianState& s, double dt, CellGeometry& cells) {
  StepOutcome out;
  const int n = s.cells();
  // C(dt/2): cooling at the start state's densities (cooling moves no node).
  closure_.cool(cells.density, s.cell_T, 0.5 * dt, T_start_);
  out.energy_cooled = energy_removed(s.cell_mass, s.cell_T, T_start_);

  // Predictor: coefficients at the start of the step.
  op_.freeze(s.cell_mass, cells.width, T_start_, dt, {}, coefficients_);
  if (!op_.advance(s, T_start_, coefficients_, dt, predicted_)) return out;

  // Corrector: coefficients at the mean of start and predicted states, the pressure
  // linearised about the predictor's compression.
  cell_widths(predicted_.node_x, widths_mid_);
  T_mid_.resize(n);
  for (int i = 0; i < n; ++i) {
    widths_mid_[i] = 0.5 * (cells.width[i] + widths_mid_[i]);
    T_mid_[i] = 0.5 * (T_start_[i] + predicted_.cell_T[i]);
  }
  op_.freeze(s.cell_mass, widths_mid_, T_mid_, dt, op_.last_velocity_differences(), coefficients_);
  if (!op_.advance(s, T_start_, coefficients_, dt, corrected_)) return out;
  out.relative_heating = largest_relative_change(T_start_, corrected_.cell_T, relative_change_);

  // C(dt/2) at the end state's densities, measured once for this and every later pass.
  cell_widths(corrected_.node_x, end_cells_.width);
  end_cells_.density.resize(n);
  for (int i = 0; i < n; ++i) end_cells_.density[i] = s.cell_mass[i] / end_cells_.width[i];
  closure_.cool(end_cells_.density, corrected_.cell_T, 0.5 * dt, T_end_);
  out.energy_cooled += energy_removed(s.cell_mass, corrected_.cell_T, T_end_);

  s.t = corrected_.t;
  std::swap(s.node_x, corrected_.node_x);
  std::swap(s.node_v, corrected_.node_v);
  std::swap(s.node_vy, corrected_.node_vy);
  std::swap(s.cell_T, T_end_);
  std::swap(cells, end_cells_);
  out.accepted = true;
  return out;
}

StepOutcome HydroIntegrator::step(LagrangianState& s, double dt) {
  measure_cells(s, cells_);
  return step(s, dt, cells_);
}

}  // namespace granvv::hydro
