#pragma once
// The heat-flux coefficients of a particle ensemble measured at their definition
// (docs/physics.md §14, "The heat flux at its definition"): the k = 1 part of the particles' own
// kinetic heat flux, snapshot by snapshot, against the gradients that drive it,
//
//   q_x = -kappa dT/dx - mu dn/dx + beta d2v_x/dx2
//
// (Brey, Dufty, Kim & Santos, PRE 58, 4638 (1998): Fourier's law of a granular gas with the
// density term mu; beta is the one linear Burnett term of the heat flux in one dimension). No
// hydro enters: the measurement needs no Navier-Stokes solution to be right, and a mode whose
// decay the Navier-Stokes equations miss (a sound wave at k l = 0.16, docs/physics.md §14) still
// gives kappa and mu.
//
// The local flow is the ensemble's mean flow U(x, t) (that of kinetic theory), not each member's
// bin mean: a bin's own sample mean correlates with its third moment and biases the flux by
// about -3/N for N disks per bin, and leaves in T a share of the velocity fluctuations that grows
// with the number of bins (measured: kappa 5 % apart between 16 and 64 bins; with U, 1.1 +- 0.6 %).
// Relative to U a member's own k = 1 flow v carries the enthalpy flux (e + P_xx) v at linear
// order, noise that is removed at the level of the mode: q = J - 2 <e> v (2D: P_xx = e = n T at
// the homogeneous state), J the box-frame kinetic energy flux, exact to second order in the mode
// amplitude at k = 1 (a product of two k = 1 parts has none).
#include <cstddef>
#include <vector>

#include "fields/field_series.hpp"

namespace granvv::compare {

// Per member (rows) and snapshot (columns): the k = 1 parts the fit reads (compare/
// mode_amplitudes.hpp, bins on [-1/2, 1/2)), and the box means.
struct HeatFluxAmplitudes {
  std::vector<double> t;                         // the snapshots' times (the first member's)
  std::vector<std::vector<double>> heat_flux;    // sine part of q (relative to U)
  std::vector<std::vector<double>> temperature;  // cosine part of T/<T> (T relative to U)
  std::vector<std::vector<double>> density;      // cosine part of n/<n>
  std::vector<std::vector<double>> flow;         // sine part of v_x
  std::vector<std::vector<double>> mean_density, mean_temperature;  // <n>, <T>
  // Whether the flux includes the contact transfer of energy at every snapshot after the first
  // (the engine measured it: the column contact_energy_flux_x is finite); the first snapshot,
  // before any collision, has none.
  bool contact_transfer = true;
};

// From the members' coarse-grained fields (columns n, v_x, v_y, kinetic_energy, energy_flux_x;
// md_bridge/coarse_grainer.hpp) of disks of one mass: the thermal energy density relative to U,
// e = E - U.p + rho |U|^2 / 2 (E the box-frame kinetic energy density, p = rho v, rho = m n),
// T = e / n (the kinetic temperature). Where a snapshot has the contact transfer of energy
// (contact_energy_flux_x) it is added to the flux, and the enthalpy removed is e + P_xx with the
// contact part of the pressure (the P_xx column's box mean) instead of 2 e: kappa and mu are then
// the whole coefficients, kinetic and contact, as Enskog's. The snapshots every member has are
// used. Throws std::invalid_argument for fewer than 8 members, members on other bins, a missing
// column, a bin empty in the ensemble, or a non-positive mass.
HeatFluxAmplitudes heat_flux_amplitudes(const std::vector<fields::FieldSeries>& members,
                                        double mass);

struct HeatFluxFit {
  // kappa / kappa0 and mu / mu0 (kappa0 = 4 eta0 / m, mu0 = T kappa0 / n, eta0 =
  // sqrt(m T / pi) / (2 sigma)), and theta = beta rho / eta0^2 (the Burnett coefficient in the
  // dilute gas's natural unit), each with its jackknife error over members; 0 and 0 for theta
  // when it is not fitted.
  double conductivity = 0.0, conductivity_error = 0.0;
  double mu = 0.0, mu_error = 0.0;
  double burnett = 0.0, burnett_error = 0.0;
  double correlation = 0.0;  // of the errors of kappa and mu
  // sum_s ((y_s - fitted_s) / error_s)^2 over the fitted snapshots and its degrees of freedom.
  double chi2 = 0.0;
  int degrees_of_freedom = 0;
  // Per fitted snapshot: the response y = q / (k kappa0 <T>) of the ensemble means, its
  // jackknife error, the fit, its Navier-Stokes part alone (kappa and mu), and mu's part alone.
  std::vector<std::size_t> snapshots;
  std::vector<double> response, response_error, fitted, navier_stokes, density_part;
};

// The weighted least-squares fit of y_s = F_kappa T_s + F_mu n_s + b v_s / sqrt(<T>_s / m)
// (T_s, n_s, v_s the ensemble means of the k = 1 parts) over the snapshots from `start` on,
// weighted by the jackknife errors of y_s; theta = -8 sqrt(pi) b <n> sigma / k. The errors come
// from refitting on every leave-one-out ensemble (the weights held), so the members' correlations
// from snapshot to snapshot are in them. k: the mode's wavenumber 2 pi / Lx in the disks' units.
// Throws std::invalid_argument for fewer snapshots than three more than the coefficients, bad
// arguments, amplitudes that are not finite, or a temperature mode proportional to the density mode
// (a scene at pressure balance to within the scatter, |correlation| > 0.999 over the fitted
// snapshots: kappa and mu cannot be told apart; nearer balance the errors of kappa and mu say how
// far they can).
HeatFluxFit fit_heat_flux(const HeatFluxAmplitudes& a, double wavenumber, double mass,
                          double diameter, std::size_t start, bool burnett);

}  // namespace granvv::compare
