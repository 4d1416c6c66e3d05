#pragma once
// The particles with one registered engine as a family (models/model_family.hpp): an ensemble
// of seeds, whose one knob every engine shares is the ensemble size md.ensemble. An engine with
// more knobs or failure modes of its own derives its family from this one
// (models/family_<engine>.cpp) and is listed in models/family_particles.cpp.
#include <string>
#include <vector>

#include "md_bridge/particle_engine.hpp"
#include "models/model_family.hpp"

namespace granvv::app {

class ParticleFamily : public ModelFamily {
 public:
  explicit ParticleFamily(const std::string& engine, ModelStyle style)
      : ModelFamily("particles/" + engine), engine_(engine), style_(std::move(style)) {}
  FamilyKind kind() const override { return FamilyKind::ensemble; }
  ModelStyle style() const override { return style_; }
  std::vector<KnobSpec> knobs() const override;
  std::optional<std::string> not_applicable(const AtlasScene& scene) const override;
  bool is_case_model(const AtlasScene& scene) const override;
  // The case's own engine, on a scene that measures one transport coefficient.
  bool keeps_transport_fit(const AtlasScene& scene) const override;
  AtlasSetting case_setting(const AtlasScene& scene) const override;
  // The case's own setting with one member.
  AtlasSetting pilot(const AtlasScene& scene) const override;
  // The ensemble sizes of atlas.ensembles, else 1, 2, 4, ... 512.
  std::vector<AtlasSetting> grid(const AtlasScene& scene) const override;
  // The pilot's wall time scaled by the engine's own work estimate of each setting's resolved
  // case (md_bridge/particle_work.hpp): members, particles, and the contact's steps. The pilot's
  // work is estimated once.
  CostEstimate estimate(const AtlasRun& pilot, const AtlasScene& scene) const override;
  // The larger ensemble.
  bool finer(const AtlasSetting& a, const AtlasSetting& b) const override;
  std::vector<std::string> overrides(const AtlasScene& scene, const AtlasSetting& s) const override;
  void run(const AtlasScene& scene, const CaseConfig& config, AtlasRun& run) const override;

 protected:
  // The work of one rank for the setting, in its engine's unit (scene/work_estimate.hpp); 0
  // where the schema or the scene refuses the setting.
  static double estimated_work(const AtlasScene& scene, const AtlasSetting& s);
  // The ensemble sizes of the grid.
  static std::vector<int> ensembles(const AtlasScene& scene);
  // What the run keeps of the engine's own details (md_bridge/particle_engine.hpp): nothing here.
  virtual void take_engine_details(const std::vector<md::EngineDetail>&, AtlasRun&) const {}

 private:
  std::string engine_;
  ModelStyle style_;
};

// The families of the engines that have their own (models/family_<engine>.cpp).
const ModelFamily* lammps_family();
const ModelFamily* event_driven_family();
const ModelFamily* recorded_family();

}  // namespace granvv::app
