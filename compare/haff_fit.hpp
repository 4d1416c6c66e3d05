#pragma once
// Fitting Haff's law T(t) = T0 (1 + t/t0)^-2 to a measured cooling curve. On Haff's law
// T^{-1/2} is a straight line in t, T^{-1/2} = T0^{-1/2} (1 + t/t0), so t0 = intercept/slope
// of a least-squares line through (t, T^{-1/2}). Across an ensemble of independent runs the
// fit is made per run and the standard error taken from the scatter of the runs.
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

}  // namespace granvv::compare
