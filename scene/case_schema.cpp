#include "scene/case_schema.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <type_traits>

#include "compare/mode_amplitudes.hpp"
#include "compare/transport_coefficients.hpp"
#include "fields/field_series.hpp"
#include "hydro/closure.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "md_bridge/particle_engine_registry.hpp"
#include "scene/case_config.hpp"

namespace granvv::app {

// ---------------------------------------------------------------------------------------------
// The schema. One row per key: key, type, default, constraint, description.
// ---------------------------------------------------------------------------------------------
namespace {
constexpr auto kReal = ValueType::real;
constexpr auto kInteger = ValueType::integer;
constexpr auto kBoolean = ValueType::boolean;
constexpr auto kString = ValueType::string;
constexpr auto kReals = ValueType::real_array;
constexpr auto kIntegers = ValueType::integer_array;
constexpr auto kStrings = ValueType::string_array;
const Default kRequired = Default::required();
const Default kFileStem = Default::file_stem();
const Default kEmpty = Default::empty_array();

// compare.transport: "none" or a coefficient a scene can measure.
std::vector<std::string> transport_choices() {
  std::vector<std::string> choices = {"none"};
  for (const auto& name : compare::transport_coefficient_names()) choices.push_back(name);
  for (const auto& pair : compare::transport_pairs()) choices.push_back(pair.name);
  for (const auto& fit : compare::transport_flux_fits()) choices.push_back(fit.name);
  return choices;
}

// compare.transport_signals: "<field>:<phase>" of every hydrodynamic field and mode phase.
std::vector<std::string> transport_signal_choices() {
  std::vector<std::string> choices;
  for (const auto& field : fields::hydrodynamic_fields()) {
    for (const auto& phase : compare::mode_phase_names()) choices.push_back(field + ":" + phase);
  }
  return choices;
}

// Integer keys are read as C++ int (CaseConfig::int_value): none may exceed this.
constexpr double kIntMax = 2147483647.0;
// A mesh this fine holds about 1 GB of state and snapshots; finer ones do not fit this machine.
constexpr double kMaxCells = 1e7;

Constraint constraint_of(const hydro::ParameterRange& range) {
  Constraint c;
  c.min = range.min;
  c.max = range.max;
  c.min_exclusive = range.min_exclusive;
  c.max_exclusive = range.max_exclusive;
  c.choices = range.choices;
  c.strictly_increasing = range.strictly_increasing;
  return c;
}

// The case type of a parameter's alternative (hydro/parameter_set.hpp).
ValueType value_type_of(const hydro::ParameterSpec& spec) {
  if (spec.is_integer()) return kInteger;
  if (spec.is_text()) return kString;
  if (spec.is_named_reals()) return ValueType::real_table;
  if (spec.is_boolean()) return kBoolean;
  if (spec.is_real_list()) return kReals;
  if (spec.is_integer_list()) return kIntegers;
  if (spec.is_text_list()) return kStrings;
  return kReal;
}

// The row of case key `key` that a model part declares (initial condition, engine, closure).
KeySpec declared_row(std::string key, const hydro::ParameterSpec& spec, std::string help) {
  const Default value = std::visit([](auto x) { return Default(x); }, spec.default_value);
  return {std::move(key), value_type_of(spec), value, constraint_of(spec.range), std::move(help)};
}

// initial.type, one of the registered types, then initial.<name> for every parameter a type
// declares; its description names the types that read it ("single_mode/linear_mode: ...").
std::vector<KeySpec> initial_condition_rows() {
  std::vector<std::string> types;
  for (const auto& type : hydro::initial_condition_types()) types.push_back(type.name);
  std::vector<KeySpec> rows = {
      {"initial.type", kString, "single_mode", one_of(types), "initial condition"}};
  for (const auto& key : hydro::initial_parameter_keys()) {
    const auto& spec = key.spec;
    const std::string help =
        key.types.empty() ? spec.help : join(key.types, "/") + ": " + spec.help;
    rows.push_back(declared_row("initial." + spec.name, spec, help));
  }
  return rows;
}

// The keys each particle engine declares as its own in table `section` ("md", "atlas";
// md_bridge/particle_engine_registry.hpp), with the engine's help as written beside it.
std::vector<KeySpec> particle_engine_rows(const std::string& section) {
  std::vector<KeySpec> rows;
  for (const auto& key : md::particle_engine_keys()) {
    if (key.section == section) rows.push_back(declared_row(key.key(), key.spec, key.spec.help));
  }
  return rows;
}

// The keys each closure declares as its own (hydro/closure.hpp, closure_keys), likewise.
std::vector<KeySpec> closure_rows() {
  std::vector<KeySpec> rows;
  for (const auto& key : hydro::closure_keys()) {
    rows.push_back(declared_row(key.key(), key.spec, key.spec.help));
  }
  return rows;
}

// `rows` with `inserted` after the row of key `anchor`, or after the last row of table
// `anchor`.
std::vector<KeySpec> inserted_after(std::vector<KeySpec> rows, const std::string& anchor,
                                    const std::vector<KeySpec>& inserted) {
  std::optional<std::size_t> after;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].key == anchor || rows[i].section() == anchor) after = i + 1;
  }
  if (!after) throw std::logic_error("case schema: no row " + anchor + " to insert after");
  rows.insert(rows.begin() + std::ptrdiff_t(*after), inserted.begin(), inserted.end());
  return rows;
}

