#include "hydro/parameter_set.hpp"

#include <stdexcept>

namespace granvv::hydro {

bool ParameterSpec::operator==(const ParameterSpec& o) const {
  return name == o.name && default_value == o.default_value && range.min == o.range.min &&
         range.max == o.range.max && range.min_exclusive == o.range.min_exclusive &&
         range.max_exclusive == o.range.max_exclusive && range.choices == o.range.choices &&
         range.strictly_increasing == o.range.strictly_increasing && help == o.help;
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

namespace {
template <typename T>
const T& typed(const ParameterValue& value, const std::string& name, const char* as) {
  const auto* x = std::get_if<T>(&value);
  if (!x) throw std::logic_error("parameter '" + name + "' is not " + as + ", read as one");
  return *x;
}
}  // namespace

double ParameterSet::real(const std::string& name) const {
  return typed<double>(value(name), name, "a real");
}

long long ParameterSet::integer(const std::string& name) const {
  return typed<long long>(value(name), name, "an integer");
}

const std::string& ParameterSet::text(const std::string& name) const {
  return typed<std::string>(value(name), name, "a text");
}

const NamedReals& ParameterSet::named_reals(const std::string& name) const {
  return typed<NamedReals>(value(name), name, "a table of named reals");
}

}  // namespace granvv::hydro
