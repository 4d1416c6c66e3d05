#pragma once
// The case schema: one declarative row per key of a case file (cases/NAME.toml).
//
// A row names a dotted key, its type, its default (or that it is required), a constraint and a
// one-line description. Tables ([physics], [hydro], ...) are implied by the dotted keys, so adding
// a section is a matter of adding rows to case_schema() in case_schema.cpp. The keys of one
// model part (an initial-condition type, a particle engine, a closure) are declared beside the
// part and derived from its registry. Checks that involve several keys are rows of
// case_cross_checks().

#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace granvv::app {

class CaseConfig;

// The order matches the alternatives of Value.
enum class ValueType {
  real,
  integer,
  boolean,
  string,
  real_array,
  integer_array,
  real_table,
  string_array
};

// A table of named reals, such as [initial.constants]: name -> value.
using RealTable = std::map<std::string, double>;

// A resolved value; Value::index() == static_cast<std::size_t>(ValueType).
using Value = std::variant<double, long long, bool, std::string, std::vector<double>,
                           std::vector<long long>, RealTable, std::vector<std::string>>;

// "a real", "an integer", "a boolean", "a string", "an array of reals", "an array of integers",
// "a table of named reals", "an array of strings".
std::string type_phrase(ValueType type);

struct Default {
  enum class Kind {
    value,        // use `value`
    required,     // the case must give the key
    file_stem,    // the stem of the case file name (string keys)
    empty_array,  // [] (array keys)
    list_of_key,  // [the value of the string key `key`] (string-array keys; `key` comes first)
  };
  Kind kind = Kind::required;
  Value value{};
  std::string key;  // list_of_key

  Default(double v) : kind(Kind::value), value(v) {}
  Default(int v) : kind(Kind::value), value(static_cast<long long>(v)) {}
  Default(long long v) : kind(Kind::value), value(v) {}
  Default(bool v) : kind(Kind::value), value(v) {}
  Default(const char* v) : kind(Kind::value), value(std::string(v)) {}
  Default(const std::string& v) : kind(Kind::value), value(v) {}
  Default(const RealTable& v) : kind(Kind::value), value(v) {}
  // A declared list (hydro::ParameterSpec): an empty one is the empty array.
  Default(const std::vector<double>& v) : kind(v.empty() ? Kind::empty_array : Kind::value) {
    value = v;
  }
  Default(const std::vector<long long>& v) : kind(v.empty() ? Kind::empty_array : Kind::value) {
    value = v;
  }
  Default(const std::vector<std::string>& v) : kind(v.empty() ? Kind::empty_array : Kind::value) {
    value = v;
  }
  static Default required() { return Default(Kind::required); }
  static Default file_stem() { return Default(Kind::file_stem); }
  static Default empty_array() { return Default(Kind::empty_array); }
  static Default list_of_key(std::string key) {
    Default d(Kind::list_of_key);
    d.key = std::move(key);
    return d;
  }

 private:
  explicit Default(Kind k) : kind(k) {}
};

// The longest case.name: a folder name (NAME_MAX on Linux).
constexpr std::size_t kMaxNameBytes = 255;

// What values of a key (or, for arrays, of each element) are allowed.
struct Constraint {
  std::optional<double> min, max;  // bounds on numbers / array elements
  bool min_exclusive = false, max_exclusive = false;
  std::vector<std::string> choices;  // strings, string arrays' elements: one of these (empty = any)
  bool distinct_non_empty = false;   // string arrays: at least one element, none repeated
  bool may_be_empty = false;         // with distinct_non_empty: none repeated, [] allowed
  bool strictly_increasing = false;  // arrays
  bool name = false;                 // strings: non-empty, no '/', '\\', control characters,
                                     // at most kMaxNameBytes (a folder name)

  // "> 0", "in (0, 0.5]", ">= 1", "one of a, b", "each >= 0, strictly increasing", "" (anything).
  std::string text() const;
};

