#include "compare/transport_pair_fit.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "compare/jackknife.hpp"

namespace granvv::compare {
namespace {

constexpr int kScanPoints = 40;            // the coarse scan of each factor over its range
constexpr int kRefitWindow = 4;            // a leave-one-out refit searches +- this many scan steps
constexpr double kFactorTolerance = 1e-9;  // golden-section refinement, relative to the range

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("transport factor pair fit: ") + what);
}

void check_factors(const std::vector<double>& f) {
  require(f.size() >= 2, "needs at least two factors on each axis");
  for (std::size_t j = 1; j < f.size(); ++j) {
    require(f[j] > f[j - 1], "factors must be strictly increasing");
  }
}

// The hydro table of a signal against the grid's shape; its snapshot count.
std::size_t check_hydro(const FactorPairGrid& grid, const PairSignal& g) {
  require(g.hydro.size() == grid.factors_a.size() && !g.hydro.front().empty(),
          "a hydro table not of the grid's shape");
  const std::size_t snapshots = g.hydro.front().front().size();
  require(snapshots > 0, "a signal without snapshots");
  for (const auto& row : g.hydro) {
    require(row.size() == grid.factors_b.size(), "a hydro table not of the grid's shape");
    for (const auto& h : row) {
      require(h.size() == snapshots, "hydro amplitudes of different lengths");
    }
  }
  return snapshots;
}

std::size_t check(const FactorPairGrid& grid, const std::vector<PairSignal>& signals) {
  check_factors(grid.factors_a);
  check_factors(grid.factors_b);
  require(!signals.empty(), "needs at least one signal");
  const std::size_t members = signals.front().members.size();
  require(members >= 2, "needs at least two members");
  std::size_t amplitudes = 0;
  for (const auto& g : signals) {
    require(g.members.size() == members, "signals with different member counts");
    const std::size_t snapshots = check_hydro(grid, g);
    for (const auto& m : g.members) {
      require(m.size() == snapshots, "members and hydro at different snapshots");
    }
    amplitudes += snapshots;
  }
  require(amplitudes >= 4, "needs at least four amplitudes in all");
  return amplitudes;
}

// The Lagrange basis of the nodes x at `at` (a handful of nodes).
std::vector<double> lagrange_basis(const std::vector<double>& x, double at) {
  std::vector<double> basis(x.size(), 1.0);
  for (std::size_t j = 0; j < x.size(); ++j) {
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (i != j) basis[j] *= (at - x[i]) / (x[j] - x[i]);
    }
  }
  return basis;
}

// Every signal's amplitudes laid end to end: the hydro's at each grid point and the members'.
struct Flat {
  std::vector<std::vector<std::vector<double>>> hydro;  // [i][j][k]
  std::vector<std::vector<double>> members;             // [m][k]
  std::vector<std::size_t> offsets;                     // signal g starts at offsets[g]
};

Flat flatten(const FactorPairGrid& grid, const std::vector<PairSignal>& signals) {
  Flat f;
  f.hydro.assign(grid.factors_a.size(), std::vector<std::vector<double>>(grid.factors_b.size()));
  f.members.assign(signals.front().members.size(), {});
  for (const auto& g : signals) {
    f.offsets.push_back(f.members.front().size());
    for (std::size_t i = 0; i < g.hydro.size(); ++i) {
      for (std::size_t j = 0; j < g.hydro[i].size(); ++j) {
        f.hydro[i][j].insert(f.hydro[i][j].end(), g.hydro[i][j].begin(), g.hydro[i][j].end());
      }
    }
    for (std::size_t m = 0; m < g.members.size(); ++m) {
      f.members[m].insert(f.members[m].end(), g.members[m].begin(), g.members[m].end());
    }
  }
  f.offsets.push_back(f.members.front().size());
  return f;
}

class PairObjective {
 public:
  PairObjective(const FactorPairGrid& grid, const Flat& flat) : grid_(grid), flat_(flat) {}

