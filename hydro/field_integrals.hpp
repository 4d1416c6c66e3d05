#pragma once
// Integrals of the initial fields over the period [-1/2, 1/2): the mass, momenta and energy the
// fields hold (docs/physics.md §1: n T is the thermal energy density in 2D), by Gauss-Legendre
// quadrature on panels that end at the fields' breaks (a table's rows, where an interpolant's
// derivatives jump), so that a piecewise polynomial of degree up to 9 (n v^2 of a cubic
// interpolant) is integrated exactly. The hydro's initial cells are built from the same
// integrals (hydro/initial_conditions.hpp, discretize), and the summary states both.
#include <vector>

#include "hydro/initial_conditions.hpp"

namespace granvv::hydro {

struct FieldTotals {
  double mass = 0.0;        // integral of n
  double momentum_x = 0.0;  // integral of n v_x
  double momentum_y = 0.0;  // integral of n v_y (0 without a transverse velocity)
  double energy = 0.0;      // integral of n (T + (v_x^2 + v_y^2) / 2)
};

// The fields' breaks wrapped into [-1/2, 1/2) and sorted.
std::vector<double> sorted_breaks(const InitialFields& fields);

// The totals of the fields over [a, b] (a < b, positions unwrapped, at most one period), by
// 5-point Gauss-Legendre on the panels between the breaks (`breaks`: sorted_breaks(fields))
// inside (a, b); v_y counts only with `transverse`.
FieldTotals totals_between(const InitialFields& fields, double a, double b,
                           const std::vector<double>& breaks, bool transverse);

// The totals over the period, on `panels` equal panels split further at the breaks.
inline constexpr int kTotalPanels = 4096;
FieldTotals field_totals(const InitialFields& fields, bool transverse, int panels = kTotalPanels);

// The mean density over the period: the mass of the fields, by the panels above.
double mean_density(const InitialFields& fields);

// |a - b| relative to the scale of the totals, quantity by quantity (mass, momentum: relative
// to sqrt(2 mass energy), a momentum scale that is not 0 when the momentum is; energy): the
// largest of them.
double largest_relative_difference(const FieldTotals& a, const FieldTotals& b);

}  // namespace granvv::hydro
