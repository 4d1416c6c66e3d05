#pragma once
// The particles' pressure against a closure's equation of state (docs/physics.md §9): the
// measured pressure of a 2D gas is the mean normal stress (P_xx + P_yy)/2, the closure's is
// p(n, T) evaluated at the measured density and temperature.
#include <vector>

#include "hydro/closure.hpp"

namespace granvv::compare {

// (P_xx + P_yy)/2, element by element (xx and yy of the same length).
std::vector<double> normal_pressure(const std::vector<double>& xx, const std::vector<double>& yy);
// Its standard error from those of P_xx and P_yy taken as independent, hypot(s_xx, s_yy)/2.
std::vector<double> normal_pressure_error(const std::vector<double>& xx_error,
                                          const std::vector<double>& yy_error);

// The closure's pressure in MD units at MD densities n and temperatures T: scaled n = n_md / n0,
// T unchanged (T0 = 1), p_md = p n0; NaN where n or T is not finite and positive.
std::vector<double> closure_pressure_md(const hydro::Closure& closure, const std::vector<double>& n,
                                        const std::vector<double>& T, double n0);

}  // namespace granvv::compare
