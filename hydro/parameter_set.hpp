#pragma once
// Named scalar parameters of a model part (an initial condition, a particle engine, a closure),
// declared by the part itself: name, default, allowed range and a one-line help. The case schema
// (scene/case_schema.cpp) turns each declaration into a case key, so a parameter is stated in one
// place only.
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace granvv::hydro {

// Named reals: a table such as [initial.constants] (name -> value).
using NamedReals = std::map<std::string, double>;

// A real, an integer, a text (a formula, a file path, a choice), a table of named reals, a
// switch, a list of reals or of integers (an atlas grid), or a list of texts (file paths); the
// alternative is the parameter's type.
using ParameterValue =
    std::variant<double, long long, std::string, NamedReals, bool, std::vector<double>,
                 std::vector<long long>, std::vector<std::string>>;

// Allowed values: min/max bounds, each open or closed; no bound = unbounded. For a text
// parameter, `choices` (empty = any text). For a list, the bounds hold for each element, and
// `strictly_increasing` asks the elements to rise.
struct ParameterRange {
  std::optional<double> min, max;
  bool min_exclusive = false, max_exclusive = false;
  std::vector<std::string> choices;
  bool strictly_increasing = false;

  static ParameterRange any() { return {}; }
  static ParameterRange at_least(double lo) { return bounds(lo, std::nullopt, false); }
  static ParameterRange greater_than(double lo) { return bounds(lo, std::nullopt, true); }
  static ParameterRange closed(double lo, double hi) { return bounds(lo, hi, false); }
  static ParameterRange open_closed(double lo, double hi) { return bounds(lo, hi, true); }
  // A list whose elements obey `each` and rise strictly.
  static ParameterRange increasing(ParameterRange each) {
    each.strictly_increasing = true;
    return each;
  }
  static ParameterRange one_of(std::vector<std::string> names) {
    ParameterRange r;
    r.choices = std::move(names);
    return r;
  }

 private:
  static ParameterRange bounds(double lo, std::optional<double> hi, bool lo_exclusive) {
    ParameterRange r;
    r.min = lo;
    r.max = hi;
    r.min_exclusive = lo_exclusive;
    return r;
  }
};

struct ParameterSpec {
  std::string name;  // "mode": the case key initial.mode
  ParameterValue default_value;
  ParameterRange range;
  std::string help;  // one line

  bool is_integer() const { return std::holds_alternative<long long>(default_value); }
  bool is_text() const { return std::holds_alternative<std::string>(default_value); }
  bool is_named_reals() const { return std::holds_alternative<NamedReals>(default_value); }
  bool is_boolean() const { return std::holds_alternative<bool>(default_value); }
  bool is_real_list() const { return std::holds_alternative<std::vector<double>>(default_value); }
  bool is_integer_list() const {
    return std::holds_alternative<std::vector<long long>>(default_value);
  }
  bool is_text_list() const {
    return std::holds_alternative<std::vector<std::string>>(default_value);
  }
  bool operator==(const ParameterSpec& o) const;
};

// Values by name. Reading a missing name, or a value of another type (an integer as a real...), is
// a programming error: std::logic_error naming the parameter.
class ParameterSet {
 public:
  ParameterSet() = default;
  ParameterSet(std::initializer_list<std::pair<const std::string, ParameterValue>> values)
      : values_(values) {}

  ParameterSet& set(const std::string& name, ParameterValue value);
  double real(const std::string& name) const;
  long long integer(const std::string& name) const;
  const std::string& text(const std::string& name) const;
  const NamedReals& named_reals(const std::string& name) const;
  const ParameterValue& value(const std::string& name) const;

 private:
  std::map<std::string, ParameterValue> values_;
};

}  // namespace granvv::hydro
