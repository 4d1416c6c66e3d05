#pragma once
// Two transport coefficients at once from the particles' mode amplitudes (docs/physics.md §14):
// the hydro is run on a grid of two factors (F_a on one coefficient, F_b on the other) and both
// are fitted jointly to the members' k = 1 amplitudes of several signals (fields and phases of
// one ensemble, e.g. a sound wave's v_x, n and T), the sibling of transport_factor_fit.hpp for a
// scene whose response mixes two coefficients.
//
// The prediction. The hydro starts from the particles' t = 0 fields, so its amplitudes are the
// prediction itself, up to one scale lambda common to every signal and snapshot (fitted, the
// weighted linear least-squares at each (F_a, F_b)): a_gs = lambda H_gs(F_a, F_b). A signal
// may start at zero (a sound wave's n and T), so amplitudes, not ratios to the start, are
// interpolated: by the tensor-product polynomial through the grid. With one signal lambda H_s is
// the single-factor fit's A R_s.
//
// The fit. (F_a, F_b) minimise chi^2 = sum_gs (a_gs - lambda H_gs)^2 / sigma_gs^2 over the
// grid's rectangle (for each F_a the best F_b, then the best F_a of that profile; scans then
// golden sections), sigma_gs the jackknife error (over members) of the residual at a first fit
// weighted by the errors of a_gs. The errors of F_a and F_b and their correlation are the
// jackknife's: both refitted on every leave-one-out ensemble, so the correlations of a member's
// amplitudes across signals and snapshots are carried in full; chi^2 is the diagonal one, a
// measure of the match (see transport_factor_fit.hpp).
#include <vector>

namespace granvv::compare {

struct PairSignal {
  // hydro[i][j][s]: the hydro's amplitude at factors_a[i], factors_b[j] and snapshot s.
  std::vector<std::vector<std::vector<double>>> hydro;
  // members[m][s]: member m's amplitude at snapshot s (compare/mode_amplitudes.hpp).
  std::vector<std::vector<double>> members;
};

struct FactorPairGrid {
  std::vector<double> factors_a, factors_b;  // each strictly increasing, at least two
  // The fit searches F_b from this far below factors_b.front() (the polynomial extrapolated),
  // for a coefficient whose hydro cannot run below it (mu < 0) but whose measured value may be
  // there within its error; 0 = the grid's range.
  double b_below = 0.0;
};

struct PairFit {
  double factor_a = 0.0, factor_b = 0.0;
  double error_a = 0.0, error_b = 0.0;  // jackknife standard errors
  double correlation = 0.0;             // of the errors of F_a and F_b (jackknife)
  double scale = 0.0;                   // lambda at the fitted factors
  double chi2 = 0.0;
  int degrees_of_freedom = 0;  // amplitudes less three (F_a, F_b, lambda)
  bool at_grid_edge = false;   // a factor at the end of its range: the grid does not bracket it
  // Per signal and snapshot: the members' mean and its jackknife error, the residual's error
  // (sigma_gs) and the prediction at the fitted factors.
  std::vector<std::vector<double>> amplitude, amplitude_error, residual_error, fitted;
};

// lambda H_gs(F_a, F_b) for every snapshot of signal g.
std::vector<double> predicted_pair_amplitudes(const FactorPairGrid& grid, const PairSignal& signal,
                                              double scale, double factor_a, double factor_b);

// Throws std::invalid_argument for a grid or signals not as described: no signals, fewer than
// two members, signals with different member counts, a hydro table not of the grid's shape, or
// fewer than four amplitudes in all.
PairFit fit_transport_factor_pair(const FactorPairGrid& grid,
                                  const std::vector<PairSignal>& signals);

}  // namespace granvv::compare
