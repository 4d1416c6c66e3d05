// The soft-contact (DEM) particles of LAMMPS as a family (models/particle_family.hpp): besides
// the ensemble size, the contact knobs md.max_overlap, md.steps_per_contact and
// md.adaptive_stiffness, whose bias against the hard disks the atlas maps (docs/atlas.md).
#include <cmath>
#include <tuple>

#include "models/particle_family.hpp"
#include "scene/case_config.hpp"

namespace granvv::app {
namespace {

// The default contact grid around the case's own (docs/atlas.md): md.max_overlap and
// md.steps_per_contact times these (the schema refuses what lies beyond its ranges, and the map
// shows those as refused).
const std::vector<double> kOverlapFactors = {0.5, 1.0, 2.0, 5.0, 10.0};
const std::vector<double> kContactStepFactors = {1.0 / 3.0, 0.5, 1.0, 2.0};

class LammpsFamily : public ParticleFamily {
 public:
  LammpsFamily() : ParticleFamily("lammps", {"C4", "v"}) {}
  std::vector<KnobSpec> knobs() const override {
    auto k = ParticleFamily::knobs();
    k.push_back({kMaxOverlapKnob, KnobSpec::Type::real, 0.0});
    k.push_back({kStepsPerContactKnob, KnobSpec::Type::integer, 0.0});
    k.push_back({kAdaptiveStiffnessKnob, KnobSpec::Type::flag, 0.0});
    return k;
  }
  bool has_contact_map() const override { return true; }

  AtlasSetting case_setting(const AtlasScene& scene) const override {
    const CaseConfig& c = *scene.config;
    AtlasSetting s = ParticleFamily::case_setting(scene);
    s.knobs[kMaxOverlapKnob] = c.real("md.max_overlap");
    s.knobs[kStepsPerContactKnob] = double(c.int_value("md.steps_per_contact"));
    s.knobs[kAdaptiveStiffnessKnob] = c.boolean("md.adaptive_stiffness") ? 1.0 : 0.0;
    return s;
  }

  // At the case's ensemble over max_overlaps x steps_per_contacts with the case's adaptive
  // stiffness, and over max_overlaps at the case's steps_per_contact with it flipped.
  std::vector<AtlasSetting> grid(const AtlasScene& scene) const override {
    const CaseConfig& c = *scene.config;
    const AtlasSetting own = case_setting(scene);
    std::vector<double> overlaps = c.reals("atlas.max_overlaps");
    if (overlaps.empty()) {
      for (double f : kOverlapFactors) overlaps.push_back(own.knob(kMaxOverlapKnob) * f);
    }
    std::vector<int> steps;
    for (long long k : c.integers("atlas.steps_per_contacts")) steps.push_back(int(k));
    if (steps.empty()) {
      for (double f : kContactStepFactors) {
        const int k = int(std::lround(own.knob(kStepsPerContactKnob) * f));
        if (steps.empty() || k > steps.back()) steps.push_back(k);
      }
    }
    const double adaptive = own.knob(kAdaptiveStiffnessKnob);
    std::vector<AtlasSetting> grid;
    auto add = [&](double overlap, double spc, double flag) {
      AtlasSetting s = own;
      s.knobs[kMaxOverlapKnob] = overlap;
      s.knobs[kStepsPerContactKnob] = spc;
      s.knobs[kAdaptiveStiffnessKnob] = flag;
      grid.push_back(s);
    };
    for (double overlap : overlaps) {
      for (int spc : steps) add(overlap, spc, adaptive);
    }
    for (double overlap : overlaps) add(overlap, own.knob(kStepsPerContactKnob), 1.0 - adaptive);
    return grid;
  }
  // The case's own contact first.
  bool plan_first(const AtlasSetting& s, const AtlasScene& scene) const override {
    return same_contact(s, case_setting(scene));
  }
  // Larger ensemble, then smaller overlap, more steps, fixed (stiffest) contact.
  bool finer(const AtlasSetting& a, const AtlasSetting& b) const override {
    auto order = [](const AtlasSetting& s) {
      return std::make_tuple(s.knob(kEnsembleKnob), -s.knob(kMaxOverlapKnob),
                             s.knob(kStepsPerContactKnob), -s.knob(kAdaptiveStiffnessKnob));
    };
    return order(a) > order(b);
  }
  std::vector<std::string> overrides(const AtlasScene& scene,
                                     const AtlasSetting& s) const override {
    std::vector<std::string> sets = ParticleFamily::overrides(scene, s);
    sets.push_back("md.max_overlap=" + format_real(s.knob(kMaxOverlapKnob)));
    sets.push_back("md.steps_per_contact=" +
                   std::to_string(std::lround(s.knob(kStepsPerContactKnob))));
    sets.push_back(std::string("md.adaptive_stiffness=") +
                   (s.knob(kAdaptiveStiffnessKnob) != 0.0 ? "true" : "false"));
    return sets;
  }

 private:
  static bool same_contact(const AtlasSetting& a, const AtlasSetting& b) {
    return a.knob(kMaxOverlapKnob) == b.knob(kMaxOverlapKnob) &&
           a.knob(kStepsPerContactKnob) == b.knob(kStepsPerContactKnob) &&
           a.knob(kAdaptiveStiffnessKnob) == b.knob(kAdaptiveStiffnessKnob);
  }
};

}  // namespace

const ModelFamily* lammps_family() {
  static const LammpsFamily family;
  return &family;
}

}  // namespace granvv::app