// Every row but the declared ones (the [initial] parameters, the engines' and closures' own
// keys: case_schema() inserts them), in schema order.
std::vector<KeySpec> rows_without_declared() {
  return {
      // [case]
      {"case.name", kString, kFileStem, name_like(), "scene name; output goes to out/<name>"},
      {"case.description", kString, "", any_value(), "one-line description for `granvv list`"},
      {"case.reference", kString, "", any_value(),
       "paper, figure or equation the scene reproduces"},

      // [physics]
      {"physics.K", kReal, kRequired, open_closed(0, 100),
       "Knudsen number K = (2/sqrt(pi)) / (sigma Lx n0); the hydrodynamics needs K << 1, and "
       "beyond 100 the transport coefficients (K^2) overflow the step control"},
      {"physics.q", kReal, kRequired, open_closed(0, 0.5), "inelasticity q = (1 - r)/2"},
      {"physics.area_fraction", kReal, 0.0, closed_open(0, 1),
       "mean area fraction phi0 of the dense-gas closure (phi = phi0 n; 0 = not given; "
       "hydro.closure = \"enskog\" needs it, \"garzo_dufty\" is dense with it, a comparison "
       "takes md.area_fraction)"},
      {"physics.cooling", kString, "small_q", one_of(hydro::cooling_rate_names()),
       "inelastic loss of the cooling term: \"small_q\" = the paper's 8q/K (1 - r^2 ~ 4q), "
       "\"exact\" = times (1 - q) (1 - r^2 = 4q(1 - q))"},

      // [initial]: initial.type and the parameters its generators declare (hydro/initial_*.cpp),
      // inserted here by with_initial_condition_rows().

      // [hydro]
      {"hydro.enabled", kBoolean, true, any_value(),
       "run the hydro for this case (false: a particle-only scene)"},
      {"hydro.cells", kInteger, 2000, closed_closed(4, kMaxCells), "number of Lagrangian cells"},
      {"hydro.t_end", kReal, 4.0, positive(),
       "end time of the hydro run (with compare.enabled: md.t_end in scaled units instead)"},
      {"hydro.output_times", kReals, kEmpty, increasing(non_negative()),
       "times at which fields are written"},
      {"hydro.cfl", kReal, 2.0, open_closed(0, 20),
       "acoustic Courant number (pressure is implicit in its adiabatic part, so > 1 is stable)"},
      {"hydro.max_compression", kReal, 0.1, closed_closed(1e-6, 0.5),
       "largest relative change of a cell width per step (below 1e-6 the round-off in a "
       "flow at rest stalls the step)"},
      {"hydro.max_temperature_change", kReal, 0.2, closed_open(1e-6, 1),
       "largest relative change of a cell temperature per step (below 1e-6 the round-off in "
       "a gas at rest stalls the step)"},
      {"hydro.dt_max", kReal, 0.05, positive(), "largest time step"},
      {"hydro.stop_density", kReal, 1e6, greater_than(1),
       "stop (singularity) when the peak density exceeds this"},
      {"hydro.min_cell_width", kReal, 1e-14, positive(),
       "stop (singularity) when a cell gets narrower than this"},
      {"hydro.transverse_velocity", kBoolean, false, any_value(),
       "evolve the transverse velocity v_y"},
      {"hydro.node_offset", kReal, 0.5, closed_open(0, 1),
       "position of the first node in units of the cell width"},
      {"hydro.progress_seconds", kReal, 2.0, positive(),
       "wall-clock seconds between progress lines"},
      {"hydro.series_every", kInteger, 1, closed_closed(1, kIntMax),
       "write the time series every N steps"},
      {"hydro.closure", kString, "dilute", one_of(hydro::closure_names()),
       "constitutive closure: \"dilute\" = the paper's Eqs. (1)-(2), \"enskog\" = dense hard "
       "disks, \"garzo_dufty\" = inelastic hard disks' transport, dense with "
       "physics.area_fraction, \"formula\" = the user's formulas hydro.pressure ... "
       "(docs/physics.md §9)"},
      {"hydro.viscosity_factor", kReal, 1.0, open_closed(0, 100),
       "multiplies the closure's viscosities: an injected model error 1 + eps for the atlas's "
       "comparison power (docs/atlas.md); 1 = the closure as written"},
      {"hydro.conductivity_factor", kReal, 1.0, open_closed(0, 100),
       "multiplies the closure's heat conductivity (an injected model error, as "
       "hydro.viscosity_factor)"},
      {"hydro.mu_factor", kReal, 1.0, open_closed(0, 100),
       "multiplies the closure's heat-flux coefficient mu of q = -kappa dT/dx - mu dn/dx (an "
       "injected model error, as hydro.viscosity_factor; no effect where mu = 0)"},
      {"hydro.cooling_factor", kReal, 1.0, open_closed(0, 100),
       "multiplies the closure's cooling sink, and so Haff's 1/t0 (an injected model error, as "
       "hydro.viscosity_factor)"},
      // The closures' own keys (hydro/closure_registry.cpp), if any, are inserted here by
      // case_schema().

      // [analysis]
      {"analysis.tau_fit_min_density", kReal, 10.0, greater_than(1),
       "lowest peak density used in the singularity-time fit"},
      {"analysis.tau_fit_max_density", kReal, 1e4, greater_than(1),
       "highest peak density used in the singularity-time fit"},
      {"analysis.profile_fit_x_min", kReal, 1e-3, positive(),
       "smallest distance from the peak used in the profile fit"},
      {"analysis.profile_fit_x_max", kReal, 2e-2, positive(),
       "largest distance from the peak used in the profile fit"},
      {"analysis.collapse_tolerance", kReal, 0.015, positive(),
       "relative tolerance of the self-similar profile collapse"},

      // [convergence]
      {"convergence.cells", kIntegers, kEmpty, increasing(closed_closed(4, kMaxCells)),
       "cell counts of the convergence study (empty = no study)"},
      {"convergence.t", kReal, 1.0, positive(), "time at which the convergence study compares"},
      {"convergence.cfl", kReal, 0.5, open_closed(0, 20),
       "Courant number of the study; its step is also capped at cfl/cells, so dt ~ h"},

      // [md]: the particle engine (2D inelastic disks; sigma = m = T0 = 1, times in
      // sigma sqrt(m/T0)). The scene is given either in particle terms (md.particles > 0) or
      // by physics.K through the scaled mapping (md.particles = 0), docs/physics.md §4.
      {"md.enabled", kBoolean, false, any_value(), "run the particle engine for this case"},
      {"md.engine", kString, "lammps", one_of(md::particle_engine_names()),
       "particle engine (md_bridge/particle_engine_registry.cpp)"},
      {"md.particles", kInteger, 0, closed_closed(0, 1e9),
       "number of disks N; 0 = from physics.K with md.area_fraction and md.box_width"},
      {"md.area_fraction", kReal, 0.05, open_closed(0, 0.5), "area fraction phi"},
      {"md.box_width", kReal, 20.0, at_least(4), "box width Ly in sigma"},
      {"md.restitution", kReal, 0.0, closed_closed(0, 1),
       "coefficient of normal restitution r; 0 = 1 - 2 physics.q; with the hydro running, "
       "r and physics.q follow the one set last"},
      {"md.seed", kInteger, 1, closed_closed(0, kIntMax),
       "seed of the particle sample (ensemble member m: seed + m)"},
      {"md.ensemble", kInteger, 1, closed_closed(1, 1000), "number of independent seeds"},
      {"md.t_end", kReal, 100.0, positive(), "end time in MD units"},
      {"md.output_times", kReals, kEmpty, increasing(non_negative()),
       "snapshot times of the coarse-grained fields, MD units"},
      {"md.sample_interval", kReal, 1.0, positive(), "time between time-series samples, MD units"},
      {"md.bins", kInteger, 100, closed_closed(1, 1e6), "coarse-graining bins along x"},
      {"md.kernel", kString, "bin", one_of({"bin", "gaussian", "lucy"}), "coarse-graining kernel"},
      {"md.kernel_width", kReal, 0.0, non_negative(),
       "kernel width in sigma (gaussian, lucy); 0 for bins"},
      // The particle engines' own keys (md_bridge/*_engine.cpp, keys()) are inserted here by
      // case_schema().
      {"md.accept_long_run", kBoolean, false, any_value(),
       "run a particle scene whose work per rank is above the limit of a run that can finish "
       "here (1e13 atom-steps, 3e10 collisions; the estimate is in --dry-run) instead of "
       "refusing it"},
      {"md.snapshot_interval", kReal, 0.0, non_negative(),
       "H5MD particle snapshots every this much MD time; 0 = none"},
      {"md.checkpoint_interval", kReal, 300.0, non_negative(),
       "wall seconds between checkpoints of the particle run (`granvv resume`); 0 = none"},
      {"md.time_unit", kString, "md", one_of({"md", "haff"}),
       "unit of md.t_end, md.sample_interval and md.output_times: MD time (sigma sqrt(m/T0)) "
       "or the kinetic-theory Haff time t0 with chi(phi) (same cooling depth for every r)"},
      {"md.haff_mode_energy_fraction", kReal, 0.01, open_open(0, 1),
       "the Haff fit ends where the box's lowest Fourier modes of the momentum carry more than "
       "this fraction of the kinetic energy (docs/physics.md §12), in a gas that starts below it"},

      // [compare]: hydro and coarse-grained particles side by side (needs md.enabled). The
      // compared times are md.output_times; the hydro runs to md.t_end (both in scaled units).
      {"compare.enabled", kBoolean, false, any_value(),
       "run hydro and MD side by side and compare the fields"},
      {"compare.hydro_initial", kString, "md", one_of({"md", "case"}),
       "hydro start: the MD's coarse-grained t = 0 fields (ensemble mean), or the case's "
       "initial fields as given to the MD"},
      {"compare.sigmas", kReal, 3.0, positive(),
       "a bin agrees when |hydro - MD| < sigmas standard errors of the MD mean"},
      {"compare.agreement_fraction", kReal, 0.95, open_closed(0, 1),
       "a field agrees at a time when at least this fraction of its bins agree"},
      {"compare.density_modes", kInteger, 0, closed_closed(0, 1e4),
       "track the density Fourier modes k = 1..this against linear theory (0 = none)"},
      {"compare.closures", kStrings, Default::list_of_key("hydro.closure"),
       distinct_choices(hydro::closure_names()),
       "the hydro closures run against the one particle ensemble, each compared on its own "
       "(default: [hydro.closure]); the first fills the compare and hydro blocks"},
      {"compare.transport", kString, "none", one_of(transport_choices()),
       "the transport coefficient the scene measures (docs/physics.md §14): the hydro's factor on "
       "it fitted to the particles' mode amplitudes, or \"heat_flux\": kappa and mu from the "
       "particles' own heat flux, no hydro in the fit (\"none\" = no measurement)"},
      {"compare.transport_field", kString, "v_y", one_of(fields::hydrodynamic_fields()),
       "the field whose k = 1 mode measures compare.transport"},
      {"compare.transport_phase", kString, "sin", one_of(compare::mode_phase_names()),
       "the part of the field's k = 1 mode it is read from: sin 2 pi x or cos 2 pi x"},
      {"compare.transport_signals", kStrings, kEmpty,
       distinct_choices_or_none(transport_signal_choices()),
       "the modes a measurement fits at once, each \"<field>:<sin|cos>\" (a sound wave: "
       "[\"v_x:sin\", \"n:cos\", \"T:cos\"]); [] = compare.transport_field's "
       "compare.transport_phase part alone"},
      {"compare.transport_start", kInteger, 0, closed_closed(0, 1e4),
       "the snapshot (index into md.output_times) from which the decay is matched, relative to "
       "the amplitude there: past the particles' kinetic transient of the first collisions"},
      {"compare.transport_factors", kReals, kEmpty, increasing(positive()),
       "the factors on the closure's coefficient at which the hydro runs for the fit, at least "
       "two ([] = 0.5, 0.75, 1, 1.25, 1.5)"},

      // [atlas]: what `granvv atlas` judges and the grid of the hydro's cost knobs
      // (docs/atlas.md). Empty lists take the atlas's defaults around the case's own setting.
      {"atlas.observables", kString, "scene", any_value(),
       "observables judged, comma-separated; \"scene\" = thermal_energy for homogeneous "
       "cooling, else crossing_times, thermal_energy, kinetic_energy, field_n, field_v_x, "
       "field_T"},
      {"atlas.cells", kIntegers, kEmpty, increasing(closed_closed(4, kMaxCells)),
       "hydro cells of the grid ([] = hydro.cells times 1/4, 1/2, 1, 2, 4, 8)"},
      {"atlas.step_factors", kReals, kEmpty, increasing(open_closed(0, 64)),
       "factors on hydro.cfl, hydro.dt_max and hydro.max_compression ([] = 1/4, 1/2, 1, 2, 4)"},
      {"atlas.bins", kInteger, 64, closed_closed(4, 4096),
       "bins on which every model's fields are compared (a particle scene: md.bins)"},
      {"atlas.ensembles", kIntegers, kEmpty, increasing(closed_closed(1, 1000)),
       "ensemble sizes of every particle engine ([] = 1, 2, 4, ..., 512 within the budget)"},
      {"atlas.injected_errors", kReals, kEmpty, increasing(open_closed(0, 99)),
       "relative model errors eps injected into the hydro for the comparison power, each "
       "transport factor times and over (1 + eps) ([] = 0.01 * 2^(k/2), k = 0..16)"},
  };
}

}  // namespace

