#include "hydro/field_integrals.hpp"

#include <algorithm>
#include <cmath>

namespace granvv::hydro {
namespace {

// 5-point Gauss-Legendre on [-1, 1]: exact for polynomials of degree 9.
constexpr double kNodes[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                              0.9061798459386640};
constexpr double kWeights[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                0.4786286704993665, 0.2369268850561891};

void add_panel(const InitialFields& f, double a, double b, bool transverse, FieldTotals& t) {
  const double centre = 0.5 * (a + b), half = 0.5 * (b - a);
  for (int k = 0; k < 5; ++k) {
    const double u = centre + half * kNodes[k], w = half * kWeights[k];
    const double x = u - std::floor(u + 0.5);  // the fields are given on [-1/2, 1/2)
    const double n = f.n(x), v = f.v(x), vy = transverse && f.vy ? f.vy(x) : 0.0;
    t.mass += w * n;
    t.momentum_x += w * n * v;
    t.momentum_y += w * n * vy;
    t.energy += w * n * (f.T(x) + 0.5 * (v * v + vy * vy));
  }
}

}  // namespace

std::vector<double> sorted_breaks(const InitialFields& fields) {
  std::vector<double> out = {-0.5};  // where a formula's periodic continuation is joined
  for (const double x : fields.breaks) out.push_back(x - std::floor(x + 0.5));
  std::sort(out.begin(), out.end());
  return out;
}

FieldTotals totals_between(const InitialFields& f, double a, double b,
                           const std::vector<double>& breaks, bool transverse) {
  std::vector<double> cuts = {a};
  // The breaks inside (a, b), in the period of a and the next one.
  for (const double shift : {std::floor(a + 0.5), std::floor(a + 0.5) + 1.0}) {
    auto it = std::upper_bound(breaks.begin(), breaks.end(), a - shift);
    for (; it != breaks.end() && *it + shift < b; ++it) cuts.push_back(*it + shift);
  }
  cuts.push_back(b);
  FieldTotals t;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    if (cuts[i + 1] > cuts[i]) add_panel(f, cuts[i], cuts[i + 1], transverse, t);
  }
  return t;
}

FieldTotals field_totals(const InitialFields& f, bool transverse, int panels) {
  const std::vector<double> breaks = sorted_breaks(f);
  FieldTotals t;
  for (int i = 0; i < panels; ++i) {
    const FieldTotals p = totals_between(f, -0.5 + double(i) / panels,
                                         -0.5 + double(i + 1) / panels, breaks, transverse);
    t.mass += p.mass;
    t.momentum_x += p.momentum_x;
    t.momentum_y += p.momentum_y;
    t.energy += p.energy;
  }
  return t;
}

double mean_density(const InitialFields& fields) {
  const std::vector<double> breaks = sorted_breaks(fields);
  InitialFields n_only = uniform_fields();
  n_only.n = fields.n;
  double mass = 0.0;
  for (int i = 0; i < kTotalPanels; ++i) {
    const double a = -0.5 + double(i) / kTotalPanels, b = -0.5 + double(i + 1) / kTotalPanels;
    mass += totals_between(n_only, a, b, breaks, false).mass;
  }
  return mass;
}

double largest_relative_difference(const FieldTotals& a, const FieldTotals& b) {
  const double momentum_scale = std::sqrt(2.0 * std::abs(b.mass * b.energy));
  const auto relative = [](double x, double y, double scale) {
    return x == y ? 0.0 : std::abs(x - y) / scale;
  };
  return std::max({relative(a.mass, b.mass, std::abs(b.mass)),
                   relative(a.momentum_x, b.momentum_x, momentum_scale),
                   relative(a.momentum_y, b.momentum_y, momentum_scale),
                   relative(a.energy, b.energy, std::abs(b.energy))});
}

}  // namespace granvv::hydro
