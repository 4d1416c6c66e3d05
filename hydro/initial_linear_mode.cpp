// A small eigenmode of the linearised equations around the homogeneous cooling state
// (docs/physics.md §2): (nu, w, theta) = amplitude * Re(V e^{i kx x}) with V the eigenvector of
// the chosen branch; the run measures its growth rate against the dispersion relation.
#include <complex>

#include "fields/constants.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "hydro/linear_stability.hpp"

namespace granvv::hydro {

InitialConditionType linear_mode_initial_condition() {
  InitialConditionType type;
  type.name = "linear_mode";
  type.parameters = {
      {"mode", 1LL, ParameterRange::at_least(1), "wave number k"},
      {"linear_amplitude", 1e-6, ParameterRange::greater_than(0),
       "amplitude of the linear eigenmode"},
      {"linear_branch", 0LL, ParameterRange::closed(0, 2), "eigenvalue branch, 0 = most unstable"},
  };
  type.generate = [](const ParameterSet& p, const Closure& closure) {
    const int mode = static_cast<int>(p.integer("mode"));
    const auto modes = hcs_modes(closure, mode);
    const Eigen::Vector3cd V =
        modes.at(p.integer("linear_branch")).eigenvector * p.real("linear_amplitude");
    const double kx = 2.0 * kPi * mode;
    auto component = [kx](std::complex<double> c) {
      return
          [c, kx](double x) { return std::real(c * std::exp(std::complex<double>(0.0, kx * x))); };
    };
    InitialFields f = uniform_fields();
    auto nu = component(V[0]), w = component(V[1]), theta = component(V[2]);
    f.n = [nu](double x) { return 1.0 + nu(x); };
    f.v = w;  // T_H(0) = 1, so u = w at t = 0
    f.dv = [V, kx](double x) {
      return std::real(std::complex<double>(0.0, kx) * V[1] *
                       std::exp(std::complex<double>(0.0, kx * x)));
    };
    f.T = [theta](double x) { return 1.0 + theta(x); };
    return f;
  };
  // The measured rate is that of linear theory only while the mode stays small.
  type.problem = [](const ParameterSet& p) -> std::optional<ParameterProblem> {
    if (p.real("linear_amplitude") <= 1e-2) return std::nullopt;
    return ParameterProblem{"linear_amplitude", "a linear mode must be small; allowed: (0, 0.01]"};
  };
  type.seeded_eigenmode = [](const ParameterSet& p) {
    return std::optional<SeededEigenmode>(
        {static_cast<int>(p.integer("mode")), static_cast<int>(p.integer("linear_branch"))});
  };
  return type;
}

}  // namespace granvv::hydro
