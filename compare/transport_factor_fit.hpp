#pragma once
// A transport coefficient from the particles' mode amplitudes (docs/physics.md §14): the hydro
// is run with its closure's coefficient times a factor F at a grid of factors, and F is fitted
// so that the hydro's linear response follows the particles' mean amplitude.
//
// The response. R_s(F) = H_s(F) / H_0(F): the hydro's amplitude at snapshot s relative to its
// start, at factor F, interpolated between the grid's factors by the polynomial through them
// (of ln R when every R of the snapshot is positive: a decaying mode's ln R is nearly linear in
// F, exactly so for a shear wave, -F k^2 ∫ nu dt; of R itself otherwise). The particles'
// amplitude at s is predicted as A R_s(F), with the start amplitude A fitted beside F (for each F
// the A of least chi^2, a weighted linear least-squares): every snapshot then informs the start,
// not the noisy first one alone, and a kinetic transient of the first collisions (which the
// Navier-Stokes hydro lacks) shifts A rather than F.
//
// The fit. F minimises chi^2(F) = sum_s (a_s - A(F) R_s(F))^2 / sigma_s^2 over the grid's range,
// with a_s the members' mean and sigma_s the jackknife error (over members,
// compare/jackknife.hpp) of the residual a_s - A R_s (each leave-one-out ensemble with its own
// A) at a first fit weighted by the errors of a_s. The standard error of F is the jackknife's: F
// (and A) refitted on every leave-one-out ensemble with the same weights. Each member's
// amplitudes are correlated from snapshot to snapshot (its mode's fluctuation persists), and
// the refits carry those correlations into the error of F in full. chi^2 uses each snapshot's
// variance alone (the diagonal), so with correlated snapshots it is a measure of the match, not
// a chi^2 variable with `degrees_of_freedom` degrees: chi^2 / dof well above 1 says the hydro's
// decay has another shape than the particles'.
#include <vector>

namespace granvv::compare {

// The hydro's amplitudes at the particles' snapshots: amplitudes[j][s] at factors[j] (strictly
// increasing, at least two) and snapshot s (s = 0: the start).
struct FactorGrid {
  std::vector<double> factors;
  std::vector<std::vector<double>> amplitudes;
};

// R_s(F) as above. Throws std::invalid_argument for a grid that is not as described.
double response_ratio(const FactorGrid& grid, std::size_t snapshot, double factor);

// A R_s(F) for every snapshot of the grid.
std::vector<double> predicted_amplitudes(const FactorGrid& grid, double start_amplitude,
                                         double factor);

struct FactorFit {
  double factor = 0.0, error = 0.0;  // F and its jackknife standard error
  double chi2 = 0.0;
  double start = 0.0;          // A at the fitted F
  int degrees_of_freedom = 0;  // snapshots less two (F and A)
  bool at_grid_edge = false;   // F at the end of the grid's range: the grid does not bracket it
  // Per snapshot: the members' mean amplitude and its jackknife error, the residual's error
  // (sigma_s), and the predictions A R_s at the fitted F and at F = 1 (each with its own A).
  std::vector<double> amplitude, amplitude_error, residual_error, fitted, unit_factor;
};

// member_amplitudes[m][s] (compare/mode_amplitudes.hpp), as many snapshots as the grid. Throws
// std::invalid_argument with fewer than two members, fewer than three snapshots or a grid that
// does not match.
FactorFit fit_transport_factor(const FactorGrid& grid,
                               const std::vector<std::vector<double>>& member_amplitudes);

}  // namespace granvv::compare