Constraint any_value();
Constraint positive();                           // > 0
Constraint non_negative();                       // >= 0
Constraint greater_than(double lo);              // > lo
Constraint at_least(double lo);                  // >= lo
Constraint open_open(double lo, double hi);      // (lo, hi)
Constraint open_closed(double lo, double hi);    // (lo, hi]
Constraint closed_open(double lo, double hi);    // [lo, hi)
Constraint closed_closed(double lo, double hi);  // [lo, hi]
Constraint one_of(std::vector<std::string> choices);
Constraint increasing(Constraint each = any_value());  // arrays: elements obey `each`, strictly up
Constraint name_like();
Constraint distinct_choices(std::vector<std::string> choices);          // string arrays
Constraint distinct_choices_or_none(std::vector<std::string> choices);  // the same, or []

struct KeySpec {
  std::string key;  // dotted, e.g. "physics.K"
  ValueType type;
  Default default_value;
  Constraint constraint;
  std::string description;  // one line, shown in error messages and in the resolved case

  std::string section() const;  // "physics" (everything before the last dot)
  std::string leaf() const;     // "K"
};

// All keys, in the order they are written to the resolved case: the rows of case_schema.cpp
// with the keys that model parts declare inserted (the initial conditions' initial.*, the
// particle engines' own md.* and the closures' own hydro.* keys, from their registries).
const std::vector<KeySpec>& case_schema();

// The model a key belongs to when a particle engine or a closure declares it as its own: the key
// that selects the model and the model's name, e.g. {"md.engine", "lammps"} for md.max_overlap.
// nullopt for a key every scene has.
struct KeyOwner {
  std::string selector;  // "md.engine" or "hydro.closure"
  std::string model;     // "lammps"
};
std::optional<KeyOwner> key_owner(std::string_view key);
// nullptr if `key` is not a key of the schema.
const KeySpec* find_key_spec(std::string_view key);
// True if `path` is a table of the schema ("hydro"; "" is the root).
bool is_schema_table(std::string_view path);
// The names directly inside table `path` ("" = root), in schema order.
std::vector<std::string> schema_children(std::string_view path);

// "an integer >= 4", "a real in (0, 0.5]", "a string, one of a, b", "a boolean (true or false)".
std::string expected_phrase(const KeySpec& spec);
// Why `value` (already of the spec's type) is not allowed, e.g. "must be > 0 (Knudsen number)";
// nullopt if it is allowed. Rejects NaN and infinities.
std::optional<std::string> constraint_violation(const KeySpec& spec, const Value& value);

// The candidate closest to `wrong` (case-insensitive edit distance) if it is close enough to be a
// likely typo; compares whole dotted names, allowing more edits for longer last components.
std::optional<std::string> closest_match(std::string_view wrong,
                                         const std::vector<std::string>& candidates);

// Value in TOML syntax: 0.0004, 1e6, 2000, true, "single_mode", [1.0, 2.5].
std::string format_value(const Value& value);
std::string join(const std::vector<std::string>& items, std::string_view sep);
std::string format_real(double x);            // shortest round-trip TOML float
std::string toml_quoted(std::string_view s);  // TOML basic string with escapes

// True if `s` is well-formed UTF-8 (no overlong forms, surrogates or code points above
// U+10FFFF): TOML, JSON and the report need it.
bool valid_utf8(std::string_view s);
// `s` with each byte that is not part of well-formed UTF-8 replaced by `replacement`.
std::string utf8_repaired(std::string_view s, char replacement);
// `s` if it has at most `limit` bytes; otherwise its first bytes (cut at a character boundary)
// and "... (N bytes)", so that a message stays one readable line.
std::string abbreviated(std::string_view s, std::size_t limit = 120);

// A rule over several keys. `check` returns the key to blame and why, e.g.
// {"hydro.output_times", "every element must be <= hydro.t_end = 4.0 (from default), ..."}.
struct CrossViolation {
  std::string key;
  std::string message;
};
struct CrossCheck {
  std::string rule;  // one line, for documentation
  std::function<std::optional<CrossViolation>(const CaseConfig&)> check;
};
const std::vector<CrossCheck>& case_cross_checks();

}  // namespace granvv::app
