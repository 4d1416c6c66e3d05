#pragma once
// Measuring the growth rate of a small Fourier mode in a hydro run, for the comparison with
// the dispersion relation of the homogeneous cooling state (hydro/linear_stability.hpp).
#include <Eigen/Dense>
#include <complex>
#include <vector>

#include "hydro/closure.hpp"
#include "hydro/lagrangian_state.hpp"

namespace granvv::hydro {

// Complex Fourier amplitudes (nu, w, theta) of mode k, X(x) = Re(X_k e^{i 2 pi k x}), with
// n = 1 + nu, v = T_H^{1/2} w, T = T_H (1 + theta) and T_H Haff's law at the state's time.
// Cell fields are integrated exactly over each cell; node velocities by the midpoint rule.
Eigen::Vector3cd hcs_mode_amplitudes(const LagrangianState& s, const Closure& closure, int k);

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