namespace {

// Every integer key is read as an int: one without a declared upper bound gets INT_MAX, and
// a declared one above it is a mistake in the schema.
std::vector<KeySpec> with_integer_bounds(std::vector<KeySpec> rows) {
  for (KeySpec& row : rows) {
    if (row.type != ValueType::integer && row.type != ValueType::integer_array) continue;
    Constraint& c = row.constraint;
    if (!c.max) c.max = kIntMax, c.max_exclusive = false;
    if (*c.max > kIntMax || (c.min && *c.min < -kIntMax)) {
      throw std::logic_error("case schema: the range of " + row.key + " exceeds an int");
    }
  }
  return rows;
}

}  // namespace

std::optional<KeyOwner> key_owner(std::string_view key) {
  for (const auto& k : md::particle_engine_keys()) {
    if (k.key() == key) return KeyOwner{"md.engine", k.engine};
  }
  for (const auto& k : hydro::closure_keys()) {
    if (k.key() == key) return KeyOwner{"hydro.closure", k.closure};
  }
  return std::nullopt;
}

const std::vector<KeySpec>& case_schema() {
  static const std::vector<KeySpec> rows = [] {
    std::vector<KeySpec> all = rows_without_declared();
    all = inserted_after(std::move(all), "physics", initial_condition_rows());
    all = inserted_after(std::move(all), "hydro.cooling_factor", closure_rows());
    all = inserted_after(std::move(all), "md.kernel_width", particle_engine_rows("md"));
    all = inserted_after(std::move(all), "atlas.ensembles", particle_engine_rows("atlas"));
    return with_integer_bounds(std::move(all));
  }();
  return rows;
}

