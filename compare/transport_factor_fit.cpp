#include "compare/transport_factor_fit.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "compare/jackknife.hpp"

namespace granvv::compare {
namespace {

constexpr int kScanPoints = 400;            // the coarse scan of chi^2 over the grid's range
constexpr double kFactorTolerance = 1e-10;  // golden-section refinement, relative to the range

void check_grid(const FactorGrid& grid) {
  if (grid.factors.size() < 2 || grid.amplitudes.size() != grid.factors.size()) {
    throw std::invalid_argument(
        "transport factor fit: needs at least two factors, each with "
        "its hydro amplitudes");
  }
  for (std::size_t j = 0; j < grid.factors.size(); ++j) {
    if (j > 0 && !(grid.factors[j] > grid.factors[j - 1])) {
      throw std::invalid_argument("transport factor fit: factors must be strictly increasing");
    }
    if (grid.amplitudes[j].size() != grid.amplitudes.front().size() || grid.amplitudes[j].empty()) {
      throw std::invalid_argument("transport factor fit: hydro amplitudes of different lengths");
    }
  }
}

// The polynomial through (x_j, y_j) at x (Lagrange's form; a handful of points).
double polynomial_through(const std::vector<double>& x, const std::vector<double>& y, double at) {
  double sum = 0.0;
  for (std::size_t j = 0; j < x.size(); ++j) {
    double basis = 1.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (i != j) basis *= (at - x[i]) / (x[j] - x[i]);
    }
    sum += basis * y[j];
  }
  return sum;
}

// A(F): the start amplitude of least chi^2 at factor F, sum w a R / sum w R^2 (w = 1/sigma^2).
double best_start(const FactorGrid& grid, const std::vector<double>& a,
                  const std::vector<double>& sigma, double factor) {
  const std::vector<double> r = predicted_amplitudes(grid, 1.0, factor);
  double num = 0.0, den = 0.0;
  for (std::size_t s = 0; s < a.size(); ++s) {
    const double w = 1.0 / (sigma[s] * sigma[s]);
    num += w * a[s] * r[s], den += w * r[s] * r[s];
  }
  return num / den;
}

double chi2_at(const FactorGrid& grid, const std::vector<double>& a,
               const std::vector<double>& sigma, double factor) {
  const std::vector<double> p =
      predicted_amplitudes(grid, best_start(grid, a, sigma, factor), factor);
  double chi2 = 0.0;
  for (std::size_t s = 0; s < a.size(); ++s) {
    const double d = (a[s] - p[s]) / sigma[s];
    chi2 += d * d;
  }
  return chi2;
}

// The F in [F_min, F_max] of least chi^2: a scan, then golden sections around its best point.
double best_factor(const FactorGrid& grid, const std::vector<double>& a,
                   const std::vector<double>& sigma) {
  const double lo = grid.factors.front(), hi = grid.factors.back();
  const double step = (hi - lo) / kScanPoints;
  int best = 0;
  double best_chi2 = chi2_at(grid, a, sigma, lo);
  for (int i = 1; i <= kScanPoints; ++i) {
    const double c = chi2_at(grid, a, sigma, lo + i * step);
    if (c < best_chi2) best = i, best_chi2 = c;
  }
  double left = lo + std::max(best - 1, 0) * step;
  double right = lo + std::min(best + 1, kScanPoints) * step;
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = right - golden * (right - left), x2 = left + golden * (right - left);
  double c1 = chi2_at(grid, a, sigma, x1), c2 = chi2_at(grid, a, sigma, x2);
  while (right - left > kFactorTolerance * (hi - lo)) {
    if (c1 < c2) {
      right = x2, x2 = x1, c2 = c1;
      x1 = right - golden * (right - left), c1 = chi2_at(grid, a, sigma, x1);
    } else {
      left = x1, x1 = x2, c1 = c2;
      x2 = left + golden * (right - left), c2 = chi2_at(grid, a, sigma, x2);
    }
  }
  const double inside = 0.5 * (left + right);
  // The ends of the range are candidates too (a minimum beyond the grid lands there).
  double chosen = inside, chosen_chi2 = chi2_at(grid, a, sigma, inside);
  for (double end : {lo, hi}) {
    const double c = chi2_at(grid, a, sigma, end);
    if (c < chosen_chi2) chosen = end, chosen_chi2 = c;
  }
  return chosen;
}

// The jackknife error of a_s - A R_s(F) at every snapshot, each sample with its own A(F).
std::vector<double> residual_errors(const FactorGrid& grid,
                                    const std::vector<std::vector<double>>& samples,
                                    const std::vector<double>& sigma, double factor) {
  std::vector<std::vector<double>> residuals;
  for (const auto& a : samples) {
    const std::vector<double> p =
        predicted_amplitudes(grid, best_start(grid, a, sigma, factor), factor);
    std::vector<double> r;
    for (std::size_t s = 0; s < a.size(); ++s) r.push_back(a[s] - p[s]);
    residuals.push_back(std::move(r));
  }
  return jackknife_errors(residuals);
}

}  // namespace

