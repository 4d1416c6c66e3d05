#pragma once
// How far a run's mean temperature strays from Haff's law (hydro/haff.hpp; docs/physics.md §2).
// A homogeneous gas cools exactly as T_H(t) = (1 + t/t0)^{-2}; the mass-weighted mean T of a
// run follows it until clusters or a steepening flow make the cooling rate n T^{3/2} uneven.
#include <vector>

namespace granvv::hydro {

// max_i |T_mean_i / T_H(t_i) - 1| over the samples (0 for none), with t0 = K/(4q)
// (haff_time_scale; +inf: no cooling, T_H = 1).
double haff_max_relative_error(const std::vector<double>& t, const std::vector<double>& T_mean,
                               double t0);

}  // namespace granvv::hydro
