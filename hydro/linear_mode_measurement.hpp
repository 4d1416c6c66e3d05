#pragma once
// Measuring the growth rate of a small Fourier mode in a hydro run, for the comparison with
// the dispersion relation of the homogeneous cooling state (hydro/linear_stability.hpp).
#include <complex>
#include <vector>

#include "hydro/closure.hpp"
#include "hydro/lagrangian_state.hpp"

namespace granvv::hydro {

// A seeded eigenmode's measured rate against the dispersion relation, the relative error it is
// judged by (README: the resolved modes of the linear_mode scene agree within 3.6e-4; the tests'
// bound is 1e-3).
inline constexpr double kLinearRateTolerance = 1e-3;

struct MeasuredRate {
  std::complex<double> measured;  // in the collision clock s (hydro/haff.hpp)
  std::complex<double> theory;
  double relative_error = 0.0;  // |measured - theory| / |theory|
  int samples = 0;
};

// Least-squares rate of the chosen eigen-branch coordinate over the snapshots
// (log-modulus and unwrapped phase against s).
MeasuredRate measure_linear_rate(const std::vector<LagrangianState>& snapshots,
                                 const Closure& closure, int k, int branch);

}  // namespace granvv::hydro
