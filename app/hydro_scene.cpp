#include "app/hydro_scene.hpp"

#include <cmath>

#include "hydro/blowup_extrapolation.hpp"
#include "hydro/cell_fields.hpp"
#include "hydro/flow_by_inertia.hpp"
#include "hydro/haff.hpp"
#include "hydro/haff_deviation.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "hydro/linear_stability.hpp"

namespace granvv::app {

HydroScene hydro_scene_from(const CaseConfig& c) {
  HydroScene s;
  s.physics = {c.real("physics.K"), c.real("physics.q")};
  hydro::ParameterSet values;
  for (const auto& key : hydro::initial_parameter_keys()) {
    const std::string name = "initial." + key.spec.name;
    if (key.spec.is_integer()) {
      values.set(key.spec.name, c.integer(name));
    } else {
      values.set(key.spec.name, c.real(name));
    }
  }
  s.initial = hydro::initial_parameters(c.string("initial.type"), std::move(values));
  const auto& ini = s.initial;
  s.closure = "dilute";  // the paper's closure; a hydro.closure key comes with the closures issue
  s.cells = static_cast<int>(c.integer("hydro.cells"));
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
  ctl.series_every = static_cast<int>(c.integer("hydro.series_every"));
  s.tau_fit_min_density = c.real("analysis.tau_fit_min_density");
  s.tau_fit_max_density = c.real("analysis.tau_fit_max_density");
  s.profile_fit_x_min = c.real("analysis.profile_fit_x_min");
  s.profile_fit_x_max = c.real("analysis.profile_fit_x_max");
  s.collapse_tolerance = c.real("analysis.collapse_tolerance");
  for (long long n : c.integers("convergence.cells")) s.convergence_cells.push_back(int(n));
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
    throw ConfigError(c.origin(key) + ": " + key + " = " + format_value(c.value(key)) + ": " +
                      problem->reason);
  }
  const auto fields = hydro::make_initial_fields(ini, s.physics);
  const auto state = hydro::discretize(fields, s.cells, s.node_offset, false);
  for (int i = 0; i < s.cells; ++i) {
    if (!(state.cell_mass[i] > 0.0) || !(state.cell_T[i] > 0.0)) {
      throw ConfigError("initial.type = " + ini.type +
                        ": the initial density or temperature is not positive in cell " +
                        std::to_string(i) + "; lower the perturbation amplitudes");
    }
  }
  return s;
}

HydroOutcome run_hydro_scene(const HydroScene& scene, const hydro::ProgressCallback& progress) {
  HydroOutcome out;
  const auto& physics = scene.physics;
  const auto closure = hydro::make_closure(scene.closure, {physics, {}});
  out.fields =
      scene.given_fields ? *scene.given_fields : hydro::make_initial_fields(scene.initial, physics);
  out.unstable_modes = hydro::clustering_unstable_modes(physics);
  out.shear_unstable_modes = hydro::shear_unstable_modes(physics);
  out.run = hydro::run_hydro(
      *closure, hydro::discretize(out.fields, scene.cells, scene.node_offset, scene.transverse),
      scene.control, progress);
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
                                                               hydro::haff_time_scale(physics));

  if (const auto seeded = hydro::seeded_eigenmode(scene.initial)) {
    std::vector<hydro::LagrangianState> states;
    for (const auto& snap : run.snapshots) states.push_back(snap.state);
    out.linear_rate = hydro::measure_linear_rate(states, *closure, seeded->mode, seeded->branch);
  }
  if (scene.convergence_cells.size() >= 3) {
    auto time_step = scene.control.time_step;
    time_step.cfl = scene.convergence_cfl;
    out.convergence =
        hydro::run_convergence_study(*closure, out.fields, scene.convergence_cells,
                                     scene.node_offset, scene.convergence_t, time_step);
  }
  return out;
}

}  // namespace granvv::app
