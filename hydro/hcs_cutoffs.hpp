#pragma once
// The cut-off modes of the homogeneous cooling state from a linearisation's coefficients, by the
// general criteria of hydro/linear_stability.hpp (k = kx / (2 pi)): the clustering mode grows
// while p_n (kappa kx^2 + Lambda_T') < p_T (Lambda_n + mu kx^2), i.e. while
// (kappa - mu p_T/p_n) kx^2 < p_T Lambda_n/p_n - Lambda_T' (every short wave clusters, no
// cutoff, should mu p_T/p_n reach kappa), the shear mode while eta_xy kx^2 < eps. The same
// rule for every closure that computes its cutoffs from its coefficients (ScaledClosure,
// FormulaClosure).
#include <cmath>
#include <limits>

#include "fields/constants.hpp"
#include "hydro/closure.hpp"

namespace granvv::hydro {

inline void set_cutoff_modes(HcsLinearisation& h) {
  const double pressure_balanced_conductivity =
      h.conductivity - h.mu * h.pressure_temperature / h.pressure_density;
  const double clustering =
      (h.pressure_temperature * h.cooling_density / h.pressure_density - h.cooling_temperature) /
      pressure_balanced_conductivity;
  h.clustering_cutoff_mode = !(pressure_balanced_conductivity > 0.0)
                                 ? std::numeric_limits<double>::infinity()
                             : clustering > 0 ? std::sqrt(clustering) / kTwoPi
                                              : 0.0;
  h.shear_cutoff_mode = std::sqrt(h.epsilon / h.shear_viscosity) / kTwoPi;
}

}  // namespace granvv::hydro
