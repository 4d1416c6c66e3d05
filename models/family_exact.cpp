// The exact references of the ladder as families (models/model_family.hpp): Haff's law of the
// homogeneous cooling state and flow by inertia (paper Eqs. 4-6). Each is one run without a
// knob, repeated when it is too quick to time.
#include "hydro/flow_by_inertia.hpp"
#include "models/families.hpp"
#include "models/model.hpp"
#include "models/setting_run.hpp"
#include "scene/hydro_scene.hpp"

namespace granvv::app {
namespace {

class HaffFamily : public ModelFamily {
 public:
  HaffFamily() : ModelFamily("haff_ode") {}
  FamilyKind kind() const override { return FamilyKind::exact; }
  ModelStyle style() const override { return {"C2", "s"}; }
  void run(const AtlasScene& scene, const CaseConfig& config, AtlasRun& run) const override {
    const HydroScene hydro = atlas_hydro_scene(config, scene);
    auto haff = [&] { return make_haff_model(hydro.physics, scene.times, scene.bins)->run(); };
    take_result(scene, haff(), run);
    time_by_fastest(run.cost, [&] { return haff().cost; });
    run.status = "ok";
  }
};

class InertiaFamily : public ModelFamily {
 public:
  InertiaFamily() : ModelFamily("flow_by_inertia") {}
  FamilyKind kind() const override { return FamilyKind::exact; }
  ModelStyle style() const override { return {"C1", "D"}; }
  std::optional<std::string> not_applicable(const AtlasScene& scene) const override {
    if (scene.has_inertia_reference) return std::nullopt;
    return "the initial velocity has no flow-by-inertia reference";
  }
  void run(const AtlasScene& scene, const CaseConfig& config, AtlasRun& run) const override {
    const HydroScene hydro = atlas_hydro_scene(config, scene);
    auto inertia = [&] {
      return make_inertia_model(hydro.initial, hydro.physics, scene.times, scene.bins,
                                scene.crossing_levels)
          ->run();
    };
    take_result(scene, inertia(), run);
    time_by_fastest(run.cost, [&] { return inertia().cost; });
    run.status = "ok";
  }
};

}  // namespace

std::vector<const ModelFamily*> exact_families() {
  static const HaffFamily haff;
  static const InertiaFamily inertia;
  return {&haff, &inertia};
}

}  // namespace granvv::app
