// The one place that names every closure (hydro/closure.hpp): adding a closure adds its line.
#include <functional>
#include <map>
#include <stdexcept>

#include "hydro/closure.hpp"
#include "hydro/dilute_closure.hpp"

namespace granvv::hydro {
namespace {

using ClosureFactory = std::function<std::unique_ptr<Closure>(const ClosureParameters&)>;

const std::map<std::string, ClosureFactory>& closure_registry() {
  static const std::map<std::string, ClosureFactory> registry{
      {"dilute",
       [](const ClosureParameters& p) { return std::make_unique<DiluteClosure>(p.physics); }},
  };
  return registry;
}

}  // namespace

std::unique_ptr<Closure> make_closure(const std::string& name, const ClosureParameters& params) {
  const auto& registry = closure_registry();
  const auto it = registry.find(name);
  if (it == registry.end()) {
    std::string known;
    for (const auto& entry : registry) known += (known.empty() ? "" : ", ") + entry.first;
    throw std::invalid_argument("unknown hydro closure '" + name + "'; known: " + known);
  }
  return it->second(params);
}

std::vector<std::string> closure_names() {
  std::vector<std::string> names;
  for (const auto& entry : closure_registry()) names.push_back(entry.first);
  return names;
}

}  // namespace granvv::hydro
