#include "hydro/initial_condition_registry.hpp"

#include <algorithm>
#include <stdexcept>

namespace granvv::hydro {

// One line per type: hydro/initial_<name>.cpp.
InitialConditionType uniform_initial_condition();
InitialConditionType single_mode_initial_condition();
InitialConditionType random_modes_initial_condition();
InitialConditionType linear_mode_initial_condition();
InitialConditionType expression_initial_condition();
InitialConditionType table_initial_condition();
InitialConditionType snapshot_initial_condition();

const std::vector<InitialConditionType>& initial_condition_types() {
  static const std::vector<InitialConditionType> types = {
      uniform_initial_condition(),      single_mode_initial_condition(),
      random_modes_initial_condition(), linear_mode_initial_condition(),
      expression_initial_condition(),   table_initial_condition(),
      snapshot_initial_condition(),
  };
  return types;
}

const InitialConditionType& find_initial_condition(const std::string& name) {
  for (const auto& type : initial_condition_types()) {
    if (type.name == name) return type;
  }
  throw std::invalid_argument("unknown initial condition " + name);
}

const std::vector<InitialParameterKey>& initial_parameter_keys() {
  static const std::vector<InitialParameterKey> keys = [] {
    std::vector<InitialParameterKey> out;
    for (const auto& type : initial_condition_types()) {
      for (const auto& spec : type.parameters) {
        const auto same = std::find_if(out.begin(), out.end(), [&](const InitialParameterKey& k) {
          return k.spec.name == spec.name;
        });
        if (same == out.end()) {
          out.push_back({spec, {type.name}});
        } else if (same->spec == spec) {
          same->types.push_back(type.name);
        } else {
          throw std::logic_error("initial condition " + type.name + " declares parameter " +
                                 spec.name + " differently from " + same->types.front());
        }
      }
    }
    for (const auto& spec : common_initial_parameters()) out.push_back({spec, {}});
    return out;
  }();
  return keys;
}

}  // namespace granvv::hydro