  // H_k(F_a, F_b) for every amplitude k.
  std::vector<double> hydro(double fa, double fb) const {
    const std::vector<double> la = lagrange_basis(grid_.factors_a, fa);
    const std::vector<double> lb = lagrange_basis(grid_.factors_b, fb);
    std::vector<double> h(flat_.offsets.back(), 0.0);
    for (std::size_t i = 0; i < la.size(); ++i) {
      for (std::size_t j = 0; j < lb.size(); ++j) {
        const double w = la[i] * lb[j];
        const std::vector<double>& row = flat_.hydro[i][j];
        for (std::size_t k = 0; k < h.size(); ++k) h[k] += w * row[k];
      }
    }
    return h;
  }

  // lambda of least chi^2: sum w a H / sum w H^2.
  static double best_scale(const std::vector<double>& h, const std::vector<double>& a,
                           const std::vector<double>& sigma) {
    double num = 0.0, den = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      const double w = 1.0 / (sigma[k] * sigma[k]);
      num += w * a[k] * h[k], den += w * h[k] * h[k];
    }
    return den > 0.0 ? num / den : 0.0;
  }

  double chi2(const std::vector<double>& a, const std::vector<double>& sigma, double fa,
              double fb) const {
    const std::vector<double> h = hydro(fa, fb);
    const double scale = best_scale(h, a, sigma);
    double sum = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      const double d = (a[k] - scale * h[k]) / sigma[k];
      sum += d * d;
    }
    return sum;
  }

 private:
  const FactorPairGrid& grid_;
  const Flat& flat_;
};

// The x in [lo, hi] of least f: a scan, golden sections around its best point, the ends as
// candidates (a minimum beyond the range lands there).
double minimise(const std::function<double(double)>& f, double lo, double hi, int scan) {
  const double step = (hi - lo) / scan;
  int best = 0;
  double best_value = f(lo);
  for (int i = 1; i <= scan; ++i) {
    const double v = f(lo + i * step);
    if (v < best_value) best = i, best_value = v;
  }
  double left = lo + std::max(best - 1, 0) * step, right = lo + std::min(best + 1, scan) * step;
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = right - golden * (right - left), x2 = left + golden * (right - left);
  double f1 = f(x1), f2 = f(x2);
  while (right - left > kFactorTolerance * (hi - lo)) {
    if (f1 < f2) {
      right = x2, x2 = x1, f2 = f1;
      x1 = right - golden * (right - left), f1 = f(x1);
    } else {
      left = x1, x1 = x2, f1 = f2;
      x2 = left + golden * (right - left), f2 = f(x2);
    }
  }
  double chosen = 0.5 * (left + right), chosen_value = f(chosen);
  for (double end : {lo, hi}) {
    const double v = f(end);
    if (v < chosen_value) chosen = end, chosen_value = v;
  }
  return chosen;
}

struct Box {
  double a_lo, a_hi, b_lo, b_hi;
};

// (F_a, F_b) of least chi^2 in the box: for each F_a the best F_b, then the best F_a.
std::pair<double, double> best_pair(const PairObjective& objective, const std::vector<double>& a,
                                    const std::vector<double>& sigma, const Box& box, int scan) {
  const auto best_b = [&](double fa) {
    return minimise([&](double fb) { return objective.chi2(a, sigma, fa, fb); }, box.b_lo, box.b_hi,
                    scan);
  };
  const double fa = minimise([&](double x) { return objective.chi2(a, sigma, x, best_b(x)); },
                             box.a_lo, box.a_hi, scan);
  return {fa, best_b(fa)};
}

// The box of a leave-one-out refit: kRefitWindow scan steps around the full fit, in the grid.
Box refit_box(const Box& grid_box, double fa, double fb) {
  const double da = kRefitWindow * (grid_box.a_hi - grid_box.a_lo) / kScanPoints;
  const double db = kRefitWindow * (grid_box.b_hi - grid_box.b_lo) / kScanPoints;
  return {std::max(grid_box.a_lo, fa - da), std::min(grid_box.a_hi, fa + da),
          std::max(grid_box.b_lo, fb - db), std::min(grid_box.b_hi, fb + db)};
}