// ---------------------------------------------------------------------------------------------
// Cross-key checks.
// ---------------------------------------------------------------------------------------------
namespace {

// Blame the key the user touched last.
int origin_rank(const CaseConfig& c, const std::string& key) {
  return c.origin_precedence(key);
}

std::string from(const CaseConfig& c, const std::string& key) {
  const std::string o = c.origin(key);
  return o == "default" ? "(default)" : "(from " + o + ")";
}

// lo_key < hi_key (both reals).
CrossCheck strictly_less(std::string lo_key, std::string hi_key) {
  CrossCheck check;
  check.rule = lo_key + " < " + hi_key;
  check.check = [lo_key, hi_key](const CaseConfig& c) -> std::optional<CrossViolation> {
    const double lo = c.real(lo_key), hi = c.real(hi_key);
    if (lo < hi) return std::nullopt;
    if (origin_rank(c, hi_key) > origin_rank(c, lo_key)) {
      return CrossViolation{
          hi_key, "must be > " + lo_key + " = " + format_real(lo) + " " + from(c, lo_key)};
    }
    return CrossViolation{lo_key,
                          "must be < " + hi_key + " = " + format_real(hi) + " " + from(c, hi_key)};
  };
  return check;
}

// Every element of the array times_key <= end_key (both in the same table's units).
CrossCheck times_within_run(std::string times_key, std::string end_key) {
  CrossCheck check;
  check.rule = "every " + times_key + " <= " + end_key;
  check.check = [times_key, end_key](const CaseConfig& c) -> std::optional<CrossViolation> {
    const double t_end = c.real(end_key);
    const std::vector<double> times = c.reals(times_key);
    if (times.empty() || times.back() <= t_end) return std::nullopt;  // times are increasing
    if (origin_rank(c, end_key) > origin_rank(c, times_key)) {
      return CrossViolation{end_key, "must be >= every " + times_key + ", the last being " +
                                         format_real(times.back()) + " " + from(c, times_key)};
    }
    for (std::size_t i = 0; i < times.size(); ++i) {
      if (times[i] > t_end) {
        return CrossViolation{times_key, "every element must be <= " + end_key + " = " +
                                             format_real(t_end) + " " + from(c, end_key) +
                                             ", but element " + std::to_string(i + 1) + " is " +
                                             format_real(times[i])};
      }
    }
    return std::nullopt;
  };
  return check;
}

// The [compare] table needs the particle engine and takes its times from it.
CrossCheck comparison_is_possible() {
  CrossCheck check;
  check.rule = "compare.enabled needs md.enabled, md.output_times from 0, no hydro.output_times";
  check.check = [](const CaseConfig& c) -> std::optional<CrossViolation> {
    if (!c.boolean("compare.enabled")) return std::nullopt;
    if (!c.boolean("hydro.enabled")) {
      return CrossViolation{"compare.enabled", "needs hydro.enabled = true " +
                                                   from(c, "hydro.enabled") +
                                                   ": a comparison runs both engines"};
    }
    if (!c.boolean("md.enabled")) {
      return CrossViolation{"compare.enabled", "needs md.enabled = true " + from(c, "md.enabled") +
                                                   ": a comparison runs both engines"};
    }
    if (!c.reals("hydro.output_times").empty()) {
      return CrossViolation{"hydro.output_times",
                            "must be empty when compare.enabled: the compared times are "
                            "md.output_times, converted to the hydro's units"};
    }
    const auto times = c.reals("md.output_times");
    if (times.size() < 2) {
      return CrossViolation{"md.output_times",
                            "needs at least two snapshot times for a comparison, the first 0"};
    }
    if (c.string("compare.hydro_initial") == "md" && times.front() != 0.0) {
      return CrossViolation{"md.output_times",
                            "must start at 0 when compare.hydro_initial = \"md\" " +
                                from(c, "compare.hydro_initial") +
                                ": the hydro starts from the MD's t = 0 fields"};
    }
    return std::nullopt;
  };
  return check;
}

// A smooth coarse-graining kernel needs a width.
CrossCheck smooth_kernel_has_width() {
  CrossCheck check;
  check.rule = "md.kernel_width > 0 when md.kernel is gaussian or lucy";
  check.check = [](const CaseConfig& c) -> std::optional<CrossViolation> {
    if (c.string("md.kernel") == "bin" || c.real("md.kernel_width") > 0.0) return std::nullopt;
    return CrossViolation{"md.kernel_width", "must be > 0 (sigma) for md.kernel = \"" +
                                                 c.string("md.kernel") + "\" " +
                                                 from(c, "md.kernel")};
  };
  return check;
}

// A case runs at least one model.
CrossCheck something_runs() {
  CrossCheck check;
  check.rule = "hydro.enabled or md.enabled";
  check.check = [](const CaseConfig& c) -> std::optional<CrossViolation> {
    if (c.boolean("hydro.enabled") || c.boolean("md.enabled")) return std::nullopt;
    return CrossViolation{"hydro.enabled", "is false " + from(c, "hydro.enabled") +
                                               " and so is md.enabled: the case runs nothing"};
  };
  return check;
}

}  // namespace

