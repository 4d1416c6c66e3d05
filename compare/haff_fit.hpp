#pragma once
// Fitting Haff's law T(t) = T0 (1 + t/t0)^-2 to a measured cooling curve. On Haff's law
// T^{-1/2} is a straight line in t, T^{-1/2} = T0^{-1/2} (1 + t/t0), so t0 = intercept/slope
// of a least-squares line through (t, T^{-1/2}). Across an ensemble of independent runs the
// fit is made per run and the standard error taken from the scatter of the runs.
#include <optional>
#include <vector>

namespace granvv::compare {

struct HaffFit {
  double t0 = 0.0, T0 = 0.0;
  double t0_error = 0.0;  // standard error (ensemble scatter; with one run, regression error)
  int runs = 0, points = 0;
  double t_min = 0.0, t_max = 0.0;  // fitted window
};

// One cooling curve over t_min <= t <= t_max; requires >= 3 points with T > 0.
HaffFit fit_haff(const std::vector<double>& t, const std::vector<double>& T, double t_min,
                 double t_max);
// Each run fitted on its own; t0 = mean, error = standard deviation / sqrt(runs) for runs >= 2.
HaffFit fit_haff_ensemble(const std::vector<std::vector<double>>& t,
                          const std::vector<std::vector<double>>& T, double t_min, double t_max);

// Haff's law with the fitted amplitude, T0 (1 + t/t0)^-2, at each of the times t (the curve
// a fit, or kinetic theory's t0 with the fit's T0, draws over the samples).
std::vector<double> haff_curve(const std::vector<double>& t, double T0, double t0);

// Acceptance of a particle run's cooling: the fitted Haff time lies within 3 % of kinetic theory
// with the Enskog chi(phi) (docs/physics.md §4). deviation = t0_measured / t0_theory - 1;
// nullopt when it is not finite (no fit).
inline constexpr double kHaffTimeTolerance = 0.03;
// measured / theory - 1: how far a measured Haff time is from a theory's. NaN (absent, null in
// summary.json) where the theory gives no Haff time: an elastic gas does not cool, its t0 is
// infinite, and a deviation of -1 would claim a theory that does not exist.
double relative_deviation(double measured, double theory);
std::optional<bool> haff_time_within_tolerance(double deviation);

// Whether a model's Haff time t0_model misses the measured one by more than 10 % and by more
// than 3 fit errors: then the model's K, q do not describe the particle box (docs/physics.md
// §4), and differences in T come from the cooling rate. nullopt when the fit has no finite t0
// or no positive, finite error.
inline constexpr double kCoolsDifferentlyRelative = 0.1;
inline constexpr double kCoolsDifferentlySigmas = 3.0;
std::optional<bool> cools_differently(double t0_model, const HaffFit& measured);

}  // namespace granvv::compare
