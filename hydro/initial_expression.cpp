// The user's own profiles as formulas in x on [-1/2, 1/2): initial.density, initial.velocity,
// initial.temperature and initial.transverse_velocity, with pi and the named constants of
// [initial.constants] (hydro/formula.hpp). Checked before anything runs: syntax, finite values,
// n > 0 and T > 0 on a fine sample, and periodicity of values and slopes at x = +-1/2.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "hydro/central_difference.hpp"
#include "hydro/field_integrals.hpp"
#include "hydro/formula.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "hydro/profile_table.hpp"

namespace granvv::hydro {
namespace {

// The sample the checks use: kSamples + 1 equispaced points of [-1/2, 1/2].
constexpr int kSamples = 8192;
// Periodicity: |f(1/2) - f(-1/2)| <= kValueTolerance max|f|, and the one-sided slopes (second
// order, step kSlopeStep) differ by at most kSlopeTolerance max(max|f'|, max|f|). A smooth
// periodic profile with wave numbers up to ~50 passes the slope test by a factor of 10.
constexpr double kValueTolerance = 1e-6;
constexpr double kSlopeTolerance = 1e-3;
constexpr double kSlopeStep = 1e-4;

struct FieldKey {
  const char* name;  // the parameter
  bool positive;     // n and T
};
constexpr FieldKey kFields[] = {
    {"density", true}, {"velocity", false}, {"temperature", true}, {"transverse_velocity", false}};

std::string number(double x) {
  std::ostringstream os;
  os.precision(6);
  os << x;
  return os.str();
}

// The first problem of one sampled formula, or nullopt.
std::optional<std::string> sample_problem(const Formula& f, bool positive) {
  double largest = 0.0, steepest = 0.0, previous = 0.0;
  for (int i = 0; i <= kSamples; ++i) {
    const double x = -0.5 + double(i) / kSamples;
    const double y = f(x);
    if (!std::isfinite(y))
      return "is not finite at x = " + number(x) + " (value " + number(y) + ")";
    if (positive && !(y > 0.0)) {
      return "must be > 0 at every x, but is " + number(y) + " at x = " + number(x);
    }
    largest = std::max(largest, std::abs(y));
    if (i > 0) steepest = std::max(steepest, std::abs(y - previous) * kSamples);
    previous = y;
  }
  const double left = f(-0.5), right = f(0.5);
  if (std::abs(right - left) > kValueTolerance * largest) {
    return "is not periodic: " + number(left) + " at x = -1/2, " + number(right) +
           " at x = 1/2 (allowed: equal within " + number(kValueTolerance) + " of max |value|)";
  }
  const double h = kSlopeStep;
  const double slope_left = (-3.0 * left + 4.0 * f(-0.5 + h) - f(-0.5 + 2.0 * h)) / (2.0 * h);
  const double slope_right = (3.0 * right - 4.0 * f(0.5 - h) + f(0.5 - 2.0 * h)) / (2.0 * h);
  if (!std::isfinite(slope_left) || !std::isfinite(slope_right) ||
      std::abs(slope_right - slope_left) > kSlopeTolerance * std::max(steepest, largest)) {
    return "is not periodic: slope " + number(slope_left) + " at x = -1/2, " + number(slope_right) +
           " at x = 1/2 (allowed: equal within " + number(kSlopeTolerance) + " of max |slope|)";
  }
  return std::nullopt;
}

Formula formula(const ParameterSet& p, const char* name) {
  return Formula(p.text(name), p.named_reals("constants"));
}

// v'(x) by fourth-order central differences, for flow by inertia: truncation h^4 |v^(5)|/30
// and round-off ~eps |v| / h, both ~1e-12 relative for a single mode.
std::function<double(double)> derivative(const Formula& f) {
  return [f](double x) {
    constexpr double h = 1e-4;
    return central_derivative(f, x, h);
  };
}

}  // namespace

InitialConditionType expression_initial_condition() {
  InitialConditionType type;
  type.name = "expression";
  const std::string in_x = " as a formula in x on [-1/2, 1/2), with pi and [initial.constants]";
  type.parameters = {
      {"density", std::string("1"), ParameterRange::any(), "n(x)" + in_x},
      {"velocity", std::string("0"), ParameterRange::any(), "v(x)" + in_x},
      {"temperature", std::string("1"), ParameterRange::any(), "T(x)" + in_x},
      {"transverse_velocity", std::string("0"), ParameterRange::any(),
       "v_y(x)" + in_x + " (other than \"0\" needs hydro.transverse_velocity = true)"},
      {"constants", NamedReals{}, ParameterRange::any(),
       "named constants of the formulas, e.g. { a = -0.05 }"},
  };
  type.problem = [](const ParameterSet& p) -> std::optional<ParameterProblem> {
    for (const FieldKey& key : kFields) {
      try {
        const Formula f = formula(p, key.name);
        if (const auto why = sample_problem(f, key.positive)) {
          return ParameterProblem{key.name, *why};
        }
        if (std::string(key.name) == "density") {
          InitialFields density = uniform_fields();
          density.n = f;
          if (const auto why = mean_density_problem(mean_density(density))) {
            return ParameterProblem{key.name, *why};
          }
        }
      } catch (const FormulaError& e) {
        return ParameterProblem{e.constant ? "constants" : key.name, e.what()};
      }
    }
    return std::nullopt;
  };
  type.generate = [](const ParameterSet& p, const Closure&) {
    InitialFields f;
    const Formula n = formula(p, "density"), v = formula(p, "velocity"),
                  T = formula(p, "temperature"), vy = formula(p, "transverse_velocity");
    f.n = n;
    f.v = v;
    f.dv = derivative(v);
    f.T = T;
    f.vy = vy;
    return f;
  };
  type.field_parameters = {"density", "velocity", "transverse_velocity", "temperature"};
  type.has_transverse_velocity = [](const ParameterSet& p) {
    return p.text("transverse_velocity") != "0";
  };
  type.inertia_reference = [](const ParameterSet& p) -> std::optional<InertiaReference> {
    const Formula v = formula(p, "velocity"), n = formula(p, "density");
    double scale = 0.0;
    for (int i = 0; i < kSamples; ++i)
      scale = std::max(scale, std::abs(v(-0.5 + double(i) / kSamples)));
    if (scale == 0.0) return std::nullopt;
    return InertiaReference{FlowByInertia(v, derivative(v), n), scale};
  };
  return type;
}

}  // namespace granvv::hydro
