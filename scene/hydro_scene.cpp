#include "scene/hydro_scene.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "hydro/blowup_extrapolation.hpp"
#include "hydro/cell_fields.hpp"
#include "hydro/diagnostics.hpp"
#include "hydro/flow_by_inertia.hpp"
#include "hydro/haff.hpp"
#include "hydro/haff_deviation.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "hydro/linear_stability.hpp"
#include "scene/work_estimate.hpp"

namespace granvv::app {

namespace {

// A wave number needs this many cells per wavelength to be represented at all (2 is the
// Nyquist limit of the mesh; the shipped clustering scene has 6.7 for its highest mode).
constexpr int kMinCellsPerWavelength = 4;
// Putting the random-mode sums on the mesh costs 9 x modes x cells cosines (three fields, a
// 3-point quadrature per cell), twice during validation: 3e8 is a few seconds here.
constexpr double kMaxFieldEvaluations = 3e8;

// The wave-number keys of the initial condition that the case's type reads (the transverse
// mode only when its amplitude is not zero): each must be resolved by the mesh.
void check_resolved_modes(const CaseConfig& c, int cells) {
  const std::string type = c.string("initial.type");
  for (const auto& key : hydro::initial_parameter_keys()) {
    const std::string& name = key.spec.name;
    if (name != "mode" && name != "random_modes" && name != "transverse_mode") continue;
    const bool read = key.types.empty()
                          ? c.real("initial.transverse_amplitude") != 0.0
                          : std::find(key.types.begin(), key.types.end(), type) != key.types.end();
    if (!read) continue;
    const std::string k = "initial." + name;
    const long long mode = c.integer(k);
    if (mode * kMinCellsPerWavelength <= cells) continue;
    const std::string blamed = key_to_blame(c, {k, "hydro.cells"});
    const std::string origin = c.origin(blamed);
    throw ConfigError((origin == "default" ? c.source() : origin) + ": " + blamed + " = " +
                      format_value(c.value(blamed)) + ": " + k + " = " + std::to_string(mode) +
                      " on hydro.cells = " + std::to_string(cells) + " leaves fewer than " +
                      std::to_string(kMinCellsPerWavelength) +
                      " cells per wavelength; the mesh cannot represent it (allowed: " + k +
                      " <= hydro.cells / " + std::to_string(kMinCellsPerWavelength) + " = " +
                      std::to_string(cells / kMinCellsPerWavelength) + ")");
  }
  if (type == "random_modes") {
    refuse_beyond(c, {"initial.random_modes", "hydro.cells"},
                  9.0 * double(c.integer("initial.random_modes")) * cells, kMaxFieldEvaluations,
                  "mode evaluations", "putting the random modes on the mesh");
  }
}

// The clustering and shear modes the theory counts must fit an int (K not absurdly small).
void check_mode_counts(const CaseConfig& c, const HydroScene& s) {
  try {
    const auto closure = make_hydro_closure(s);
    (void)hydro::shear_unstable_modes(*closure);
    (void)hydro::clustering_unstable_modes(*closure);
  } catch (const std::overflow_error&) {
    throw ConfigError(c.origin("physics.K") +
                      ": physics.K = " + format_value(c.value("physics.K")) +
                      ": more than 2^31 unstable modes; K must be larger");
  }
}

// The convergence study compares smooth solutions: it must end before the flow-by-inertia
// singularity of the initial velocity (pressure only delays it), and fit the work budget.
void check_convergence_study(const CaseConfig& c, const HydroScene& s) {
  if (s.convergence_cells.empty()) return;
  if (const auto inertia = hydro::inertia_reference(s.initial)) {
    const double tau = inertia->flow.singularity_time();
    if (std::isfinite(tau) && s.convergence_t >= tau) {
      const std::string blamed =
          key_to_blame(c, {"convergence.t", "initial.velocity_amplitude", "initial.mode"});
      const std::string origin = c.origin(blamed);
      throw ConfigError((origin == "default" ? c.source() : origin) + ": " + blamed + " = " +
                        format_value(c.value(blamed)) +
                        ": convergence.t = " + format_real(s.convergence_t) +
                        " must be before the flow-by-inertia singularity of the initial "
                        "velocity, tau = " +
                        format_real(tau) + ": the study needs a smooth solution");
    }
  }
  double cell_steps = 0.0;  // each level's step is at most min(dt_max, cfl / cells)
  for (const int n : s.convergence_cells) {
    cell_steps +=
        double(n) * s.convergence_t / std::min(s.control.time_step.dt_max, s.convergence_cfl / n);
  }
  refuse_beyond(c, {"convergence.t", "convergence.cells", "convergence.cfl", "hydro.dt_max"},
                cell_steps, kMaxCellSteps, "cell-steps", "the convergence study");
}

// hydro.closure, physics.cooling and physics.area_fraction. A comparison's hydro models the
// particle scene, so its phi0 is md.area_fraction, and a physics.area_fraction that says
// otherwise is refused (0, the default, is "not given": a resolved case.toml runs again).
void read_closure(const CaseConfig& c, HydroScene& s) {
  s.closure = c.string("hydro.closure");
  s.cooling = hydro::cooling_rate_from_name(c.string("physics.cooling"));
  s.area_fraction = c.real("physics.area_fraction");
  for (const auto& [key, factor] : transport_factor_keys()) s.factors.*factor = c.real(key);
  if (c.boolean("md.enabled") && c.boolean("compare.enabled")) {
    const double scene = c.real("md.area_fraction");
    if (s.area_fraction != 0.0 && s.area_fraction != scene) {  // 0: not given
      throw ConfigError(
          c.origin("physics.area_fraction") +
          ": physics.area_fraction = " + format_value(c.value("physics.area_fraction")) +
          " contradicts md.area_fraction = " + format_value(c.value("md.area_fraction")) +
          " of the particle scene the hydro models (allowed: leave it unset or "
          "equal to md.area_fraction)");
    }
    s.area_fraction = scene;
  }
  read_closure_keys(c, s.closure_settings);
  if (const auto problem = hydro::closure_parameter_problem(s.closure, closure_parameters(s))) {
    const std::string key = closure_problem_key(s.closure, *problem);
    const std::string origin = c.origin(key);
    throw ConfigError((origin == "default" ? c.source() : origin) + ": " + key + " = " +
                      format_value(c.value(key)) + ": hydro.closure = \"" + s.closure +
                      "\": " + problem->reason);
  }
}

}  // namespace

const std::vector<std::pair<std::string, double hydro::TransportFactors::*>>&
transport_factor_keys() {
  static const std::vector<std::pair<std::string, double hydro::TransportFactors::*>> keys = {
      {"hydro.viscosity_factor", &hydro::TransportFactors::viscosity},
      {"hydro.conductivity_factor", &hydro::TransportFactors::conductivity},
      {"hydro.cooling_factor", &hydro::TransportFactors::cooling},
      {"hydro.mu_factor", &hydro::TransportFactors::mu},
  };
  return keys;
}

void set_transport_factor(HydroScene& scene, const std::string& key, double value) {
  for (const auto& [name, factor] : transport_factor_keys()) {
    if (name == key) {
      scene.factors.*factor = value;
      return;
    }
  }
  throw std::invalid_argument("set_transport_factor: \"" + key + "\" is not a factor key");
}

hydro::ClosureParameters closure_parameters(const HydroScene& scene) {
  hydro::ClosureParameters params = scene.closure_settings;
  params.physics = scene.physics;
  params.extra["area_fraction"] = scene.area_fraction;
  params.cooling = scene.cooling;
  params.factors = scene.factors;
  return params;
}

void read_closure_keys(const CaseConfig& c, hydro::ClosureParameters& params) {
  for (const auto& key : hydro::closure_keys()) {
    const Value& value = c.value(key.key());
    switch (find_key_spec(key.key())->type) {
      case ValueType::integer:
        params.extra[key.spec.name] = double(std::get<long long>(value));
        break;
      case ValueType::boolean:
        params.extra[key.spec.name] = double(std::get<bool>(value));
        break;
      case ValueType::string:
        params.texts[key.spec.name] = std::get<std::string>(value);
        break;
      case ValueType::real_table:
        params.tables[key.spec.name] = std::get<RealTable>(value);
        break;
      default:
        params.extra[key.spec.name] = std::get<double>(value);
    }
  }
}

std::string closure_problem_key(const std::string& closure,
                                const hydro::ClosureParameterProblem& problem) {
  for (const auto& key : hydro::closure_keys()) {
    if (key.closure == closure && key.spec.name == problem.parameter) return key.key();
  }
  return "physics." + problem.parameter;
}

std::unique_ptr<hydro::Closure> make_hydro_closure(const HydroScene& scene) {
  return hydro::make_closure(scene.closure, closure_parameters(scene));
}

hydro::InitialParameters initial_parameters_from(const CaseConfig& c) {
  hydro::ParameterSet values;
  for (const auto& key : hydro::initial_parameter_keys()) {
    const std::string name = "initial." + key.spec.name;
    if (key.spec.is_integer()) {
      values.set(key.spec.name, static_cast<long long>(c.int_value(name)));
    } else if (key.spec.is_text()) {
      values.set(key.spec.name, c.string(name));
    } else if (key.spec.is_named_reals()) {
      values.set(key.spec.name, std::get<RealTable>(c.value(name)));
    } else {
      values.set(key.spec.name, c.real(name));
    }
  }
  return hydro::initial_parameters(c.string("initial.type"), std::move(values));
}

HydroScene hydro_scene_from(const CaseConfig& c) {
  HydroScene s;
  s.physics = {c.real("physics.K"), c.real("physics.q")};
  s.initial = initial_parameters_from(c);
  const auto& ini = s.initial;
  read_closure(c, s);
  s.cells = c.int_value("hydro.cells");
  s.node_offset = c.real("hydro.node_offset");
  s.transverse = c.boolean("hydro.transverse_velocity");
  s.progress_seconds = c.real("hydro.progress_seconds");
  auto& ctl = s.control;
  ctl.t_end = c.real("hydro.t_end");
  ctl.output_times = c.reals("hydro.output_times");
  ctl.time_step.cfl = c.real("hydro.cfl");
  ctl.time_step.max_compression = c.real("hydro.max_compression");
  ctl.time_step.max_temperature_change = c.real("hydro.max_temperature_change");
  ctl.time_step.dt_max = c.real("hydro.dt_max");
  ctl.stop_density = c.real("hydro.stop_density");
  ctl.min_cell_width = c.real("hydro.min_cell_width");
  ctl.series_every = c.int_value("hydro.series_every");
  s.tau_fit_min_density = c.real("analysis.tau_fit_min_density");
  s.tau_fit_max_density = c.real("analysis.tau_fit_max_density");
  s.profile_fit_x_min = c.real("analysis.profile_fit_x_min");
  s.profile_fit_x_max = c.real("analysis.profile_fit_x_max");
  s.collapse_tolerance = c.real("analysis.collapse_tolerance");
  s.convergence_cells = c.int_values("convergence.cells");
  s.convergence_t = c.real("convergence.t");
  s.convergence_cfl = c.real("convergence.cfl");

  // Combinations the engine cannot run.
  if (s.convergence_cells.size() == 1 || s.convergence_cells.size() == 2) {
    throw ConfigError(c.origin("convergence.cells") + ": convergence.cells has " +
                      std::to_string(s.convergence_cells.size()) +
                      " levels: an observed order needs at least 3 (or [] for no study)");
  }
  const std::string mesh = hydro::convergence_mesh_problem(s.convergence_cells, s.node_offset);
  if (!mesh.empty())
    throw ConfigError(c.origin("convergence.cells") + ": convergence.cells: " + mesh);
  if (const auto problem = hydro::initial_parameter_problem(ini, s.transverse)) {
    const std::string key = "initial." + problem->parameter;
    throw ConfigError(c.origin(key) + ": " + key + " = " + abbreviated(format_value(c.value(key))) +
                      ": " + problem->reason);
  }
  check_mode_counts(c, s);
  check_resolved_modes(c, s.cells);
  check_convergence_study(c, s);
  try {
    // In a comparison the hydro runs to md.t_end instead (md_scene_from checks that run).
    if (c.boolean("hydro.enabled") && !c.boolean("compare.enabled")) {
      check_hydro_work(c, s, ctl.t_end, "hydro.t_end");
    }
    // The fields where every mesh of the run evaluates them (the run's and the convergence
    // study's), before anything is written.
    const auto fields = hydro::make_initial_fields(ini, *make_hydro_closure(s));
    std::vector<long long> meshes = {s.cells};
    meshes.insert(meshes.end(), s.convergence_cells.begin(), s.convergence_cells.end());
    for (const long long cells : meshes) {
      const auto state = hydro::discretize(fields, int(cells), s.node_offset, s.transverse);
      for (int i = 0; i < state.cells(); ++i) {
        if (!(state.cell_mass[i] > 0.0) || !(state.cell_T[i] > 0.0)) {
          throw ConfigError("initial.type = " + ini.type +
                            ": the initial density or temperature is not positive in cell " +
                            std::to_string(i) + " of " + std::to_string(cells) +
                            "; lower the perturbation amplitudes");
        }
      }
    }
  } catch (const hydro::InitialFieldError& e) {
    throw initial_field_refusal(c, e);
  }
  return s;
}

ConfigError initial_field_refusal(const CaseConfig& c, const hydro::InitialFieldError& e) {
  const std::string key = "initial." + e.parameter;
  return ConfigError(c.origin(key) + ": " + key + " = " + abbreviated(format_value(c.value(key))) +
                     ": " + e.what());
}

void check_hydro_work(const CaseConfig& c, const HydroScene& s, double t_end,
                      const std::string& end_key) {
  const auto& step = s.control.time_step;
  // At least t_end / dt_max steps, before anything is allocated.
  refuse_beyond(c, {end_key, "hydro.dt_max", "hydro.cells"},
                double(s.cells) * std::ceil(t_end / step.dt_max), kMaxCellSteps, "cell-steps",
                "the hydro run (" + end_key + " / hydro.dt_max steps)");
  // The first step's size, kept to t_end: an estimate of the whole run.
  const auto closure = make_hydro_closure(s);
  const auto state = hydro::discretize(hydro::make_initial_fields(s.initial, *closure), s.cells,
                                       s.node_offset, false);
  hydro::CellGeometry cells;
  hydro::measure_cells(state, cells);
  const hydro::TimeStepLimit first = hydro::TimeStepLimiter(*closure, step).limit(state, cells);
  const std::string limiting = first.limited_by == "compression" ? "hydro.max_compression"
                               : first.limited_by == "sound"     ? "hydro.cfl"
                                                                 : "hydro.dt_max";
  refuse_beyond(
      c, {end_key, limiting, "hydro.cells", "physics.K"}, double(s.cells) * t_end / first.dt,
      kMaxCellSteps, "cell-steps",
      "the hydro run (first step " + format_real(first.dt) + ", limited by " + limiting + ")");
}

HydroOutcome run_hydro_scene(const HydroScene& scene, const hydro::ProgressCallback& progress) {
  HydroOutcome out;
  const auto closure = make_hydro_closure(scene);
  out.fields = scene.given_fields ? *scene.given_fields
                                  : hydro::make_initial_fields(scene.initial, *closure);
  out.unstable_modes = hydro::clustering_unstable_modes(*closure);
  out.shear_unstable_modes = hydro::shear_unstable_modes(*closure);
  hydro::LagrangianState initial =
      hydro::discretize(out.fields, scene.cells, scene.node_offset, scene.transverse);
  const hydro::Diagnostics cells0 = hydro::diagnose(initial);
  double momentum_y = 0.0;
  for (int j = 0; j < initial.cells() && initial.has_transverse(); ++j) {
    momentum_y += hydro::node_mass(initial, j) * initial.node_vy[j];
  }
  out.initial_cells = {cells0.mass, cells0.momentum, momentum_y, cells0.energy()};
  out.initial_given = hydro::field_totals(out.fields, scene.transverse);
  out.run = hydro::run_hydro(*closure, std::move(initial), scene.control, progress);
  const auto& run = out.run;
  out.cell_fields = hydro::cell_field_series(run.snapshots);

  // Paper Fig. 3: flow by inertia from the initial velocity profile.
  const auto inertia = hydro::inertia_reference(scene.initial);
  if (inertia) {
    const double tau = inertia->flow.singularity_time();
    if (std::isfinite(tau)) out.inertia_tau = tau;
  }
  for (const auto& snap : run.snapshots) {
    SnapshotCheck check;
    check.t = snap.state.t;
    check.label = snap.label;
    check.diagnostics = hydro::diagnose(snap.state);
    for (int j = 0; j < snap.state.cells(); ++j) {
      const double xi = snap.state.node_x[j] - snap.state.t * snap.state.node_v[j];
      check.xi.push_back(hydro::wrap_position(xi));
      check.inertia_v0.push_back(out.fields.v(xi));
    }
    if (inertia) {
      check.collapse_error =
          hydro::inertia_collapse_error(snap.state, out.fields.v, inertia->velocity_scale);
    }
    out.snapshots.push_back(std::move(check));
  }

  // Paper Fig. 4: tau from 1/n_max(t), the density profile near the peak.
  out.singularity = hydro::fit_singularity_time(
      run.series.t, run.series.n_max, scene.tau_fit_min_density, scene.tau_fit_max_density);
  if (run.status == hydro::RunStatus::singularity) {
    out.blowup_time = hydro::extrapolate_blowup_time(run.series.t, run.series.n_max);
  }
  for (auto it = run.snapshots.rbegin(); it != run.snapshots.rend(); ++it) {
    if (it->label != "output") continue;
    out.profile_slope = hydro::fit_density_profile_slope(it->state, scene.profile_fit_x_min,
                                                         scene.profile_fit_x_max);
    out.profile_slope_time = it->state.t;
    break;
  }

  out.haff_max_relative_error = hydro::haff_max_relative_error(run.series.t, run.series.T_mean,
                                                               hydro::haff_time_scale(*closure));

  if (const auto seeded = hydro::seeded_eigenmode(scene.initial)) {
    std::vector<hydro::LagrangianState> states;
    for (const auto& snap : run.snapshots) states.push_back(snap.state);
    out.linear_rate = hydro::measure_linear_rate(states, *closure, seeded->mode, seeded->branch);
  }
  if (scene.convergence_cells.size() >= 3) {
    auto time_step = scene.control.time_step;
    time_step.cfl = scene.convergence_cfl;
    out.convergence = hydro::run_convergence_study(
        *closure, out.fields, scene.convergence_cells, scene.node_offset, scene.convergence_t,
        time_step, {scene.control.stop_density, scene.control.min_cell_width}, progress);
  }
  return out;
}

}  // namespace granvv::app