const std::vector<CrossCheck>& case_cross_checks() {
  static const std::vector<CrossCheck> rows = {
      times_within_run("hydro.output_times", "hydro.t_end"),
      times_within_run("md.output_times", "md.t_end"),
      smooth_kernel_has_width(),
      comparison_is_possible(),
      something_runs(),
      strictly_less("analysis.tau_fit_min_density", "analysis.tau_fit_max_density"),
      strictly_less("analysis.profile_fit_x_min", "analysis.profile_fit_x_max"),
      // convergence.cells (strictly increasing, each >= 4) is a per-key constraint above.
  };
  return rows;
}

// ---------------------------------------------------------------------------------------------
// Machinery.
// ---------------------------------------------------------------------------------------------
std::string KeySpec::section() const {
  const auto dot = key.rfind('.');
  return dot == std::string::npos ? std::string() : key.substr(0, dot);
}

std::string KeySpec::leaf() const {
  const auto dot = key.rfind('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

const KeySpec* find_key_spec(std::string_view key) {
  for (const KeySpec& spec : case_schema()) {
    if (spec.key == key) return &spec;
  }
  return nullptr;
}

bool is_schema_table(std::string_view path) {
  if (path.empty()) return true;
  for (const KeySpec& spec : case_schema()) {
    const std::string_view k = spec.key;
    if (k.size() > path.size() && k.substr(0, path.size()) == path && k[path.size()] == '.') {
      return true;
    }
  }
  return false;
}

std::vector<std::string> schema_children(std::string_view path) {
  std::vector<std::string> out;
  for (const KeySpec& spec : case_schema()) {
    std::string_view rest = spec.key;
    if (!path.empty()) {
      if (rest.size() <= path.size() || rest.substr(0, path.size()) != path ||
          rest[path.size()] != '.') {
        continue;
      }
      rest.remove_prefix(path.size() + 1);
    }
    std::string child(rest.substr(0, rest.find('.')));
    if (std::find(out.begin(), out.end(), child) == out.end()) out.push_back(std::move(child));
  }
  return out;
}

Constraint any_value() {
  return {};
}
Constraint positive() {
  return greater_than(0);
}
Constraint non_negative() {
  return at_least(0);
}
Constraint greater_than(double lo) {
  Constraint c;
  c.min = lo;
  c.min_exclusive = true;
  return c;
}
Constraint at_least(double lo) {
  Constraint c;
  c.min = lo;
  return c;
}
namespace {
Constraint interval(double lo, bool lo_open, double hi, bool hi_open) {
  Constraint c;
  c.min = lo;
  c.min_exclusive = lo_open;
  c.max = hi;
  c.max_exclusive = hi_open;
  return c;
}
}  // namespace
Constraint open_open(double lo, double hi) {
  return interval(lo, true, hi, true);
}
Constraint open_closed(double lo, double hi) {
  return interval(lo, true, hi, false);
}
Constraint closed_open(double lo, double hi) {
  return interval(lo, false, hi, true);
}
Constraint closed_closed(double lo, double hi) {
  return interval(lo, false, hi, false);
}
Constraint one_of(std::vector<std::string> choices) {
  Constraint c;
  c.choices = std::move(choices);
  return c;
}
Constraint distinct_choices(std::vector<std::string> choices) {
  Constraint c = one_of(std::move(choices));
  c.distinct_non_empty = true;
  return c;
}
Constraint distinct_choices_or_none(std::vector<std::string> choices) {
  Constraint c = distinct_choices(std::move(choices));
  c.may_be_empty = true;
  return c;
}
Constraint increasing(Constraint each) {
  each.strictly_increasing = true;
  return each;
}
Constraint name_like() {
  Constraint c;
  c.name = true;
  return c;
}

std::string join(const std::vector<std::string>& items, std::string_view sep) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i) out += sep;
    out += items[i];
  }
  return out;
}

