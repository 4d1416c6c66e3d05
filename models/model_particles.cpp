// The particles as a model of the ladder (models/model.hpp).
#include "models/model.hpp"

namespace granvv::app {

ParticleModel::ParticleModel(MdScene scene, md::ParticleEngine& engine, Progress progress,
                             const MdCheckpointing* checkpointing)
    : scene_(std::move(scene)),
      engine_(engine),
      progress_(std::move(progress)),
      checkpointing_(checkpointing) {}

std::string ParticleModel::name() const {
  return "particles/" + scene_.engine;
}

fields::ModelResult ParticleModel::run() {
  outcome_ = run_md_scene(scene_, engine_, progress_, checkpointing_);
  std::vector<fields::FieldSeries> members;
  for (const auto& run : outcome_.runs) members.push_back(run.fields);
  return particle_result(
      scene_, outcome_,
      compare::ensemble_mean_fields(members, scaled_units(scene_.spec.scene)).fields);
}

compare::ScaledUnits scaled_units(const md::ParticleScene& scene) {
  return {scene.box_length, scene.number_density(), scene.box_length};
}

fields::ModelResult particle_result(const MdScene& scene, const MdOutcome& out,
                                    fields::FieldSeries mean_fields) {
  fields::ModelResult r;
  r.model = "particles/" + scene.engine;
  r.fields = std::move(mean_fields);
  const auto& sc = scene.spec.scene;
  r.observables.push_back(
      {"haff_t0", sc.scaled_time(out.haff.t0), sc.scaled_time(out.haff.t0_error)});
  // The box's pressure over the run in the scaled unit n0 T0 (T0 = 1 in MD units), and P/(nT).
  const double n0 = sc.number_density();
  r.observables.push_back({"pressure", out.pressure.mean / n0, out.pressure.error / n0});
  r.observables.push_back({"compressibility", out.compressibility.mean, out.compressibility.error});
  r.cost = out.cost;
  return r;
}

}  // namespace granvv::app
