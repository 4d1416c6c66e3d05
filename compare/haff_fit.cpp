#include "compare/haff_fit.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace granvv::compare {

HaffFit fit_haff(const std::vector<double>& t, const std::vector<double>& T, double t_min,
                 double t_max) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  HaffFit f;
  f.t_min = t_max, f.t_max = t_min;
  std::vector<double> xs, ys;
  for (size_t i = 0; i < t.size() && i < T.size(); ++i) {
    if (t[i] < t_min || t[i] > t_max || !(T[i] > 0.0)) continue;
    const double y = 1.0 / std::sqrt(T[i]);
    xs.push_back(t[i]), ys.push_back(y);
    n += 1, sx += t[i], sy += y, sxx += t[i] * t[i], sxy += t[i] * y;
    f.t_min = std::min(f.t_min, t[i]), f.t_max = std::max(f.t_max, t[i]);
  }
  if (n < 3) throw std::invalid_argument("Haff fit needs at least 3 samples in its window");
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double intercept = (sy - slope * sx) / n;
  if (!(slope > 0.0)) throw std::invalid_argument("the temperature does not decay: no Haff fit");
  f.t0 = intercept / slope;
  f.T0 = 1.0 / (intercept * intercept);
  f.points = int(n);
  f.runs = 1;
  // Regression standard errors of slope and intercept, propagated to t0 = a/b.
  double ss = 0;
  for (size_t i = 0; i < xs.size(); ++i) {
    const double r = ys[i] - (intercept + slope * xs[i]);
    ss += r * r;
  }
  const double sigma2 = ss / std::max(1.0, n - 2), sxx_c = sxx - sx * sx / n;
  const double var_b = sigma2 / sxx_c, var_a = sigma2 * (1.0 / n + (sx / n) * (sx / n) / sxx_c);
  const double cov_ab = -sigma2 * (sx / n) / sxx_c;
  f.t0_error = std::abs(f.t0) *
               std::sqrt(std::max(0.0, var_a / (intercept * intercept) + var_b / (slope * slope) -
                                           2 * cov_ab / (intercept * slope)));
  return f;
}

HaffFit fit_haff_ensemble(const std::vector<std::vector<double>>& t,
                          const std::vector<std::vector<double>>& T, double t_min, double t_max) {
  if (t.empty() || t.size() != T.size()) throw std::invalid_argument("no runs to fit");
  std::vector<HaffFit> fits;
  for (size_t r = 0; r < t.size(); ++r) fits.push_back(fit_haff(t[r], T[r], t_min, t_max));
  if (fits.size() == 1) return fits.front();
  HaffFit f = fits.front();
  double mean = 0, mean_T0 = 0;
  for (const auto& x : fits) mean += x.t0, mean_T0 += x.T0;
  mean /= fits.size(), mean_T0 /= fits.size();
  double var = 0;
  for (const auto& x : fits) var += (x.t0 - mean) * (x.t0 - mean);
  var /= fits.size() - 1;
  f.t0 = mean, f.T0 = mean_T0;
  f.t0_error = std::sqrt(var / fits.size());
  f.runs = int(fits.size());
  return f;
}

std::vector<double> haff_curve(const std::vector<double>& t, double T0, double t0) {
  std::vector<double> T;
  for (double ti : t) T.push_back(T0 / std::pow(1.0 + ti / t0, 2));
  return T;
}

double relative_deviation(double measured, double theory) {
  if (!std::isfinite(theory) || !(theory > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return measured / theory - 1.0;
}

std::optional<bool> haff_time_within_tolerance(double deviation) {
  if (!std::isfinite(deviation)) return std::nullopt;
  return std::abs(deviation) <= kHaffTimeTolerance;
}

std::optional<bool> cools_differently(double t0_model, const HaffFit& measured) {
  if (!std::isfinite(measured.t0) || !std::isfinite(measured.t0_error) ||
      !(measured.t0_error > 0)) {
    return std::nullopt;
  }
  return std::abs(t0_model / measured.t0 - 1.0) > kCoolsDifferentlyRelative &&
         std::abs(t0_model - measured.t0) > kCoolsDifferentlySigmas * measured.t0_error;
}

}  // namespace granvv::compare
