// The event-driven hard disks as a family (models/particle_family.hpp): besides the ensemble
// size, the particle count as a factor on the case's (md.box_width, and md.particles where the
// case sets it, times f, so that Lx and the area fraction stay the case's), and one failure mode
// of its own: collapse rules that changed too many collisions (docs/atlas.md).
#include <cmath>

#include "models/particle_family.hpp"
#include "scene/case_config.hpp"

namespace granvv::app {
namespace {

constexpr const char* kParticleFactor = "particle_factor";
// The engine's share of collisions whose restitution its collapse rules changed
// (md_bridge/hard_disk_collision.hpp), as its summary detail and as the atlas keeps it.
constexpr const char* kCollapseRuleDetail = "collapse_rule.fraction_changed";
constexpr const char* kCollapseRuleScalar = "collapse_rule_fraction_changed";

class EventDrivenFamily : public ParticleFamily {
 public:
  EventDrivenFamily() : ParticleFamily("event_driven", {"C5", "P"}) {}
  std::vector<KnobSpec> knobs() const override {
    auto k = ParticleFamily::knobs();
    k.push_back({kParticleFactor, KnobSpec::Type::real, 1.0, true});
    return k;
  }
  AtlasSetting case_setting(const AtlasScene& scene) const override {
    return with_knob(ParticleFamily::case_setting(scene), kParticleFactor, 1.0);
  }
  // Every ensemble size at the case's particles, and the case's ensemble at each particle
  // factor of atlas.particle_factors other than 1.
  std::vector<AtlasSetting> grid(const AtlasScene& scene) const override {
    std::vector<AtlasSetting> grid = ParticleFamily::grid(scene);
    for (double f : scene.config->reals("atlas.particle_factors")) {
      if (f != 1.0) grid.push_back(with_knob(case_setting(scene), kParticleFactor, f));
    }
    return grid;
  }
  // The reference keeps the case's particle count: other counts are another scene's size.
  bool may_be_reference(const AtlasSetting& s) const override {
    return s.knob(kParticleFactor) == 1.0;
  }
  std::vector<std::string> overrides(const AtlasScene& scene,
                                     const AtlasSetting& s) const override {
    std::vector<std::string> sets = ParticleFamily::overrides(scene, s);
    const double f = s.knob(kParticleFactor);
    if (f != 1.0) {
      const CaseConfig& c = *scene.config;
      sets.push_back("md.box_width=" + format_real(c.real("md.box_width") * f));
      if (const long long n = c.int_value("md.particles"); n > 0) {
        sets.push_back("md.particles=" + std::to_string(std::llround(double(n) * f)));
      }
    }
    return sets;
  }
  // A finished run whose collapse rules changed more than atlas.collapse_rule_limit of its
  // collisions is no longer the hard-disk gas of constant r (docs/atlas.md).
  void judge(const AtlasScene& scene, AtlasRun& run) const override {
    const double limit = scene.config->real("atlas.collapse_rule_limit");
    const auto f = run.scalars.find(kCollapseRuleScalar);
    if (run.status != "ok" || f == run.scalars.end() || !(f->second > limit)) return;
    run.status = "collapse_rule_active";
    run.reason = "the collapse rules changed the restitution of " + format_real(f->second) +
                 " of all collisions, above atlas.collapse_rule_limit = " + format_real(limit);
  }

 protected:
  void take_engine_details(const std::vector<md::EngineDetail>& details,
                           AtlasRun& run) const override {
    for (const auto& d : details) {
      if (d.key == kCollapseRuleDetail && std::holds_alternative<double>(d.value)) {
        run.scalars[kCollapseRuleScalar] = std::get<double>(d.value);
      }
    }
  }
};

}  // namespace

const ModelFamily* event_driven_family() {
  static const EventDrivenFamily family;
  return &family;
}

}  // namespace granvv::app
