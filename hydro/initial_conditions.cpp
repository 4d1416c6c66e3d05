#include "hydro/initial_conditions.hpp"

#include <cmath>
#include <sstream>
#include <utility>

#include "fields/constants.hpp"
#include "hydro/dilute_closure.hpp"
#include "hydro/field_integrals.hpp"
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

namespace {

// f, throwing InitialFieldError where its value is not finite.
std::function<double(double)> finite_only(std::function<double(double)> f, std::string field,
                                          std::string parameter) {
  return [f = std::move(f), field = std::move(field), parameter = std::move(parameter)](double x) {
    const double value = f(x);
    if (!std::isfinite(value)) {
      std::ostringstream why;
      why.precision(10);
      why << "the initial " << field << " is " << value << " at x = " << x
          << " (allowed: a finite value at every x, also between the points it was checked at)";
      throw InitialFieldError(parameter, why.str());
    }
    return value;
  };
}

std::string or_type(const std::string& parameter) {
  return parameter.empty() ? "type" : parameter;
}

}  // namespace

InitialFields make_initial_fields(const InitialParameters& p, const Closure& closure) {
  const InitialConditionType& type = find_initial_condition(p.type);
  InitialFields f = type.generate(p.values, closure);
  const auto& keys = type.field_parameters;
  std::string vy_parameter = or_type(keys.vy);
  const double b = p.values.real("transverse_amplitude");
  if (b != 0.0) {
    const double ky = 2.0 * kPi * p.values.integer("transverse_mode");
    f.vy = [b, ky](double x) { return b * std::cos(ky * x); };
    vy_parameter = "transverse_amplitude";
  }
  f.n = finite_only(std::move(f.n), "density", or_type(keys.n));
  f.v = finite_only(std::move(f.v), "velocity", or_type(keys.v));
  f.T = finite_only(std::move(f.T), "temperature", or_type(keys.T));
  if (f.vy) f.vy = finite_only(std::move(f.vy), "transverse velocity", vy_parameter);
  return f;
}

std::optional<ParameterProblem> initial_parameter_problem(const InitialParameters& p,
                                                          bool transverse_velocity) {
  const bool amplitude = p.values.real("transverse_amplitude") != 0.0;
  if (amplitude && !transverse_velocity) {
    return ParameterProblem{"transverse_amplitude",
                            "a transverse velocity needs hydro.transverse_velocity = true"};
  }
  const auto& type = find_initial_condition(p.type);
  if (auto problem = type.problem ? type.problem(p.values) : std::nullopt) return problem;
  // The type's own v_y: a formula (initial.transverse_velocity) or a table's v_y column.
  if (type.has_transverse_velocity && type.has_transverse_velocity(p.values)) {
    const std::string own = or_type(type.field_parameters.vy);
    const std::string what = own == "from" ? "the v_y column of initial.from" : "initial." + own;
    if (amplitude) {
      return ParameterProblem{"transverse_amplitude",
                              "initial.transverse_amplitude and " + what +
                                  " both set the transverse velocity (allowed: one of them; set "
                                  "initial.transverse_amplitude = 0 to keep " +
                                  what + ")"};
    }
    if (!transverse_velocity) {
      return ParameterProblem{own, what +
                                       " gives a transverse velocity v_y, which needs "
                                       "hydro.transverse_velocity = true"};
    }
  }
  return std::nullopt;
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
  const std::vector<double> breaks = sorted_breaks(f);
  LagrangianState s;
  const double h = 1.0 / cells;
  for (int j = 0; j < cells; ++j) {
    const double x = -0.5 + (j + node_offset) * h;
    s.node_x.push_back(x);
    s.node_xi.push_back(x);
  }
  // The cells' halves: [x_i, centre_i] and [centre_i, x_i+1].
  std::vector<FieldTotals> left(cells), right(cells);
  for (int i = 0; i < cells; ++i) {
    const double a = s.node_x[i], centre = a + 0.5 * h, b = a + h;
    left[i] = totals_between(f, a, centre, breaks, transverse);
    right[i] = totals_between(f, centre, b, breaks, transverse);
    s.cell_mass.push_back(left[i].mass + right[i].mass);
  }
  std::vector<double> kinetic(cells);  // of node j
  for (int j = 0; j < cells; ++j) {
    const int before = j == 0 ? cells - 1 : j - 1;
    const double mu = node_mass(s, j);
    const double v = (right[before].momentum_x + left[j].momentum_x) / mu;
    s.node_v.push_back(v);
    kinetic[j] = 0.5 * mu * v * v;
    if (transverse) {
      const double vy = (right[before].momentum_y + left[j].momentum_y) / mu;
      s.node_vy.push_back(vy);
      kinetic[j] += 0.5 * mu * vy * vy;
    }
  }
  for (int i = 0; i < cells; ++i) {
    const double energy = left[i].energy + right[i].energy;
    const double thermal = energy - 0.5 * (kinetic[i] + kinetic[(i + 1) % cells]);
    s.cell_T.push_back(thermal / s.cell_mass[i]);
  }
  return s;
}

}  // namespace granvv::hydro
