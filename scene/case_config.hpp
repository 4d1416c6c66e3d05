#pragma once
// A case: a TOML file (cases/NAME.toml) validated against the schema of case_schema.cpp, with
// `--set key=value` overrides applied and defaults filled in.
//
// Every problem with the input is a ConfigError whose what() is ONE line naming the place
// (file:line:column, or the --set argument), the key, the value and what is allowed, e.g.
//   cases/x.toml:7:5: physics.K = -0.001: must be > 0 (Knudsen number ...)
// Asking a CaseConfig for a key that is not in the schema, or with the accessor of another type,
// is a programming error: std::logic_error.

#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scene/case_schema.hpp"

namespace granvv::app {

struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Prints "granvv: error: <message>" on stderr once per job: under mpirun only the first rank
// prints. The rank is read from the launcher's environment (Open MPI, MPICH, PMIx), because
// input is validated before MPI starts.
void report_input_error(const ConfigError& error);

class CaseConfig {
 public:
  // Reads and validates `file`; `sets` are the arguments of --set ("physics.K=1e-3"). A file that
  // is missing or unreadable is a ConfigError too.
  static CaseConfig from_file(const std::filesystem::path& file,
                              const std::vector<std::string>& sets = {});
  // `source_name` is the path shown in messages; its stem is the default case.name.
  static CaseConfig from_string(std::string_view toml_text, std::string source_name,
                                const std::vector<std::string>& sets = {});

  double real(std::string_view key) const;  // "physics.K"; an integer in the file reads as real
  long long integer(std::string_view key) const;
  // An integer key as an int, for every count, mode number or size the engines take as int.
  // The schema bounds each integer key within an int; a value outside its range is a
  // ConfigError naming the key, its value and the allowed range.
  int int_value(std::string_view key) const;
  std::vector<int> int_values(std::string_view key) const;
  bool boolean(std::string_view key) const;
  std::string string(std::string_view key) const;
  std::vector<double> reals(std::string_view key) const;
  std::vector<std::string> strings(std::string_view key) const;
  std::vector<long long> integers(std::string_view key) const;
  const Value& value(std::string_view key) const;  // any type

  std::string name() const;                              // case.name, defaulting to the file stem
  const std::string& source() const { return source_; }  // as given to from_string/from_file
  const std::vector<std::string>& overrides() const { return sets_; }

  // Where a key's value came from: "cases/x.toml:7:5", "--set physics.K=1e-3" or "default".
  std::string origin(std::string_view key) const;
  // 2 + its position for a --set, 1 for the case file, 0 for a default: of several keys behind
  // one problem, the message names the one the user touched last.
  int origin_precedence(std::string_view key) const;

  // The whole resolved case (every key of the schema, defaults filled, overrides applied) as TOML
  // text, with each key's description and allowed values as a comment. Parsing it back with
  // from_string gives the same flattened() list.
  std::string resolved_toml() const;
  // ("physics.K", "0.0004") for every key, sorted by key; values in TOML syntax (strings quoted),
  // i.e. exactly what `--set KEY=VALUE` accepts.
  std::vector<std::pair<std::string, std::string>> flattened() const;

 private:
  CaseConfig() = default;
  const Value& checked(std::string_view key, ValueType type) const;
  // One gas, one restitution: see the definition.
  void reconcile_restitution();

  std::string source_;
  std::vector<std::string> sets_;
  std::map<std::string, Value, std::less<>> values_;
  std::map<std::string, std::string, std::less<>> origins_;
};

// Refuses a key that a particle engine or a closure declares as its own (key_owner) when the
// user gave it (in the case file or by --set, with a value other than its default) and the case
// does not run that model: a ConfigError naming the key, its value, the model it belongs to and
// the one the case runs. The case runs md.engine when md.enabled, and hydro.closure and, with
// compare.enabled, the compare.closures when hydro.enabled; a part that does not run reads none
// of its keys, so none of them is refused. A key at its default is what every resolved
// case.toml lists, and is not refused.
// `granvv atlas` runs more models than the case names: every registered particle engine, and
// every closure on every ladder (hydro/closure.hpp, closure_on_every_ladder) beside the case's
// own (RunningCommand::atlas).
enum class RunningCommand { run, atlas };
void refuse_keys_of_models_not_run(const CaseConfig& config,
                                   RunningCommand command = RunningCommand::run);

}  // namespace granvv::app
