#pragma once
// Initial conditions as continuous fields n(x), v(x), v_y(x), T(x) on [-1/2, 1/2), and their
// discretisation onto the Lagrangian mesh. Each type (cases name it as initial.type) is one
// generator file hydro/initial_<name>.cpp listed in hydro/initial_condition_registry.cpp; it
// declares its own parameters, from which the case schema derives the initial.* keys.
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "hydro/closure.hpp"
#include "hydro/flow_by_inertia.hpp"
#include "hydro/lagrangian_state.hpp"
#include "hydro/parameter_set.hpp"
#include "hydro/physics.hpp"

namespace granvv::hydro {

struct InitialFields {
  std::function<double(double)> n, v, vy, T;
  // Initial velocity profile and its slope when the scene has a smooth one (flow by
  // inertia, paper Eq. 5, uses them); empty otherwise.
  std::function<double(double)> dv;
  // Where the fields' derivatives may jump (a table's rows): the integrals of
  // hydro/field_integrals.hpp split their panels there.
  std::vector<double> breaks;
};

// The homogeneous state n = T = 1, v = v_y = 0 that the generators perturb.
InitialFields uniform_fields();

struct InitialParameters {
  std::string type;     // a registered initial condition (initial.type)
  ParameterSet values;  // every parameter of initial_parameter_specs(), by name
};

// A parameter that is outside what the generator can use, though within its per-key range.
struct ParameterProblem {
  std::string parameter;  // "linear_amplitude"
  std::string reason;     // "a linear mode must be small; allowed: (0, 0.01]"
};

// The exact flow by inertia from the initial velocity (docs/physics.md §3, paper Eq. 5), for
// types whose velocity is a smooth, non-zero profile; collapse errors are in units of
// velocity_scale.
struct InertiaReference {
  FlowByInertia flow;
  double velocity_scale;
};

// The eigenmode of the homogeneous cooling state a type seeds, whose growth rate is measured.
struct SeededEigenmode {
  int mode;
  int branch;
};

// A field that is not finite at a point where it was evaluated: NaN or inf between the points a
// formula or table was checked at (the hydro's nodes, the particle sampler's positions).
struct InitialFieldError : std::invalid_argument {
  InitialFieldError(std::string parameter, const std::string& reason)
      : std::invalid_argument(reason), parameter(std::move(parameter)) {}
  std::string parameter;  // the initial.<parameter> key the field comes from
};

// type and values. Throws std::invalid_argument for an
// unknown type.
InitialParameters initial_parameters(std::string type, ParameterSet values);
// Every field of the result throws InitialFieldError where its value is not finite.
InitialFields make_initial_fields(const InitialParameters& p, const Closure& closure);
// The same with the paper's dilute closure of K, q.
InitialFields make_initial_fields(const InitialParameters& p, const Physics& physics);
// First problem of the parameters: a transverse velocity without transverse_velocity, two
// transverse velocities (initial.transverse_amplitude and the type's own), or a problem the
// type's generator reports.
std::optional<ParameterProblem> initial_parameter_problem(const InitialParameters& p,
                                                          bool transverse_velocity);
std::optional<InertiaReference> inertia_reference(const InitialParameters& p);
std::optional<SeededEigenmode> seeded_eigenmode(const InitialParameters& p);
// The files the fields are read from (empty for a type that reads none).
std::vector<std::string> initial_files(const InitialParameters& p);

// Nodes at x_j = -1/2 + (j + offset)/N (offset 1/2 puts a cell centre at x = 0, where the
// single-mode singularity forms), built so that the state holds the fields' mass, momentum and
// energy (hydro/field_integrals.hpp) to round-off: a cell's mass is the integral of n over it;
// a node's velocity is the momentum of its dual cell (between the neighbouring cell centres)
// over its node mass; a cell's temperature is its energy less half the kinetic energy of each
// of its two nodes, over its mass. (v_y counts only with `transverse`.)
LagrangianState discretize(const InitialFields& fields, int cells, double node_offset,
                           bool transverse);

}  // namespace granvv::hydro
