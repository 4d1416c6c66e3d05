// The hydro as a model of the ladder (models/model.hpp).
#include <cstdio>

#include "compare/binned_fields.hpp"
#include "hydro/closure.hpp"
#include "hydro/haff.hpp"
#include "models/model.hpp"

namespace granvv::app {

HydroModel::HydroModel(HydroScene scene, int bins, hydro::ProgressCallback progress)
    : scene_(std::move(scene)), bins_(bins), progress_(std::move(progress)) {}

std::string HydroModel::name() const {
  return "hydro/" + scene_.closure;
}

fields::ModelResult HydroModel::run() {
  outcome_ = run_hydro_scene(scene_, progress_);
  return hydro_result(scene_, outcome_, bins_);
}

std::string crossing_time_name(double level) {
  char name[64];
  std::snprintf(name, sizeof name, "crossing_time_n%g", level);
  return name;
}

fields::ModelResult hydro_result(const HydroScene& scene, const HydroOutcome& out, int bins) {
  fields::ModelResult r;
  r.model = "hydro/" + scene.closure;
  if (bins > 0) {
    fields::FieldSeries f = fields::FieldSeries::on_bins(-0.5, 1.0, bins);
    for (const auto& snap : out.run.snapshots) {
      fields::FieldSnapshot s = compare::bin_lagrangian_state(snap.state, bins);
      s.t = snap.state.t;
      s.label = snap.label;
      f.snapshots.push_back(std::move(s));
    }
    r.fields = std::move(f);
  } else {
    r.fields = out.cell_fields;
  }
  const auto closure = make_hydro_closure(scene);
  r.observables.push_back({"haff_t0", hydro::haff_time_scale(*closure)});
  r.observables.push_back({"t_final", out.run.snapshots.back().state.t});
  if (out.run.status == hydro::RunStatus::singularity && out.singularity) {
    r.observables.push_back({"singularity_time", out.singularity->tau});
  }
  for (const auto& [level, t] : out.run.crossing_times) {
    r.observables.push_back({crossing_time_name(level), t});
  }
  r.cost = {out.run.wall_seconds, double(out.run.steps) * scene.cells, "cell_steps"};
  return r;
}

}  // namespace granvv::app
