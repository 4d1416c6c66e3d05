#include "compare/binned_fields.hpp"

#include <cmath>
#include <stdexcept>

namespace granvv::compare {

fields::FieldSnapshot bin_lagrangian_state(const hydro::LagrangianState& s, int bins) {
  if (bins < 1) throw std::invalid_argument("bin_lagrangian_state: bins must be >= 1");
  const int cells = s.cells();
  if (cells < 1) throw std::invalid_argument("bin_lagrangian_state: the state has no cells");
  const bool transverse = s.has_transverse();
  std::vector<double> mass(bins, 0.0), px(bins, 0.0), py(bins, 0.0), thermal(bins, 0.0),
      mv2(bins, 0.0);
  for (int i = 0; i < cells; ++i) {
    const int j = (i + 1) % cells;
    const double xa = s.node_x[i];
    const double xb = i + 1 < cells ? s.node_x[j] : s.node_x[0] + 1.0;
    const double width = xb - xa;
    const double n = s.cell_mass[i] / width;
    const double va = s.node_v[i], vb = s.node_v[j];
    const double wa = transverse ? s.node_vy[i] : 0.0, wb = transverse ? s.node_vy[j] : 0.0;
    // Bin coordinate u = (x + 1/2) bins; the cell covers [ua, ub], wrapped periodically.
    const double ua = (xa + 0.5) * bins, ub = (xb + 0.5) * bins;
    for (double lo = ua; lo < ub;) {
      const double cell_of_lo = std::floor(lo);
      const double hi = std::min(ub, cell_of_lo + 1.0);
      const int b = ((static_cast<long long>(cell_of_lo) % bins) + bins) % bins;
      const double length = (hi - lo) / bins;  // in x
      // Linear velocity: exact means of v and v^2 over [lo, hi] from its end values (Simpson).
      const double fa = (lo - ua) / (ub - ua), fb = (hi - ua) / (ub - ua);
      const double v1 = va + (vb - va) * fa, v2 = va + (vb - va) * fb;
      const double w1 = wa + (wb - wa) * fa, w2 = wa + (wb - wa) * fb;
      const double m = n * length;
      mass[b] += m;
      px[b] += m * 0.5 * (v1 + v2);
      py[b] += m * 0.5 * (w1 + w2);
      mv2[b] += m * (v1 * v1 + v1 * v2 + v2 * v2 + w1 * w1 + w1 * w2 + w2 * w2) / 3.0;
      thermal[b] += m * s.cell_T[i];
      lo = hi;
    }
  }
  fields::FieldSnapshot f;
  const double dx = 1.0 / bins;
  for (int b = 0; b < bins; ++b) {
    f.x.push_back(-0.5 + (b + 0.5) * dx);
    f.n.push_back(mass[b] / dx);
    const double vx = px[b] / mass[b], vy = py[b] / mass[b];
    f.v_x.push_back(vx);
    f.v_y.push_back(vy);
    const double sub_bin_flow = 0.5 * (mv2[b] - mass[b] * (vx * vx + vy * vy));
    f.T.push_back((thermal[b] + std::max(0.0, sub_bin_flow)) / mass[b]);
  }
  return f;
}

std::function<double(double)> bin_interpolant(std::vector<double> values) {
  if (values.empty()) throw std::invalid_argument("bin_interpolant: no values");
  return [values = std::move(values)](double x) {
    const int bins = static_cast<int>(values.size());
    const double u = (x + 0.5) * bins - 0.5;  // 0 at the first bin centre
    const double lower = std::floor(u);
    const double f = u - lower;
    const int i = static_cast<int>(((static_cast<long long>(lower) % bins) + bins) % bins);
    return (1.0 - f) * values[i] + f * values[(i + 1) % bins];
  };
}

hydro::LagrangianState flow_by_inertia_state(const hydro::InitialFields& initial, double t,
                                             int labels) {
  if (labels < 2) throw std::invalid_argument("flow_by_inertia_state: labels must be >= 2");
  hydro::LagrangianState s;
  s.t = t;
  const double d = 1.0 / labels;
  for (int j = 0; j < labels; ++j) {
    const double xi = -0.5 + j * d;
    s.node_xi.push_back(xi);
    s.node_x.push_back(xi + t * initial.v(xi));
    s.node_v.push_back(initial.v(xi));
    // Cell mass by the midpoint rule on the label grid (mass is carried with the label).
    const double mid = xi + 0.5 * d;
    s.cell_mass.push_back(initial.n(mid) * d);
    s.cell_T.push_back(initial.T(mid));
  }
  return s;
}

}  // namespace granvv::compare
