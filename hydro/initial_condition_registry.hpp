#pragma once
// The registry of initial-condition types. A type is one file hydro/initial_<name>.cpp that
// defines `InitialConditionType <name>_initial_condition()` and one line of the table in
// hydro/initial_condition_registry.cpp (an explicit table: self-registering objects in a static
// library are dropped by the linker when nothing references them).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "hydro/initial_conditions.hpp"

namespace granvv::hydro {

struct InitialConditionType {
  std::string name;                       // initial.type
  std::vector<ParameterSpec> parameters;  // the initial.<name> keys it reads
  // The fields from the parameters; the closure supplies what a type needs of the hydro's
  // physics (linear_mode: the eigenvector of its homogeneous-cooling theory).
  std::function<InitialFields(const ParameterSet&, const Closure&)> generate;
  // Optional: a problem beyond the per-key ranges.
  std::function<std::optional<ParameterProblem>(const ParameterSet&)> problem;
  // Optional: the flow-by-inertia reference of a smooth initial velocity.
  std::function<std::optional<InertiaReference>(const ParameterSet&)> inertia_reference;
  // Optional: the eigenmode of the cooling state it seeds.
  std::function<std::optional<SeededEigenmode>(const ParameterSet&)> seeded_eigenmode;
  // Optional: the files its fields are read from (their paths and checksums go into
  // summary.json for provenance).
  std::function<std::vector<std::string>(const ParameterSet&)> files;
  // The parameters whose values make n, v_x, v_y and T, named when a field is not finite
  // where it is evaluated (empty: "type", a field the type computes from its numbers).
  struct FieldParameters {
    std::string n, v, vy, T;
  } field_parameters;
  // Optional: whether the parameters give a transverse velocity v_y (a formula other than "0",
  // a table's v_y column that is not all zero); without it, the type gives none.
  std::function<bool(const ParameterSet&)> has_transverse_velocity;
};

// In table order: uniform, single_mode, random_modes, linear_mode, expression, table, snapshot.
const std::vector<InitialConditionType>& initial_condition_types();
// Throws std::invalid_argument for an unknown name.
const InitialConditionType& find_initial_condition(const std::string& name);

// A parameter of the union of all types, with the types that read it.
struct InitialParameterKey {
  ParameterSpec spec;
  std::vector<std::string> types;  // empty: applies to every type (the transverse velocity)
};
// Every parameter once, in order of first declaration, then the common ones. A parameter that
// two types declare must be declared identically (std::logic_error otherwise).
const std::vector<InitialParameterKey>& initial_parameter_keys();

// The parameters every type accepts: a transverse velocity v_y = b cos(2 pi k_y x).
const std::vector<ParameterSpec>& common_initial_parameters();

}  // namespace granvv::hydro