namespace {

// Bounds print as plain numbers: 0, 0.5, 1e+06 -> 1e6.
std::string bound(double x) {
  if (x == std::floor(x) && std::abs(x) < 1e15 && std::abs(x) >= 1e6) {
    const std::string digits = std::to_string(static_cast<long long>(x));
    const std::string shortest = format_real(x);  // 1e7 rather than 10000000
    return shortest.size() < digits.size() && shortest.find('.') == std::string::npos ? shortest
                                                                                      : digits;
  }
  std::string s = format_real(x);
  if (s.size() > 2 && s.compare(s.size() - 2, 2, ".0") == 0) s.resize(s.size() - 2);
  return s;
}

// The numeric / choice part, without the array decorations.
std::string scalar_text(const Constraint& c) {
  if (c.min && c.max) {
    return "in " + std::string(c.min_exclusive ? "(" : "[") + bound(*c.min) + ", " + bound(*c.max) +
           (c.max_exclusive ? ")" : "]");
  }
  if (c.min) return (c.min_exclusive ? "> " : ">= ") + bound(*c.min);
  if (c.max) return (c.max_exclusive ? "< " : "<= ") + bound(*c.max);
  if (!c.choices.empty()) return "one of " + join(c.choices, ", ");
  if (c.name) {
    return "non-empty, at most " + std::to_string(kMaxNameBytes) +
           " bytes, without '/', '\\' or control characters";
  }
  return "";
}

bool number_ok(const Constraint& c, double x) {
  if (c.min && (c.min_exclusive ? !(x > *c.min) : !(x >= *c.min))) return false;
  if (c.max && (c.max_exclusive ? !(x < *c.max) : !(x <= *c.max))) return false;
  return true;
}

bool is_array(ValueType t) {
  return t == ValueType::real_array || t == ValueType::integer_array ||
         t == ValueType::string_array;
}

std::string with_description(std::string text, const KeySpec& spec) {
  return spec.description.empty() ? text : text + " (" + spec.description + ")";
}

// Why the elements of a string array are not allowed (Constraint::choices, distinct_non_empty).
std::optional<std::string> string_array_violation(const KeySpec& spec,
                                                  const std::vector<std::string>& xs) {
  const Constraint& c = spec.constraint;
  if (c.distinct_non_empty && !c.may_be_empty && xs.empty()) {
    return with_description("must name at least one, each " + scalar_text(c), spec);
  }
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const std::string element = "element " + std::to_string(i + 1);
    if (!valid_utf8(xs[i])) return with_description(element + " must be valid UTF-8 text", spec);
    if (!c.choices.empty() &&
        std::find(c.choices.begin(), c.choices.end(), xs[i]) == c.choices.end()) {
      return with_description("every element must be " + scalar_text(c) + ", but " + element +
                                  " is " + toml_quoted(xs[i]),
                              spec);
    }
    if (c.distinct_non_empty && std::find(xs.begin(), xs.begin() + i, xs[i]) != xs.begin() + i) {
      return with_description(element + " (" + toml_quoted(xs[i]) + ") repeats an earlier one",
                              spec);
    }
  }
  return std::nullopt;
}

