#include "compare/power_law_fit.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace granvv::compare {

PowerLawFit fit_power_law(const std::vector<double>& x, const std::vector<double>& y,
                          const std::vector<double>& y_error) {
  if (x.size() != y.size() || y.size() != y_error.size()) {
    throw std::invalid_argument("fit_power_law: x, y and errors differ in length");
  }
  double S = 0, Sx = 0, Sy = 0, Sxx = 0, Sxy = 0;
  int n = 0;
  std::vector<double> lx, ly, w;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0) || !(y[i] > 0) || !(y_error[i] > 0) || !std::isfinite(x[i]) ||
        !std::isfinite(y[i]) || !std::isfinite(y_error[i])) {
      throw std::invalid_argument("fit_power_law: point " + std::to_string(i) +
                                  " needs finite x > 0, y > 0 and error > 0");
    }
    const double a = std::log(x[i]), b = std::log(y[i]), wi = std::pow(y[i] / y_error[i], 2);
    lx.push_back(a), ly.push_back(b), w.push_back(wi);
    S += wi, Sx += wi * a, Sy += wi * b, Sxx += wi * a * a, Sxy += wi * a * b, ++n;
  }
  const double det = S * Sxx - Sx * Sx;
  if (n < 2 || !(det > 1e-300 * S * Sxx)) {
    throw std::invalid_argument("fit_power_law: needs at least two points with distinct x");
  }
  PowerLawFit f;
  f.points = n;
  f.power = (S * Sxy - Sx * Sy) / det;
  const double intercept = (Sxx * Sy - Sx * Sxy) / det;
  f.prefactor = std::exp(intercept);
  double chi2 = 0.0;
  for (int i = 0; i < n; ++i) chi2 += w[i] * std::pow(ly[i] - intercept - f.power * lx[i], 2);
  f.chi2_per_dof = n > 2 ? chi2 / (n - 2) : std::numeric_limits<double>::quiet_NaN();
  const double inflate = n > 2 ? std::sqrt(std::max(1.0, f.chi2_per_dof)) : 1.0;
  f.power_error = std::sqrt(S / det) * inflate;
  return f;
}

}  // namespace granvv::compare
