// A model's result as the atlas keeps it (models/setting_run.hpp).
#include "models/setting_run.hpp"

#include <algorithm>

#include "atlas/work_precision.hpp"
#include "compare/binned_energies.hpp"
#include "compare/model_comparison.hpp"
#include "models/compare_scene.hpp"
#include "scene/case_config.hpp"
#include "scene/hydro_scene.hpp"
#include "scene/md_scene.hpp"

namespace granvv::app {

namespace {

using atlas::kNoValue;

// Below this a run is repeated, up to kTimingRepeats runs in all (setting_run.hpp).
constexpr double kShortestTimed = 1e-3;
constexpr int kTimingRepeats = 50;

}  // namespace

compare::EnergiesPerParticle snapshot_energies(const fields::FieldSnapshot& s) {
  fields::FieldSnapshot full = s;  // flow by inertia has no T, a 1D hydro may have no v_y
  if (full.T.empty()) full.T.assign(full.n.size(), 0.0);
  if (full.v_y.empty()) full.v_y.assign(full.n.size(), 0.0);
  return compare::box_energies(full);
}

HydroScene atlas_hydro_scene(const CaseConfig& config, const AtlasScene& scene) {
  HydroScene hydro = hydro_scene_from(config);
  hydro.convergence_cells.clear();
  if (scene.particles) {
    const auto md = md_scene_from(config, hydro);
    fields::FieldSeries times;  // align_hydro_with_md reads only the snapshots' times
    for (double t : config.reals("md.output_times")) {
      fields::FieldSnapshot s;
      s.t = t;
      times.snapshots.push_back(s);
    }
    align_hydro_with_md(hydro, md->spec.scene, config.real("md.t_end"), times);
  }
  return hydro;
}

fields::FieldSeries compared_times(const AtlasScene& scene) {
  fields::FieldSeries times;
  for (double t : scene.times) {
    fields::FieldSnapshot s;
    s.t = t;
    times.snapshots.push_back(s);
  }
  return times;
}

void take_result(const AtlasScene& scene, const fields::ModelResult& r, AtlasRun& run) {
  run.cost = r.cost;
  for (const auto& o : r.observables) {
    run.scalars[o.name] = o.value;
    run.scalar_errors[o.name] = o.standard_error;
  }
  if (!r.fields) return;
  fields::FieldSeries kept = fields::FieldSeries::on_bins(-0.5, 1.0, scene.bins);
  for (const auto& [i, j] : compare::common_snapshots(compared_times(scene), *r.fields)) {
    const fields::FieldSnapshot& s = r.fields->snapshots[j];
    const compare::EnergiesPerParticle e = snapshot_energies(s);
    run.times.push_back(scene.times[i]);
    run.thermal.push_back(s.T.empty() ? kNoValue : e.thermal);
    run.flow.push_back(e.flow);
    run.thermal_error.push_back(kNoValue);
    run.flow_error.push_back(kNoValue);
    kept.snapshots.push_back(s);
  }
  run.fields = std::move(kept);
}

void time_by_fastest(fields::ModelCost& cost, const std::function<fields::ModelCost()>& rerun) {
  double spent = cost.wall_seconds;
  for (int k = 1; k < kTimingRepeats && spent < kShortestTimed; ++k) {
    const double again = rerun().wall_seconds;
    spent += again;
    cost.wall_seconds = std::min(cost.wall_seconds, again);
  }
}

}  // namespace granvv::app
