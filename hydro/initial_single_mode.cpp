// Paper Eq. (7): n = T = 1, v = a sin(2 pi k x); its flow by inertia (paper Eq. 5) is exact.
#include <cmath>

#include "fields/constants.hpp"
#include "hydro/initial_condition_registry.hpp"

namespace granvv::hydro {

InitialConditionType single_mode_initial_condition() {
  InitialConditionType type;
  type.name = "single_mode";
  type.parameters = {
      {"velocity_amplitude", -0.05, ParameterRange::any(), "v = a sin(2 pi mode x), amplitude a"},
      {"mode", 1LL, ParameterRange::at_least(1), "wave number k"},
  };
  type.generate = [](const ParameterSet& p, const Closure&) {
    InitialFields f = uniform_fields();
    const double a = p.real("velocity_amplitude"), kx = 2.0 * kPi * p.integer("mode");
    f.v = [a, kx](double x) { return a * std::sin(kx * x); };
    f.dv = [a, kx](double x) { return a * kx * std::cos(kx * x); };
    return f;
  };
  type.inertia_reference = [](const ParameterSet& p) -> std::optional<InertiaReference> {
    const double a = p.real("velocity_amplitude");
    if (a == 0.0) return std::nullopt;
    return InertiaReference{FlowByInertia::single_mode(a, static_cast<int>(p.integer("mode"))),
                            std::abs(a)};
  };
  return type;
}

}  // namespace granvv::hydro
