#pragma once
// The runs of `granvv atlas` (docs/atlas.md): one model of a scene's ladder at one setting of
// its cost knobs, run through the model interface (app/model.hpp) and reduced to what the atlas
// judges; and the cache that keeps each run by its resolved case, so that a re-run (a larger
// budget, an interrupted atlas) only adds runs.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/case_catalog.hpp"
#include "fields/model_result.hpp"

namespace granvv::app {

// One setting of one model of the ladder.
struct AtlasSetting {
  std::string model;  // "haff_ode", "flow_by_inertia", "hydro/<closure>"
  // The hydro's knobs: cells, and the factor on its step bounds hydro.cfl, hydro.dt_max and
  // hydro.max_compression (1 = the case's own); 0 for the exact solutions, which have none.
  int cells = 0;
  double step_factor = 0.0;
};

// "hydro/dilute cells=500 step_factor=1", "haff_ode".
std::string describe(const AtlasSetting& setting);

// What the atlas keeps of a run.
struct AtlasRun {
  AtlasSetting setting;
  // "ok", or how it failed: inadmissible_step, non_finite, step_underflow, closure_limit,
  // unresolved_singularity (a cell reached hydro.min_cell_width before the peak density reached
  // hydro.stop_density), refused (the case schema or the scene refused the setting).
  std::string status;
  std::string reason;  // the model's own words
  fields::ModelCost cost;
  long long rejected_steps = 0;
  std::map<std::string, double> crossing_times;  // "crossing_time_n10" -> t
  // The compared times the run reached, its energies per particle there (NaN where the model
  // has none: flow by inertia has no temperature) and its fields on the atlas's bins.
  std::vector<double> times, thermal, flow;
  std::optional<fields::FieldSeries> fields;
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
  int bins = 0;                // atlas.bins
  double area_fraction = 0.0;  // physics.area_fraction (a particle scene's md.area_fraction)
  bool particles = false;      // md.enabled
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
// case). A setting the schema or the scene refuses comes back with status "refused".
AtlasRun run_atlas_setting(const AtlasScene& scene, const AtlasSetting& setting,
                           const std::filesystem::path& cache_dir);

}  // namespace granvv::app
