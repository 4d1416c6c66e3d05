#include "hydro/initial_conditions.hpp"

#include <cmath>
#include <utility>

#include "fields/constants.hpp"
#include "hydro/dilute_closure.hpp"
#include "hydro/initial_condition_registry.hpp"

namespace granvv::hydro {
InitialFields uniform_fields() {
  InitialFields f;
  f.n = [](double) { return 1.0; };
  f.v = [](double) { return 0.0; };
  f.dv = [](double) { return 0.0; };
  f.vy = [](double) { return 0.0; };
  f.T = [](double) { return 1.0; };
  return f;
}

// Any scene may add a transverse velocity v_y = b cos(2 pi k_y x): the shear mode whose growth
// in a long box the 1D model leaves out unless v_y is carried (docs/physics.md §6).
const std::vector<ParameterSpec>& common_initial_parameters() {
  static const std::vector<ParameterSpec> parameters = {
      {"transverse_amplitude", 0.0, ParameterRange::any(),
       "amplitude b of a transverse velocity v_y = b cos(2 pi k_y x) (needs "
       "hydro.transverse_velocity)"},
      {"transverse_mode", 1LL, ParameterRange::at_least(1), "mode k_y of the transverse velocity"},
  };
  return parameters;
}

InitialParameters initial_parameters(std::string type, ParameterSet values) {
  find_initial_condition(type);  // an unknown type is refused here, not at first use
  InitialParameters p;
  p.type = std::move(type);
  p.values = std::move(values);
  return p;
}

InitialFields make_initial_fields(const InitialParameters& p, const Physics& physics) {
  return make_initial_fields(p, DiluteClosure(physics));
}

InitialFields make_initial_fields(const InitialParameters& p, const Closure& closure) {
  InitialFields f = find_initial_condition(p.type).generate(p.values, closure);
  const double b = p.values.real("transverse_amplitude");
  if (b != 0.0) {
    const double ky = 2.0 * kPi * p.values.integer("transverse_mode");
    f.vy = [b, ky](double x) { return b * std::cos(ky * x); };
  }
  return f;
}

std::optional<ParameterProblem> initial_parameter_problem(const InitialParameters& p,
                                                          bool transverse_velocity) {
  if (p.values.real("transverse_amplitude") != 0.0 && !transverse_velocity) {
    return ParameterProblem{"transverse_amplitude",
                            "a transverse velocity needs hydro.transverse_velocity = true"};
  }
  const auto& type = find_initial_condition(p.type);
  for (const auto& spec : type.parameters) {  // a formula for v_y (initial.type = "expression")
    if (spec.name == "transverse_velocity" && !transverse_velocity &&
        p.values.text(spec.name) != "0") {
      return ParameterProblem{spec.name,
                              "a transverse velocity needs hydro.transverse_velocity = true"};
    }
  }
  return type.problem ? type.problem(p.values) : std::nullopt;
}

std::optional<InertiaReference> inertia_reference(const InitialParameters& p) {
  const auto& reference = find_initial_condition(p.type).inertia_reference;
  return reference ? reference(p.values) : std::nullopt;
}

std::optional<SeededEigenmode> seeded_eigenmode(const InitialParameters& p) {
  const auto& seeded = find_initial_condition(p.type).seeded_eigenmode;
  return seeded ? seeded(p.values) : std::nullopt;
}

std::vector<std::string> initial_files(const InitialParameters& p) {
  const auto& files = find_initial_condition(p.type).files;
  return files ? files(p.values) : std::vector<std::string>{};
}

LagrangianState discretize(const InitialFields& f, int cells, double node_offset, bool transverse) {
  static const double gauss_x[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  static const double gauss_w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  LagrangianState s;
  const double h = 1.0 / cells;
  for (int j = 0; j < cells; ++j) {
    const double x = -0.5 + (j + node_offset) * h;
    s.node_x.push_back(x);
    s.node_xi.push_back(x);
    s.node_v.push_back(f.v(x));
    if (transverse) s.node_vy.push_back(f.vy(x));
  }
  for (int i = 0; i < cells; ++i) {
    const double centre = s.node_x[i] + 0.5 * h;
    double mass = 0.0, energy = 0.0;
    for (int g = 0; g < 3; ++g) {
      const double x = centre + 0.5 * h * gauss_x[g];
      const double n = f.n(x);
      mass += 0.5 * h * gauss_w[g] * n;
      energy += 0.5 * h * gauss_w[g] * n * f.T(x);
    }
    s.cell_mass.push_back(mass);
    s.cell_T.push_back(energy / mass);
  }
  return s;
}

}  // namespace granvv::hydro
