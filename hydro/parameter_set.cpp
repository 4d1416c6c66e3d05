#include "hydro/parameter_set.hpp"

#include <stdexcept>

namespace granvv::hydro {

bool ParameterSpec::operator==(const ParameterSpec& o) const {
  return name == o.name && default_value == o.default_value && range.min == o.range.min &&
         range.max == o.range.max && range.min_exclusive == o.range.min_exclusive &&
         range.max_exclusive == o.range.max_exclusive && help == o.help;
}

ParameterSet& ParameterSet::set(const std::string& name, ParameterValue value) {
  values_[name] = value;
  return *this;
}

const ParameterValue& ParameterSet::value(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) throw std::logic_error("parameter '" + name + "' is not set");
  return it->second;
}

double ParameterSet::real(const std::string& name) const {
  const auto* x = std::get_if<double>(&value(name));
  if (!x) throw std::logic_error("parameter '" + name + "' is an integer, read as a real");
  return *x;
}

long long ParameterSet::integer(const std::string& name) const {
  const auto* x = std::get_if<long long>(&value(name));
  if (!x) throw std::logic_error("parameter '" + name + "' is a real, read as an integer");
  return *x;
}

}  // namespace granvv::hydro
