#pragma once
// A power law y = C x^p fitted to measured points with errors: weighted least squares of
// ln y against ln x, each point weighted by 1 / (dy / y)^2 (its relative error is the error of
// ln y to first order). The parameter errors come from the weights (the covariance of the
// weighted fit), scaled up by sqrt(chi^2 / dof) when the scatter exceeds the stated errors, so a
// poor fit is not reported as a precise one.
#include <vector>

namespace granvv::compare {

struct PowerLawFit {
  double power = 0.0, power_error = 0.0;
  double prefactor = 0.0;     // C
  double chi2_per_dof = 0.0;  // of the unscaled weighted fit (NaN for two points)
  int points = 0;
};

// Needs >= 2 points with x > 0, y > 0 and dy > 0 (all finite) and two distinct x; throws
// std::invalid_argument otherwise or if the sizes differ.
PowerLawFit fit_power_law(const std::vector<double>& x, const std::vector<double>& y,
                          const std::vector<double>& y_error);

}  // namespace granvv::compare
