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
  double S = 0, Sx = 0, Sy = 0;
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
    S += wi, Sx += wi * a, Sy += wi * b, ++n;
  }
  // Two distinct abscissae, compared directly: for equal x the determinant S Sxx - Sx^2 is a
  // rounding residue of either sign, not zero.
  bool distinct = false;
  for (const double a : lx) distinct = distinct || a != lx.front();
  if (n < 2 || !distinct) {
    throw std::invalid_argument("fit_power_law: needs at least two points with distinct x");
  }
  PowerLawFit f;
  f.points = n;
  // Centred sums: no cancellation when ln x has a large mean and a small spread.
  const double abar = Sx / S, bbar = Sy / S;
  double Saa = 0.0, Sab = 0.0;
  for (int i = 0; i < n; ++i) {
    Saa += w[i] * (lx[i] - abar) * (lx[i] - abar);
    Sab += w[i] * (lx[i] - abar) * (ly[i] - bbar);
  }
  f.power = Sab / Saa;
  const double intercept = bbar - f.power * abar;
  f.prefactor = std::exp(intercept);
  double chi2 = 0.0;
  for (int i = 0; i < n; ++i) chi2 += w[i] * std::pow(ly[i] - intercept - f.power * lx[i], 2);
  f.chi2_per_dof = n > 2 ? chi2 / (n - 2) : std::numeric_limits<double>::quiet_NaN();
  const double inflate = n > 2 ? std::sqrt(std::max(1.0, f.chi2_per_dof)) : 1.0;
  f.power_error = std::sqrt(1.0 / Saa) * inflate;
  return f;
}

}  // namespace granvv::compare