template <typename T>
std::string number_text(T x) {
  if constexpr (std::is_same_v<T, double>) {
    return format_real(x);
  } else {
    return std::to_string(x);
  }
}

template <typename T>
std::optional<std::string> array_violation(const KeySpec& spec, const std::vector<T>& xs) {
  const Constraint& c = spec.constraint;
  const std::string each = scalar_text(c);
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const double x = static_cast<double>(xs[i]);
    if (!std::isfinite(x)) {
      return with_description("every element must be finite, but element " + std::to_string(i + 1) +
                                  " is " + number_text(xs[i]),
                              spec);
    }
    if (!number_ok(c, x)) {
      return with_description("every element must be " + each + ", but element " +
                                  std::to_string(i + 1) + " is " + number_text(xs[i]),
                              spec);
    }
    if (c.strictly_increasing && i > 0 && !(xs[i] > xs[i - 1])) {
      return with_description("must be strictly increasing, but element " + std::to_string(i + 1) +
                                  " (" + number_text(xs[i]) + ") does not exceed element " +
                                  std::to_string(i) + " (" + number_text(xs[i - 1]) + ")",
                              spec);
    }
  }
  return std::nullopt;
}

// Case-insensitive Levenshtein distance.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (same ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::optional<std::string> closest_match(std::string_view wrong,
                                         const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  std::size_t best_distance = 0;
  for (const std::string& c : candidates) {
    const std::string_view leaf = std::string_view(c).substr(c.rfind('.') + 1);
    const std::size_t allowed = leaf.size() <= 2 ? 0 : leaf.size() <= 5 ? 1 : 2;
    const std::size_t d = edit_distance(wrong, c);
    if (d <= allowed && (!best || d < best_distance)) {
      best = c;
      best_distance = d;
    }
  }
  return best;
}

std::string Constraint::text() const {
  std::string s = scalar_text(*this);
  if (distinct_non_empty && may_be_empty) return "none repeated, each " + s;
  if (distinct_non_empty) return "at least one, none repeated, each " + s;
  if (!strictly_increasing) return s;
  return s.empty() ? "strictly increasing" : "each " + s + ", strictly increasing";
}

std::string type_phrase(ValueType type) {
  switch (type) {
    case ValueType::real:
      return "a real";
    case ValueType::integer:
      return "an integer";
    case ValueType::boolean:
      return "a boolean";
    case ValueType::string:
      return "a string";
    case ValueType::real_array:
      return "an array of reals";
    case ValueType::integer_array:
      return "an array of integers";
    case ValueType::real_table:
      return "a table of named reals";
    case ValueType::string_array:
      return "an array of strings";
  }
  return "a value";
}

std::string expected_phrase(const KeySpec& spec) {
  if (spec.type == ValueType::boolean) return "a boolean (true or false)";
  const std::string c = spec.constraint.text();
  if (c.empty()) return type_phrase(spec.type);
  const bool comma = is_array(spec.type) || spec.type == ValueType::string;
  return type_phrase(spec.type) + (comma ? ", " : " ") + c;
}

std::optional<std::string> constraint_violation(const KeySpec& spec, const Value& value) {
  const Constraint& c = spec.constraint;
  if (value.index() != static_cast<std::size_t>(spec.type)) {
    return "must be " + expected_phrase(spec);
  }
  switch (spec.type) {
    case ValueType::real: {
      const double x = std::get<double>(value);
      if (!std::isfinite(x)) {
        return with_description("must be a finite real" + (c.text().empty() ? "" : " " + c.text()),
                                spec);
      }
      if (!number_ok(c, x)) return with_description("must be " + c.text(), spec);
      return std::nullopt;
    }
    case ValueType::integer:
      if (!number_ok(c, static_cast<double>(std::get<long long>(value)))) {
        return with_description("must be " + c.text(), spec);
      }
      return std::nullopt;
    case ValueType::boolean:
      return std::nullopt;
    case ValueType::string: {
      const std::string& s = std::get<std::string>(value);
      if (!valid_utf8(s)) return with_description("must be valid UTF-8 text", spec);
      if (!c.choices.empty() &&
          std::find(c.choices.begin(), c.choices.end(), s) == c.choices.end()) {
        std::string why = with_description("must be " + c.text(), spec);
        if (const auto guess = closest_match(s, c.choices))
          why += "; did you mean \"" + *guess + "\"?";
        return why;
      }
      if (c.name) {
        const bool bad_char = std::any_of(s.begin(), s.end(), [](char ch) {
          const auto u = static_cast<unsigned char>(ch);
          return ch == '/' || ch == '\\' || u < 0x20 || u == 0x7f;
        });
        if (s.empty() || s == "." || s == ".." || bad_char || s.size() > kMaxNameBytes) {
          return with_description("must be " + c.text(), spec);
        }
      }
      return std::nullopt;
    }
    case ValueType::real_array:
      return array_violation(spec, std::get<std::vector<double>>(value));
    case ValueType::integer_array:
      return array_violation(spec, std::get<std::vector<long long>>(value));
    case ValueType::real_table:
      for (const auto& [name, x] : std::get<RealTable>(value)) {
        if (!std::isfinite(x)) {
          return with_description(
              "every value must be a finite real, but " + name + " is " + format_real(x), spec);
        }
      }
      return std::nullopt;
    case ValueType::string_array:
      return string_array_violation(spec, std::get<std::vector<std::string>>(value));
  }
  return std::nullopt;
}