double response_ratio(const FactorGrid& grid, std::size_t snapshot, double factor) {
  check_grid(grid);
  std::vector<double> ratio;
  bool positive = true;
  for (const auto& h : grid.amplitudes) {
    ratio.push_back(h.at(snapshot) / h.front());
    positive = positive && ratio.back() > 0.0;
  }
  if (!positive) return polynomial_through(grid.factors, ratio, factor);
  for (double& r : ratio) r = std::log(r);
  return std::exp(polynomial_through(grid.factors, ratio, factor));
}

std::vector<double> predicted_amplitudes(const FactorGrid& grid, double start_amplitude,
                                         double factor) {
  check_grid(grid);
  std::vector<double> p;
  for (std::size_t s = 0; s < grid.amplitudes.front().size(); ++s) {
    p.push_back(start_amplitude * response_ratio(grid, s, factor));
  }
  return p;
}

FactorFit fit_transport_factor(const FactorGrid& grid,
                               const std::vector<std::vector<double>>& member_amplitudes) {
  check_grid(grid);
  const std::size_t snapshots = grid.amplitudes.front().size();
  if (snapshots < 3) {
    throw std::invalid_argument("transport factor fit: needs at least three snapshots");
  }
  for (const auto& row : member_amplitudes) {
    if (row.size() != snapshots) {
      throw std::invalid_argument(
          "transport factor fit: members and hydro at different "
          "snapshots");
    }
  }
  const std::vector<std::vector<double>> samples = leave_one_out_means(member_amplitudes);
  FactorFit fit;
  fit.amplitude = member_mean(member_amplitudes);
  fit.amplitude_error = jackknife_errors(samples);
  const double first = best_factor(grid, fit.amplitude, fit.amplitude_error);
  fit.residual_error = residual_errors(grid, samples, fit.amplitude_error, first);
  fit.factor = best_factor(grid, fit.amplitude, fit.residual_error);
  fit.chi2 = chi2_at(grid, fit.amplitude, fit.residual_error, fit.factor);
  fit.degrees_of_freedom = int(snapshots) - 2;  // F and A
  fit.at_grid_edge = fit.factor == grid.factors.front() || fit.factor == grid.factors.back();
  std::vector<double> refitted;
  for (const auto& a : samples) refitted.push_back(best_factor(grid, a, fit.residual_error));
  fit.error = jackknife_error(refitted);
  fit.start = best_start(grid, fit.amplitude, fit.residual_error, fit.factor);
  fit.fitted = predicted_amplitudes(grid, fit.start, fit.factor);
  fit.unit_factor =
      predicted_amplitudes(grid, best_start(grid, fit.amplitude, fit.residual_error, 1.0), 1.0);
  return fit;
}

}  // namespace granvv::compare