std::vector<double> residual_errors(const PairObjective& objective,
                                    const std::vector<std::vector<double>>& samples,
                                    const std::vector<double>& sigma, double fa, double fb) {
  const std::vector<double> h = objective.hydro(fa, fb);
  std::vector<std::vector<double>> residuals;
  for (const auto& a : samples) {
    const double scale = PairObjective::best_scale(h, a, sigma);
    std::vector<double> r;
    for (std::size_t k = 0; k < a.size(); ++k) r.push_back(a[k] - scale * h[k]);
    residuals.push_back(std::move(r));
  }
  return jackknife_errors(residuals);
}

std::vector<std::vector<double>> split(const std::vector<double>& flat,
                                       const std::vector<std::size_t>& offsets) {
  std::vector<std::vector<double>> out;
  for (std::size_t g = 0; g + 1 < offsets.size(); ++g) {
    out.emplace_back(flat.begin() + std::ptrdiff_t(offsets[g]),
                     flat.begin() + std::ptrdiff_t(offsets[g + 1]));
  }
  return out;
}

}  // namespace

std::vector<double> predicted_pair_amplitudes(const FactorPairGrid& grid, const PairSignal& signal,
                                              double scale, double factor_a, double factor_b) {
  check_factors(grid.factors_a);
  check_factors(grid.factors_b);
  check_hydro(grid, signal);
  const std::vector<double> la = lagrange_basis(grid.factors_a, factor_a);
  const std::vector<double> lb = lagrange_basis(grid.factors_b, factor_b);
  std::vector<double> p(signal.hydro.front().front().size(), 0.0);
  for (std::size_t i = 0; i < la.size(); ++i) {
    for (std::size_t j = 0; j < lb.size(); ++j) {
      for (std::size_t s = 0; s < p.size(); ++s) {
        p[s] += scale * la[i] * lb[j] * signal.hydro[i][j][s];
      }
    }
  }
  return p;
}

PairFit fit_transport_factor_pair(const FactorPairGrid& grid,
                                  const std::vector<PairSignal>& signals) {
  const std::size_t amplitudes = check(grid, signals);
  const Flat flat = flatten(grid, signals);
  const PairObjective objective(grid, flat);
  const std::vector<std::vector<double>> samples = leave_one_out_means(flat.members);
  const std::vector<double> mean = member_mean(flat.members);
  const std::vector<double> mean_error = jackknife_errors(samples);
  for (double e : mean_error) {
    require(e > 0.0, "an amplitude without scatter over the members (its error is zero)");
  }
  require(grid.b_below >= 0.0, "b_below must not be negative");
  const Box whole = {grid.factors_a.front(), grid.factors_a.back(),
                     grid.factors_b.front() - grid.b_below, grid.factors_b.back()};

  const auto [fa0, fb0] = best_pair(objective, mean, mean_error, whole, kScanPoints);
  const std::vector<double> sigma = residual_errors(objective, samples, mean_error, fa0, fb0);
  const auto [fa, fb] = best_pair(objective, mean, sigma, whole, kScanPoints);

  PairFit fit;
  fit.factor_a = fa, fit.factor_b = fb;
  fit.chi2 = objective.chi2(mean, sigma, fa, fb);
  fit.degrees_of_freedom = int(amplitudes) - 3;  // F_a, F_b and lambda
  fit.at_grid_edge = fa == whole.a_lo || fa == whole.a_hi || fb == whole.b_lo || fb == whole.b_hi;
  const std::vector<double> h = objective.hydro(fa, fb);
  fit.scale = PairObjective::best_scale(h, mean, sigma);

  const Box window = refit_box(whole, fa, fb);
  std::vector<double> refit_a, refit_b;
  for (const auto& a : samples) {
    const auto [ra, rb] = best_pair(objective, a, sigma, window, 2 * kRefitWindow);
    refit_a.push_back(ra), refit_b.push_back(rb);
  }
  fit.error_a = jackknife_error(refit_a);
  fit.error_b = jackknife_error(refit_b);
  fit.correlation = jackknife_correlation(refit_a, refit_b);

  std::vector<double> fitted(h.size());
  for (std::size_t k = 0; k < h.size(); ++k) fitted[k] = fit.scale * h[k];
  fit.amplitude = split(mean, flat.offsets);
  fit.amplitude_error = split(mean_error, flat.offsets);
  fit.residual_error = split(sigma, flat.offsets);
  fit.fitted = split(fitted, flat.offsets);
  return fit;
}

}  // namespace granvv::compare