std::string format_real(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  // Shortest round-trip digits; fixed notation for 1e-4 <= |x| < 1e6 (like %g), else scientific.
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::scientific);
  std::string s(buf, res.ptr);
  const auto e = s.find('e');
  const int exponent10 = std::stoi(s.substr(e + 1));
  if (x == 0 || (exponent10 >= -4 && exponent10 < 6)) {
    res = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::fixed);
    s.assign(buf, res.ptr);
    if (s.find('.') == std::string::npos) s += ".0";  // a TOML float, not an integer
    return s;
  }
  // 1.5e+06 -> 1.5e6, 1e-05 -> 1e-5 (both are valid TOML; the short form reads better).
  return s.substr(0, e) + "e" + std::to_string(exponent10);
}

std::string toml_quoted(std::string_view s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto u = static_cast<unsigned char>(ch);
    switch (ch) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\f':
        out += "\\f";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (u < 0x20 || u == 0x7f) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04X", static_cast<unsigned>(u));
          out += buf;
        } else {
          out += ch;
        }
    }
  }
  return out + "\"";
}

namespace {

// Length of the well-formed UTF-8 sequence starting at s[i], or 0 if there is none.
std::size_t utf8_sequence_length(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t j) { return static_cast<unsigned char>(s[j]); };
  const unsigned char b0 = byte(i);
  if (b0 < 0x80) return 1;
  std::size_t length = 0;
  unsigned char lo = 0x80, hi = 0xBF;  // allowed range of the second byte
  if (b0 >= 0xC2 && b0 <= 0xDF) {
    length = 2;
  } else if (b0 >= 0xE0 && b0 <= 0xEF) {
    length = 3;
    if (b0 == 0xE0) lo = 0xA0;  // no overlong forms
    if (b0 == 0xED) hi = 0x9F;  // no surrogates
  } else if (b0 >= 0xF0 && b0 <= 0xF4) {
    length = 4;
    if (b0 == 0xF0) lo = 0x90;
    if (b0 == 0xF4) hi = 0x8F;  // nothing above U+10FFFF
  } else {
    return 0;
  }
  if (i + length > s.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t j = 2; j < length; ++j) {
    if (byte(i + j) < 0x80 || byte(i + j) > 0xBF) return 0;
  }
  return length;
}

}  // namespace

bool valid_utf8(std::string_view s) {
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t n = utf8_sequence_length(s, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

std::string utf8_repaired(std::string_view s, char replacement) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t n = utf8_sequence_length(s, i);
    if (n == 0) {
      out += replacement;
      ++i;
    } else {
      out.append(s.substr(i, n));
      i += n;
    }
  }
  return out;
}

std::string abbreviated(std::string_view s, std::size_t limit) {
  if (s.size() <= limit) return std::string(s);
  std::size_t cut = limit;
  while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;
  return std::string(s.substr(0, cut)) + "... (" + std::to_string(s.size()) + " bytes)";
}

std::string format_value(const Value& value) {
  struct Visitor {
    std::string operator()(double x) const { return format_real(x); }
    std::string operator()(long long x) const { return std::to_string(x); }
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(const std::string& s) const { return toml_quoted(s); }
    std::string operator()(const std::vector<double>& xs) const {
      std::vector<std::string> items;
      for (const double x : xs) items.push_back(format_real(x));
      return "[" + join(items, ", ") + "]";
    }
    std::string operator()(const std::vector<long long>& xs) const {
      std::vector<std::string> items;
      for (const long long x : xs) items.push_back(std::to_string(x));
      return "[" + join(items, ", ") + "]";
    }
    std::string operator()(const RealTable& table) const {  // a TOML inline table
      std::vector<std::string> items;
      for (const auto& [name, x] : table) {
        const bool bare = !name.empty() && std::all_of(name.begin(), name.end(), [](char ch) {
          return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-';
        });
        items.push_back((bare ? name : toml_quoted(name)) + " = " + format_real(x));
      }
      return items.empty() ? "{}" : "{ " + join(items, ", ") + " }";
    }
    std::string operator()(const std::vector<std::string>& xs) const {
      std::vector<std::string> items;
      for (const std::string& x : xs) items.push_back(toml_quoted(x));
      return "[" + join(items, ", ") + "]";
    }
  };
  return std::visit(Visitor{}, value);
}

}  // namespace granvv::app
