#pragma once
// The spatial operator of the Lagrangian scheme for paper Eqs. (1)-(2) on a staggered
// periodic mesh, in its "compatible" form: the work done on a cell's internal energy is
// exactly the kinetic energy the nodes lose, so E = sum(m T + mu v^2/2) changes only by
// the cooling sink (paper Eq. 3). Viscous stress and heat conduction enter implicitly
// (Crank-Nicolson, periodic tridiagonal systems). The pressure is frozen except for its
// adiabatic response to the cell's own compression over the step, which is implicit:
//   p_eff = p - alpha (dv - dv_ref),  alpha = (B/dx) dt/2
// with B the closure's adiabatic modulus (dp/d(dx) = -B/dx at fixed mass and entropy), so a
// half-step change dx -> dx + dt dv/2 changes p by -(B/dx) dt dv/2 (dilute 2D gas: B = 2p).
// This removes the sound-crossing limit of the thin cells in a density peak, where the flow is
// supersonic and the compression limit already sets the step. Every constitutive coefficient
// comes from the closure (hydro/closure.hpp), one call per pass.
//
// The inelastic heat flux down the density gradient, -mu dn/dx (hydro/closure.hpp), is frozen
// with the pressure: explicit, at the pass's densities (in the corrector those of the mean of
// the start and predicted widths, so time-centred to second order). It is conservative (a flux
// between cells) and needs no step limit of its own: it drives T but not n directly, and the
// implicit conduction bounds the relative temperature change it drives in a cell to
// mu n/(kappa T) times the relative density contrast (Garzo-Dufty: mu*/kappa* = 0.16 at r = 0.9,
// 0.33 at r = 0.8), less than the adiabatic response of the pressure to that contrast; the
// heating limit of the step (TimeStepControl::max_temperature_change) counts it with the work
// and the conduction. A closure with mu = 0 everywhere (the dilute and Enskog ones) skips it,
// so its runs are those of the paper's Eq. (2) bit for bit.
#include <vector>

#include "hydro/batched_tridiagonal.hpp"
#include "hydro/closure.hpp"
#include "hydro/lagrangian_state.hpp"

namespace granvv::hydro {

// Coefficients frozen over one pass, evaluated at one time level (or a mean of two).
struct FrozenCoefficients {
  std::vector<double> density;           // n_i = m_i / dx_i per cell
  CellCoefficients cell;                 // the closure's p_i, B_i, eta_i, eta_xy_i, kappa_i
  std::vector<double> viscous_coupling;  // a_i = eta_i / dx_i per cell
  std::vector<double> shear_coupling;    // a_xy_i = eta_xy_i / dx_i per cell
  std::vector<double> heat_coupling;     // b_j = kappa_j / h_j at node j (between cells j-1, j)
  // d_j = mu_j / h_j at node j, empty when mu = 0 in every cell (no density-gradient heat flux)
  std::vector<double> density_heat_coupling;
  std::vector<double>
      acoustic_coupling;             // alpha_i = B_i dt / (2 dx_i) (implicit adiabatic response)
  std::vector<double> reference_dv;  // dv_ref_i about which the pressure is linearised
};

// The fields one pass moves: node positions and velocities and cell temperatures at the end
// of the pass. Cell masses and node labels stay those of the start state (Lagrangian mesh).
struct PassFields {
  double t = 0.0;
  std::vector<double> node_x, node_v, node_vy, cell_T;  // node_vy empty: not carried
};

class LagrangianOperator {
 public:
  // The closure must outlive the operator.
  LagrangianOperator(const Closure& closure, int cells);

  // Coefficients from cell widths and temperatures (both per cell) for a step dt, with the
  // pressure linearised about the velocity differences reference_dv (empty: zero).
  void freeze(const std::vector<double>& cell_mass, const std::vector<double>& widths,
              const std::vector<double>& T, double dt, const std::vector<double>& reference_dv,
              FrozenCoefficients& out);
  // Velocity differences vbar_{i+1} - vbar_i of the time-centred velocity of the last advance().
  const std::vector<double>& last_velocity_differences() const { return dv_mid_; }

  // One pass over dt with the frozen coefficients from the state `from` with cell temperatures
  // T_from: solve the momentum equation (implicit viscosity) for the time-centred velocity,
  // move the nodes, then the energy equation (compatible work, implicit conduction). `to` is
  // overwritten. Returns false if the result is unphysical (T <= 0 or not finite, or a node
  // overtook its neighbour).
  bool advance(const LagrangianState& from, const std::vector<double>& T_from,
               const FrozenCoefficients& c, double dt, PassFields& to);

 private:
  const Closure& closure_;
  int n_;
  PeriodicLdlFactors momentum_, energy_, shear_;
  std::vector<double> momentum_diag_, momentum_upper_, energy_diag_, energy_upper_;
  std::vector<double> shear_diag_, shear_upper_;
  std::vector<double> v_mid_, vy_mid_, dv_mid_, work_;
  std::vector<double> inertia_;        // 2 mu_j / dt per node
  std::vector<double> inverse_width_;  // 1 / dx_i per cell
};

}  // namespace granvv::hydro
