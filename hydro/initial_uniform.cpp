// The homogeneous cooling state itself: n = T = 1, v = 0 (Haff's law, docs/physics.md §2).
#include "hydro/initial_condition_registry.hpp"

namespace granvv::hydro {

InitialConditionType uniform_initial_condition() {
  InitialConditionType type;
  type.name = "uniform";
  type.generate = [](const ParameterSet&, const Closure&) { return uniform_fields(); };
  return type;
}

}  // namespace granvv::hydro
