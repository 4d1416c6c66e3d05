#pragma once
// The runs of `granvv atlas` (docs/atlas.md): one model of a scene's ladder at one setting of
// its cost knobs, run through the model interface (models/model.hpp) and reduced to what the atlas
// judges; and the cache that keeps each run by its resolved case, so that a re-run (a larger
// budget, an interrupted atlas) only adds runs.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "fields/model_result.hpp"
#include "scene/case_catalog.hpp"

namespace granvv::app {

// One setting of one model of the ladder.
struct AtlasSetting {
  // "haff_ode", "flow_by_inertia", "hydro/<closure>", "particles/<engine>" (md.engine)
  std::string model;
  // The hydro's knobs: cells, and the factor on its step bounds hydro.cfl, hydro.dt_max and
  // hydro.max_compression (1 = the case's own); 0 for the other models.
  int cells = 0;
  double step_factor = 0.0;
  // The particles' knobs: md.ensemble, and LAMMPS's contact (md.max_overlap,
  // md.steps_per_contact, md.adaptive_stiffness; 0 for the event-driven engine, which has none).
  int ensemble = 0;
  // The event-driven engine's particle count as a factor on the case's (atlas.particle_factors):
  // md.box_width, and md.particles where the case sets it, times this, so that Lx and the area
  // fraction stay the case's; 1 for every other run.
  double particle_factor = 1.0;
  double max_overlap = 0.0;
  int steps_per_contact = 0;
  bool adaptive_stiffness = false;
  // An injected model error of the hydro (the comparison power): the key of one transport
  // factor (hydro/transport_factors.hpp: "viscosity_factor", "conductivity_factor",
  // "cooling_factor") and the factor set on it; empty for every other run.
  std::string injected;
  double injected_factor = 1.0;
};

// A hydro's setting: its model, cells and step factor.
AtlasSetting hydro_setting(const std::string& model, int cells, double step_factor);

bool is_hydro(const std::string& model);
bool is_particles(const std::string& model);
// The soft-contact engine, whose contact knobs the atlas sweeps.
bool is_lammps(const std::string& model);

// "hydro/dilute cells=500 step_factor=1", "particles/event_driven ensemble=16", "haff_ode",
// "hydro/dilute cells=500 step_factor=1 viscosity_factor=1.1".
std::string describe(const AtlasSetting& setting);
// The setting as atlas.json gives it: the model and its knobs.
nlohmann::json setting_json(const AtlasSetting& setting);

// What the atlas keeps of a run.
struct AtlasRun {
  AtlasSetting setting;
  // "ok", or how it failed: inadmissible_step, non_finite, step_underflow, closure_limit,
  // unresolved_singularity (a cell reached hydro.min_cell_width before the peak density reached
  // hydro.stop_density); for the particles restitution_check_missed, event_rate_runaway,
  // collapse_rule_active (more than atlas.collapse_rule_limit of the collisions changed by the
  // event-driven engine's collapse rules), engine_failed; refused (the case schema or the scene
  // refused the setting); interrupted.
  std::string status;
  std::string reason;  // the model's own words
  fields::ModelCost cost;
  long long rejected_steps = 0;
  // Named scalars with their standard errors (NaN: none): crossing_time_n<level>, haff_t0 and,
  // for the particles, pressure and compressibility (the box's P and P/(nT), averaged over the
  // samples and the members).
  std::map<std::string, double> scalars, scalar_errors;
  // The compared times the run reached, its energies per particle there (NaN where the model
  // has none: flow by inertia has no temperature) with their ensemble standard errors (NaN for
  // a deterministic model) and its fields on the atlas's bins (with the *_stderr of a particle
  // ensemble mean).
  std::vector<double> times, thermal, flow, thermal_error, flow_error;
  std::optional<fields::FieldSeries> fields;
  // A hydro's validity monitors (hydro/validity_monitors.hpp) that reached their threshold: the
  // monitor's name and the first time it did (scaled units).
  std::map<std::string, double> monitor_crossings;
  bool cached = false;  // taken from the cache, not run now
};

// The scene an atlas weighs: the case with the user's --set overrides, and what every run shares.
struct AtlasScene {
  CaseSource source;
  std::vector<std::string> sets;  // the user's, applied before each setting's own
  std::string name;
  // The case's own hydro knobs (the atlas's step factor 1).
  int case_cells = 0;
  double case_cfl = 0.0, case_dt_max = 0.0, case_max_compression = 0.0;
  std::vector<double> times;  // compared times, scaled units
  std::vector<double> crossing_levels;
  int bins = 0;                // atlas.bins (a particle scene's md.bins)
  double area_fraction = 0.0;  // physics.area_fraction (a particle scene's md.area_fraction)
  bool particles = false;      // md.enabled
  // The case's own particle knobs (md.ensemble, md.max_overlap, md.steps_per_contact,
  // md.adaptive_stiffness) and its particle count.
  int case_ensemble = 0;
  double case_max_overlap = 0.0;
  int case_steps_per_contact = 0;
  bool case_adaptive_stiffness = false;
  long long particle_count = 0;
  double case_box_width = 0.0;             // md.box_width
  long long case_particles = 0;            // md.particles (0: the count follows from physics.K)
  double md_t_end = 0.0, md_t_haff = 0.0;  // md.t_end and the kinetic-theory Haff time, MD units
  double t0_theory = 0.0;  // the Enskog kinetic-theory Haff time (with chi), scaled units
  double sigmas = 3.0;     // compare.sigmas: the allowance of σ-aware adequacy
  double collapse_rule_limit = 0.01;  // atlas.collapse_rule_limit
  // What the side-by-side comparison of the comparison power needs: the case's own closure,
  // compare.agreement_fraction, the particles' initial signal-to-noise (scene/md_scene.hpp) and
  // whether the hydro carries v_y (hydro.transverse_velocity).
  std::string closure;
  double agreement_fraction = 0.0;
  double signal_to_noise = 0.0;
  bool transverse = false;
  bool has_inertia_reference = false;
};

// The hydro of the scene as the atlas runs it: without its convergence study and, in a particle
// scene, on the particles' physics and compared times (scaled units) from the case's own fields.
struct HydroScene;
class CaseConfig;
HydroScene atlas_hydro_scene(const CaseConfig& config, const AtlasScene& scene);

// The --set overrides that make `setting` from the case (after the user's).
std::vector<std::string> setting_overrides(const AtlasScene& scene, const AtlasSetting& setting);

// Runs one setting, or takes it from cache_dir (the file named by the hash of its resolved
// case). A setting the schema or the scene refuses comes back with status "refused"; a run a
// signal stopped, with status "interrupted" (and is not cached). Particle runs call MPI: run
// them on the main thread.
AtlasRun run_atlas_setting(const AtlasScene& scene, const AtlasSetting& setting,
                           const std::filesystem::path& cache_dir);

}  // namespace granvv::app
