#include "compare/pressure_comparison.hpp"

#include <cmath>
#include <cstddef>
#include <limits>

namespace granvv::compare {

std::vector<double> normal_pressure(const std::vector<double>& xx, const std::vector<double>& yy) {
  std::vector<double> p;
  for (std::size_t i = 0; i < xx.size(); ++i) p.push_back(0.5 * (xx[i] + yy[i]));
  return p;
}

std::vector<double> normal_pressure_error(const std::vector<double>& xx_error,
                                          const std::vector<double>& yy_error) {
  std::vector<double> e;
  for (std::size_t i = 0; i < xx_error.size(); ++i) {
    e.push_back(0.5 * std::hypot(xx_error[i], yy_error[i]));
  }
  return e;
}

std::vector<double> closure_pressure_md(const hydro::Closure& closure, const std::vector<double>& n,
                                        const std::vector<double>& T, double n0) {
  std::vector<double> out(n.size(), std::numeric_limits<double>::quiet_NaN());
  std::vector<double> ns, Ts;
  std::vector<std::size_t> at;
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (std::isfinite(n[i]) && std::isfinite(T[i]) && n[i] > 0 && T[i] > 0) {
      ns.push_back(n[i] / n0), Ts.push_back(T[i]), at.push_back(i);
    }
  }
  hydro::CellCoefficients c;
  closure.cell_coefficients(ns, Ts, c);
  for (std::size_t k = 0; k < at.size(); ++k) out[at[k]] = c.pressure[k] * n0;
  return out;
}

}  // namespace granvv::compare
