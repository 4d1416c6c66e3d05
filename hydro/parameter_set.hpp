#pragma once
// Named scalar parameters of a model part (an initial condition, ...), declared by the part
// itself: name, default, allowed range and a one-line help. The case schema (app/case_schema.cpp)
// turns each declaration into a case key, so a parameter is stated in one place only.
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace granvv::hydro {

// A real or an integer; the alternative is the parameter's type.
using ParameterValue = std::variant<double, long long>;

// Allowed values: min/max bounds, each open or closed; no bound = unbounded.
struct ParameterRange {
  std::optional<double> min, max;
  bool min_exclusive = false, max_exclusive = false;

  static ParameterRange any() { return {}; }
  static ParameterRange at_least(double lo) { return {lo, std::nullopt, false, false}; }
  static ParameterRange greater_than(double lo) { return {lo, std::nullopt, true, false}; }
  static ParameterRange closed(double lo, double hi) { return {lo, hi, false, false}; }
};

struct ParameterSpec {
  std::string name;  // "mode": the case key initial.mode
  ParameterValue default_value;
  ParameterRange range;
  std::string help;  // one line

  bool is_integer() const { return std::holds_alternative<long long>(default_value); }
  bool operator==(const ParameterSpec& o) const;
};

// Values by name. Reading a missing name, or an integer as a real (or the reverse), is a
// programming error: std::logic_error naming the parameter.
class ParameterSet {
 public:
  ParameterSet() = default;
  ParameterSet(std::initializer_list<std::pair<const std::string, ParameterValue>> values)
      : values_(values) {}

  ParameterSet& set(const std::string& name, ParameterValue value);
  double real(const std::string& name) const;
  long long integer(const std::string& name) const;
  const ParameterValue& value(const std::string& name) const;

 private:
  std::map<std::string, ParameterValue> values_;
};

}  // namespace granvv::hydro
