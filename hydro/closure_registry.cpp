// The one place that names every closure (hydro/closure.hpp): adding a closure adds its line.
#include <functional>
#include <map>
#include <stdexcept>

#include "hydro/closure.hpp"
#include "hydro/dilute_closure.hpp"
#include "hydro/enskog_closure.hpp"
#include "hydro/formula_closure.hpp"
#include "hydro/garzo_dufty_closure.hpp"
#include "hydro/scaled_closure.hpp"

namespace granvv::hydro {
namespace {

struct RegisteredClosure {
  std::function<std::unique_ptr<Closure>(const ClosureParameters&)> make;
  // Empty: the closure reads no parameter beyond K, q and the cooling rate.
  std::function<std::optional<ClosureParameterProblem>(const ClosureParameters&)> problem;
  // Its own case keys hydro.<name> (closure.hpp, ClosureKey): the formula closure's formulas.
  // physics.area_fraction is read by several (the Enskog and Garzo-Dufty closures for chi(phi),
  // the dilute one for its area-fraction validity monitor, the formulas as phi0), so that key
  // is the schema's.
  std::vector<ParameterSpec> keys;
  // Whether it has a heat flux down the density gradient (mu != 0 for r < 1), so that an
  // injected error in mu (hydro.mu_factor) can change its runs.
  bool density_heat_flux = false;
  bool on_every_ladder = true;  // closure.hpp, closure_on_every_ladder
};

const std::map<std::string, RegisteredClosure>& closure_registry() {
  static const std::map<std::string, RegisteredClosure> registry{
      {"dilute",
       {[](const ClosureParameters& p) {
          return std::make_unique<DiluteClosure>(p.physics, p.cooling,
                                                 EnskogClosure::area_fraction_in(p));
        },
        {},
        {},
        false}},
      {"enskog", {&EnskogClosure::make, &EnskogClosure::parameter_problem, {}, false}},
      {"garzo_dufty", {&GarzoDuftyClosure::make, &GarzoDuftyClosure::parameter_problem, {}, true}},
      // The user's mu may be nonzero; the closure is on the ladder only where chosen.
      {"formula",
       {&FormulaClosure::make, &FormulaClosure::parameter_problem, FormulaClosure::keys(), true,
        false}},
  };
  return registry;
}

const RegisteredClosure& find_closure(const std::string& name) {
  const auto& registry = closure_registry();
  const auto it = registry.find(name);
  if (it == registry.end()) {
    std::string known;
    for (const auto& entry : registry) known += (known.empty() ? "" : ", ") + entry.first;
    throw std::invalid_argument("unknown hydro closure '" + name + "'; known: " + known);
  }
  return it->second;
}

}  // namespace

std::unique_ptr<Closure> make_closure(const std::string& name, const ClosureParameters& params) {
  std::unique_ptr<Closure> closure = find_closure(name).make(params);
  if (params.factors.is_identity()) return closure;
  return std::make_unique<ScaledClosure>(std::move(closure), params.factors);
}

std::optional<ClosureParameterProblem> closure_parameter_problem(const std::string& name,
                                                                 const ClosureParameters& params) {
  const auto& closure = find_closure(name);
  return closure.problem ? closure.problem(params) : std::nullopt;
}

bool closure_has_density_heat_flux(const std::string& name) {
  return find_closure(name).density_heat_flux;
}

const std::vector<ClosureKey>& closure_keys() {
  static const std::vector<ClosureKey> keys = [] {
    std::vector<ClosureKey> out;
    for (const auto& [name, closure] : closure_registry()) {
      for (const ParameterSpec& spec : closure.keys) {
        for (const ClosureKey& other : out) {
          if (other.spec.name == spec.name) {
            throw std::logic_error("closures " + other.closure + " and " + name +
                                   " both declare hydro." + spec.name);
          }
        }
        out.push_back({spec, name});
      }
    }
    return out;
  }();
  return keys;
}

bool closure_on_every_ladder(const std::string& name) {
  return find_closure(name).on_every_ladder;
}

std::vector<std::string> closure_names() {
  std::vector<std::string> names;
  for (const auto& entry : closure_registry()) names.push_back(entry.first);
  return names;
}

}  // namespace granvv::hydro
