#include "hydro/formula_closure.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "hydro/central_difference.hpp"
#include "hydro/hcs_cutoffs.hpp"

namespace granvv::hydro {
namespace {

// The formulas, in the order FormulaClosure holds them, with their keys hydro.<name> and
// defaults: the dilute closure's p = n T, eta = eta_xy = (K/4) T^{1/2}, kappa = K T^{1/2},
// mu = 0 and Lambda = (8q/K) n T^{3/2} (hydro/dilute_closure.hpp).
enum Quantity : size_t { kPressure, kViscosity, kShearViscosity, kConductivity, kMu, kCooling };
struct QuantitySpec {
  const char* name;
  const char* dilute;
  bool positive;  // else any finite value
  const char* help;
};
constexpr QuantitySpec kQuantities[] = {
    {"pressure", "n*T", true, "pressure p(n, T)"},
    {"viscosity", "K/4*sqrt(T)", true, "longitudinal viscosity eta(n, T), stress eta dv/dx"},
    {"shear_viscosity", "K/4*sqrt(T)", true, "shear viscosity eta_xy(n, T), stress eta_xy dv_y/dx"},
    {"conductivity", "K*sqrt(T)", true, "heat conductivity kappa(n, T)"},
    // Either sign: the term -mu dn/dx moves heat down (mu > 0, inelastic kinetic theory) or up
    // the density gradient, and leaves the heat equation's diffusion in T to kappa > 0.
    {"mu", "0", false, "mu(n, T) of the heat flux -kappa dT/dx - mu dn/dx (any sign)"},
    {"cooling_rate", "8*q/K*n*T^(3/2)", true,
     "cooling sink Lambda(n, T), dT/dt = -Lambda (physics.cooling = \"exact\": times 1 - q)"},
};
constexpr size_t kQuantityCount = std::size(kQuantities);
constexpr const char* kConstantsKey = "constants";
constexpr const char* kDensityLimitKey = "density_limit";
constexpr double kDefaultDensityLimit = 1e6;
constexpr const char* kFormulaHelp = "formula: ";

// Relative step of the numerical derivatives (hydro/central_difference.hpp).
constexpr double kRelativeStep = 1e-3;
// Local error bound of one Dormand-Prince step of the cooling, relative to u = T^{-1/2}.
constexpr double kCoolingTolerance = 1e-13;
// Tries of one cooling step past which Lambda is taken to be singular on the way.
constexpr int kMaxCoolingSteps = 100000;

std::string number(double x) {
  std::ostringstream os;
  os.precision(6);
  os << x;
  return os.str();
}

const std::string& text_of(const ClosureParameters& p, const QuantitySpec& q,
                           const std::string& fallback) {
  const auto it = p.texts.find(q.name);
  return it == p.texts.end() ? fallback : it->second;
}

double density_limit_of(const ClosureParameters& p) {
  const auto it = p.extra.find(kDensityLimitKey);
  return it == p.extra.end() ? kDefaultDensityLimit : it->second;
}

double area_fraction_of(const ClosureParameters& p) {
  const auto it = p.extra.find("area_fraction");
  return it == p.extra.end() ? 0.0 : it->second;
}

// The constants every formula may use: the case's, then the user's (which may not shadow them).
NamedReals constants_of(const ClosureParameters& p) {
  NamedReals constants{{"K", p.physics.K},
                       {"q", p.physics.q},
                       {"r", 1.0 - 2.0 * p.physics.q},
                       {"phi0", area_fraction_of(p)}};
  const auto user = p.tables.find(kConstantsKey);
  if (user == p.tables.end()) return constants;
  for (const auto& [name, value] : user->second) {
    if (constants.count(name)) {
      FormulaError e("constant '" + name +
                     "' is reserved (K, q, r = 1 - 2q and phi0 are the case's physics)");
      e.constant = true;
      throw e;
    }
  }
  for (const auto& [name, value] : user->second) constants[name] = value;
  return constants;
}

// Compiles the formulas of p (the defaults where it has none); throws FormulaError.
std::vector<Formula> compile(const ClosureParameters& p) {
  NamedReals constants;
  try {
    constants = constants_of(p);
  } catch (FormulaError& e) {
    throw ClosureParameterProblem{kConstantsKey, e.what()};
  }
  std::vector<Formula> formulas;
  for (const QuantitySpec& q : kQuantities) {
    try {
      formulas.emplace_back(text_of(p, q, q.dilute), constants, std::vector<std::string>{"n", "T"});
    } catch (FormulaError& e) {
      throw ClosureParameterProblem{e.constant ? kConstantsKey : q.name, e.what()};
    }
  }
  return formulas;
}

double adiabatic_modulus_of(const Formula& pressure, double n, double T) {
  const double dp_dn =
      central_derivative([&](double m) { return pressure(m, T); }, n, kRelativeStep * n);
  const double dp_dT =
      central_derivative([&](double s) { return pressure(n, s); }, T, kRelativeStep * T);
  return n * dp_dn + pressure(n, T) * dp_dT / n;
}

// 10^(i / kCheckPointsPerDecade) from lo (a power of ten) up to hi, and hi: the powers of ten
// themselves (n = 1, T = 1) are points.
std::vector<double> log_grid(double lo, double hi) {
  std::vector<double> grid;
  const double first = std::round(std::log10(lo) * kCheckPointsPerDecade);
  for (double i = first;; ++i) {
    const double x = std::pow(10.0, i / kCheckPointsPerDecade);
    if (x >= hi) break;
    grid.push_back(x);
  }
  grid.push_back(hi);
  return grid;
}

// The first formula with a value outside what it allows on the grid, or nullopt.
std::optional<ClosureParameterProblem> grid_problem(const std::vector<Formula>& formulas,
                                                    double density_limit) {
  const std::vector<double> densities = log_grid(kLowestCheckedDensity, density_limit);
  const std::vector<double> temperatures =
      log_grid(kCheckedTemperatures[0], kCheckedTemperatures[1]);
  const std::string grid = "for n in [" + number(kLowestCheckedDensity) + ", " +
                           number(density_limit) + "] (hydro.density_limit) and T in [" +
                           number(kCheckedTemperatures[0]) + ", " +
                           number(kCheckedTemperatures[1]) + "]";
  for (size_t k = 0; k < kQuantityCount; ++k) {
    const QuantitySpec& q = kQuantities[k];
    for (const double n : densities) {
      for (const double T : temperatures) {
        const double value = formulas[k](n, T);
        const bool allowed = q.positive ? value > 0.0 && value < HUGE_VAL : std::isfinite(value);
        if (!allowed) {
          return ClosureParameterProblem{
              q.name, "is " + number(value) + " at n = " + number(n) + ", T = " + number(T) +
                          " (allowed: finite" + (q.positive ? " and > 0 " : ", of either sign, ") +
                          grid + ")"};
        }
        if (k != kPressure) continue;
        const double B = adiabatic_modulus_of(formulas[k], n, T);
        if (!(B > 0.0 && B < HUGE_VAL)) {
          return ClosureParameterProblem{
              q.name, "gives the adiabatic modulus n dp/dn + p (dp/dT) / n = " + number(B) +
                          " at n = " + number(n) + ", T = " + number(T) +
                          " (allowed: finite and > 0, a real sound speed, " + grid + ")"};
        }
      }
    }
  }
  return std::nullopt;
}

std::optional<ClosureParameterProblem> problem_of(const ClosureParameters& p,
                                                  std::vector<Formula>* compiled) {
  try {
    std::vector<Formula> formulas = compile(p);
    const auto problem = grid_problem(formulas, density_limit_of(p));
    if (compiled) *compiled = std::move(formulas);
    return problem;
  } catch (const ClosureParameterProblem& problem) {
    return problem;
  }
}

}  // namespace

std::vector<ParameterSpec> FormulaClosure::keys() {
  std::vector<ParameterSpec> keys;
  for (const QuantitySpec& q : kQuantities) {
    keys.push_back({q.name, std::string(q.dilute), ParameterRange::any(),
                    std::string(kFormulaHelp) + q.help +
                        ", an expression of n, T, K, q, r, phi0 and hydro.constants"});
  }
  keys.push_back({kConstantsKey, NamedReals{}, ParameterRange::any(),
                  "formula: named constants of the formulas, e.g. { a = 2.5 }"});
  keys.push_back({kDensityLimitKey, kDefaultDensityLimit, ParameterRange::greater_than(1.0),
                  "formula: the densest n the formulas hold at (checked from n = " +
                      number(kLowestCheckedDensity) + "; a run stops where a cell passes it)"});
  return keys;
}

std::unique_ptr<Closure> FormulaClosure::make(const ClosureParameters& params) {
  return std::make_unique<FormulaClosure>(params);
}

std::optional<ClosureParameterProblem> FormulaClosure::parameter_problem(
    const ClosureParameters& params) {
  return problem_of(params, nullptr);
}

FormulaClosure::FormulaClosure(const ClosureParameters& params)
    : physics_(params.physics),
      area_fraction_(area_fraction_of(params)),
      density_limit_(density_limit_of(params)),
      loss_factor_(inelastic_loss_factor(params.cooling, params.physics.q)) {
  if (const auto problem = problem_of(params, &formulas_)) {
    throw std::invalid_argument("formula closure: hydro." + problem->parameter + ": " +
                                problem->reason);
  }
}

double FormulaClosure::adiabatic_modulus(double n, double T) const {
  return adiabatic_modulus_of(formulas_[kPressure], n, T);
}

double FormulaClosure::cooling_rate(double n, double T) const {
  return loss_factor_ * formulas_[kCooling](n, T);
}

void FormulaClosure::cell_coefficients(const std::vector<double>& n, const std::vector<double>& T,
                                       CellCoefficients& out) const {
  const size_t cells = n.size();
  out.resize(cells);
  for (size_t i = 0; i < cells; ++i) {
    const double ni = n[i], Ti = T[i];  // loaded once: the outputs might alias the inputs
    out.pressure[i] = formulas_[kPressure](ni, Ti);
    out.adiabatic_modulus[i] = adiabatic_modulus(ni, Ti);
    out.viscosity[i] = formulas_[kViscosity](ni, Ti);
    out.shear_viscosity[i] = formulas_[kShearViscosity](ni, Ti);
    out.conductivity[i] = formulas_[kConductivity](ni, Ti);
    out.mu[i] = formulas_[kMu](ni, Ti);
  }
}

void FormulaClosure::sound_speed(const std::vector<double>& n, const std::vector<double>& T,
                                 std::vector<double>& c) const {
  c.resize(n.size());
  for (size_t i = 0; i < n.size(); ++i) c[i] = std::sqrt(adiabatic_modulus(n[i], T[i]) / n[i]);
}

void FormulaClosure::cooling_rate(const std::vector<double>& n, const std::vector<double>& T,
                                  std::vector<double>& rate) const {
  rate.resize(n.size());
  for (size_t i = 0; i < n.size(); ++i) rate[i] = cooling_rate(n[i], T[i]);
}

// dT/dt = -Lambda(n, T) as du/dt = f(u) = Lambda(n, u^-2) u^3 / 2 for u = T^{-1/2}, by the
// Dormand-Prince 5(4) pair (Dormand & Prince, J. Comput. Appl. Math. 6, 19 (1980)), advancing
// the fifth-order solution, with its step set so that the embedded error estimate stays below
// kCoolingTolerance u.
double FormulaClosure::cooled(double n, double T, double dt) const {
  const auto f = [&](double u) { return 0.5 * cooling_rate(n, 1.0 / (u * u)) * u * u * u; };
  static constexpr double a[6][6] = {
      {1.0 / 5},
      {3.0 / 40, 9.0 / 40},
      {44.0 / 45, -56.0 / 15, 32.0 / 9},
      {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729},
      {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656},
      {35.0 / 384, 0.0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}};
  // Fifth-order weights (the last row of a) minus the fourth-order ones.
  static constexpr double e[7] = {71.0 / 57600,      0.0,        -71.0 / 16695, 71.0 / 1920,
                                  -17253.0 / 339200, 22.0 / 525, -1.0 / 40};
  if (!(dt > 0.0)) return T;
  double u = 1.0 / std::sqrt(T), t = 0.0, h = dt;
  int steps = 0;
  while (t < dt) {
    h = std::min(h, dt - t);
    double k[7];
    k[0] = f(u);
    for (int s = 1; s < 7; ++s) {
      double increment = 0.0;
      for (int j = 0; j < s; ++j) increment += a[s - 1][j] * k[j];
      k[s] = f(u + h * increment);
    }
    double next = 0.0, error = 0.0;
    for (int j = 0; j < 6; ++j) next += a[5][j] * k[j];
    for (int j = 0; j < 7; ++j) error += e[j] * k[j];
    next = u + h * next;
    error = std::abs(h * error);
    if (!std::isfinite(error) || ++steps > kMaxCoolingSteps) return std::nan("");
    const double tolerance = kCoolingTolerance * next;
    if (error <= tolerance) {
      t += h;
      u = next;
    }
    // The usual controller: h (tolerance / error)^{1/5}, safety 0.9, at most 5 times larger.
    h *= error > 0.0 ? std::clamp(0.9 * std::pow(tolerance / error, 0.2), 0.2, 5.0) : 5.0;
  }
  return 1.0 / (u * u);
}

void FormulaClosure::cool(const std::vector<double>& n, const std::vector<double>& T, double dt,
                          std::vector<double>& cooled_T) const {
  cooled_T.resize(n.size());
  for (size_t i = 0; i < n.size(); ++i) cooled_T[i] = cooled(n[i], T[i], dt);
}

HcsLinearisation FormulaClosure::hcs_linearisation() const {
  const Formula& p = formulas_[kPressure];
  const auto rate = [&](double n, double T) { return cooling_rate(n, T); };
  const double h = kRelativeStep;  // at n = T = 1
  HcsLinearisation lin;
  const double Lambda = rate(1.0, 1.0);
  lin.haff_time = 2.0 / Lambda;
  lin.epsilon = 0.5 * Lambda;
  lin.pressure_density = central_derivative([&](double n) { return p(n, 1.0); }, 1.0, h);
  lin.pressure_temperature = central_derivative([&](double T) { return p(1.0, T); }, 1.0, h);
  lin.compression_heating = p(1.0, 1.0);
  lin.viscosity = formulas_[kViscosity](1.0, 1.0);
  lin.shear_viscosity = formulas_[kShearViscosity](1.0, 1.0);
  lin.conductivity = formulas_[kConductivity](1.0, 1.0);
  lin.cooling_density = central_derivative([&](double n) { return rate(n, 1.0); }, 1.0, h);
  lin.cooling_temperature =
      central_derivative([&](double T) { return rate(1.0, T); }, 1.0, h) - Lambda;
  lin.mu = formulas_[kMu](1.0, 1.0);
  set_cutoff_modes(lin);
  return lin;
}

ValidityScales FormulaClosure::validity_scales() const {
  // The area-fraction monitor fires where the formulas stop holding: phi0 hydro.density_limit.
  return {physics_.K, area_fraction_, false, area_fraction_ * density_limit_};
}

std::string FormulaClosure::validity_problem(const std::vector<double>& n) const {
  const auto densest = std::max_element(n.begin(), n.end());
  if (densest == n.end() || *densest <= density_limit_) return {};
  return "the density n = " + number(*densest) + " in cell " + std::to_string(densest - n.begin()) +
         " passed hydro.density_limit = " + number(density_limit_) +
         ", the densest n the formulas were checked at";
}

}  // namespace granvv::hydro
