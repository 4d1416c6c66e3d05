// The recorded particles as a family (models/particle_family.hpp): another program's run,
// replayed from its files (md_bridge/recorded_engine.hpp). It has no cost knob: its members are
// the entries of md.recorded.files, so the atlas runs it once, as a fixed reference. It applies
// only to a scene that names files.
#include "models/particle_family.hpp"
#include "scene/case_config.hpp"

namespace granvv::app {
namespace {

class RecordedFamily : public ParticleFamily {
 public:
  RecordedFamily() : ParticleFamily("recorded", {"k", "*"}) {}
  std::optional<std::string> not_applicable(const AtlasScene& scene) const override {
    if (auto no = ParticleFamily::not_applicable(scene)) return no;
    if (scene.config->strings("md.recorded.files").empty()) {
      return "md.recorded.files is empty: no recorded particles";
    }
    return std::nullopt;
  }
  // Its one setting: every member of the files.
  AtlasSetting case_setting(const AtlasScene& scene) const override {
    return with_knob(ParticleFamily::case_setting(scene), kEnsembleKnob,
                     double(scene.config->strings("md.recorded.files").size()));
  }
  AtlasSetting pilot(const AtlasScene& scene) const override { return case_setting(scene); }
  std::vector<AtlasSetting> grid(const AtlasScene& scene) const override {
    return {case_setting(scene)};
  }
  std::vector<std::string> overrides(const AtlasScene&, const AtlasSetting&) const override {
    return {"md.engine=\"recorded\""};
  }
};

}  // namespace

const ModelFamily* recorded_family() {
  static const RecordedFamily family;
  return &family;
}

}  // namespace granvv::app
