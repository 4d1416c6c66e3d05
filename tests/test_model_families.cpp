// The ladder's model families (models/model_family.hpp): every registered closure and engine has
// its rung, in the ladder's order; each family's knobs, settings and descriptions agree with one
// another; and each says when it applies, from the scene alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "hydro/closure.hpp"
#include "md_bridge/particle_engine_registry.hpp"
#include "models/model_family.hpp"
#include "scene/case_catalog.hpp"
#include "scene/case_config.hpp"
#include "scene/hydro_scene.hpp"

namespace granvv::testing {
namespace {

using app::AtlasScene;
using app::FamilyKind;
using app::ModelFamily;

// The atlas's view of a shipped scene, with --set overrides, as atlas/atlas_setup.cpp makes it.
AtlasScene scene_of(const std::string& name, const std::vector<std::string>& sets = {}) {
  AtlasScene scene;
  scene.source = app::locate_case(name);
  scene.sets = sets;
  scene.config = std::make_shared<const app::CaseConfig>(
      app::CaseConfig::from_string(scene.source.text, scene.source.origin, sets));
  const app::HydroScene hydro = app::hydro_scene_from(*scene.config);
  scene.case_hydro = std::make_shared<const app::HydroScene>(hydro);
  scene.particles = scene.config->boolean("md.enabled");
  return scene;
}

TEST(ModelFamilies, EveryRegisteredClosureAndEngineHasItsRungInLadderOrder) {
  std::vector<std::string> names;
  for (const ModelFamily* f : app::model_families()) names.push_back(f->name());
  std::vector<std::string> expected = {"haff_ode", "flow_by_inertia"};
  for (const auto& c : hydro::closure_names()) expected.push_back("hydro/" + c);
  for (const auto& e : md::particle_engine_names()) expected.push_back("particles/" + e);
  EXPECT_EQ(names, expected);
  for (std::size_t i = 0; i < names.size(); ++i) {
    EXPECT_EQ(app::ladder_rank(names[i]), int(i));
    EXPECT_EQ(&app::model_family(names[i]), app::model_families()[i]);
  }
  EXPECT_THROW(app::model_family("hydro/no_such_closure"), std::invalid_argument);
}

TEST(ModelFamilies, KindsRiseAlongTheLadder) {
  // exact < discretised < ensemble: the richest model is always last.
  int last = -1;
  for (const ModelFamily* f : app::model_families()) {
    EXPECT_GE(int(f->kind()), last) << f->name();
    last = int(f->kind());
  }
}

TEST(ModelFamilies, StylesAreDeclaredAndDistinct) {
  std::set<std::pair<std::string, std::string>> seen;
  for (const ModelFamily* f : app::model_families()) {
    EXPECT_FALSE(f->style().color.empty()) << f->name();
    EXPECT_FALSE(f->style().marker.empty()) << f->name();
    EXPECT_TRUE(seen.insert({f->style().color, f->style().marker}).second) << f->name();
  }
}

TEST(ModelFamilies, AtlasH5ColumnsAreEveryKnobOnce) {
  std::set<std::string> names;
  for (const auto& k : app::all_knobs()) EXPECT_TRUE(names.insert(k.name).second) << k.name;
  for (const ModelFamily* f : app::model_families()) {
    for (const auto& k : f->knobs()) EXPECT_TRUE(names.count(k.name)) << f->name() << " " << k.name;
  }
}

TEST(ModelFamilies, CaseSettingsCarryEveryKnobAndDescribeThemselves) {
  const AtlasScene scene = scene_of("quickstart");
  for (const ModelFamily* f : app::model_families()) {
    if (f->not_applicable(scene)) continue;
    const app::AtlasSetting own = f->case_setting(scene);
    EXPECT_EQ(own.model, f->name());
    EXPECT_EQ(own.knobs.size(), f->knobs().size()) << f->name();
    const auto j = f->setting_json(own);
    EXPECT_EQ(j["model"], f->name());
    for (const auto& k : f->knobs()) EXPECT_TRUE(j.contains(k.name)) << f->name() << " " << k.name;
    EXPECT_EQ(app::describe(own).rfind(f->name(), 0), 0u) << app::describe(own);
    // Every grid setting is one of the family's own, with the same knobs.
    for (const auto& s : f->grid(scene)) {
      EXPECT_EQ(s.model, f->name());
      EXPECT_EQ(s.knobs.size(), own.knobs.size());
    }
  }
  const app::AtlasSetting hydro = app::model_family("hydro/dilute").case_setting(scene);
  EXPECT_EQ(app::describe(hydro), "hydro/dilute cells=400 step_factor=1");
  EXPECT_EQ(app::setting_json(hydro).dump(),
            R"({"cells":400,"model":"hydro/dilute","step_factor":1.0})");
}

TEST(ModelFamilies, TheFinestSettingIsTheReferenceOfADiscretisedFamily) {
  const AtlasScene scene =
      scene_of("single_mode", {"atlas.cells=[100, 200]", "atlas.step_factors=[0.5, 1]"});
  const ModelFamily& hydro = app::model_family("hydro/dilute");
  const auto grid = hydro.grid(scene);
  ASSERT_FALSE(grid.empty());
  const auto finest = *std::max_element(
      grid.begin(), grid.end(), [&](const auto& a, const auto& b) { return hydro.finer(b, a); });
  EXPECT_EQ(finest.knob("cells"), 200);
  EXPECT_EQ(finest.knob("step_factor"), 0.5);
  EXPECT_TRUE(hydro.plan_first(finest, scene));
  // One step coarser in one knob is a neighbour; two knobs at once is not.
  EXPECT_TRUE(hydro.coarser_neighbour(hydro.with_knob(finest, "cells", 100), finest));
  EXPECT_TRUE(hydro.coarser_neighbour(hydro.with_knob(finest, "step_factor", 1.0), finest));
  EXPECT_FALSE(hydro.coarser_neighbour(
      hydro.with_knob(hydro.with_knob(finest, "cells", 100), "step_factor", 1.0), finest));
}

TEST(ModelFamilies, EachFamilySaysWhenItDoesNotApply) {
  // The Haff scene: no particles, a uniform initial state, no area fraction for Enskog.
  const AtlasScene haff = scene_of("haff");
  EXPECT_FALSE(app::model_family("haff_ode").not_applicable(haff));
  EXPECT_FALSE(app::model_family("hydro/dilute").not_applicable(haff));
  const auto enskog = app::model_family("hydro/enskog").not_applicable(haff);
  ASSERT_TRUE(enskog);
  EXPECT_NE(enskog->find("physics.area_fraction"), std::string::npos) << *enskog;
  for (const auto& e : md::particle_engine_names()) {
    EXPECT_EQ(app::model_family("particles/" + e).not_applicable(haff),
              std::optional<std::string>("md.enabled = false"));
  }
  // A dense gas makes the Enskog rung apply; the case's own closure is its case model.
  const AtlasScene dense =
      scene_of("haff", {"hydro.closure=\"enskog\"", "physics.area_fraction=0.2"});
  EXPECT_FALSE(app::model_family("hydro/enskog").not_applicable(dense));
  EXPECT_TRUE(app::model_family("hydro/enskog").is_case_model(dense));
  EXPECT_FALSE(app::model_family("hydro/dilute").is_case_model(dense));
  // The formula closure runs only where the case chooses it (its defaults copy the dilute one).
  const auto formula = app::model_family("hydro/formula").not_applicable(haff);
  ASSERT_TRUE(formula);
  EXPECT_NE(formula->find("hydro.closure = \"formula\""), std::string::npos) << *formula;
  EXPECT_FALSE(app::model_family("hydro/formula")
                   .not_applicable(scene_of("haff", {"hydro.closure=\"formula\""})));
}

TEST(ModelFamilies, ParticleGridsFollowTheirKeys) {
  const AtlasScene scene =
      scene_of("quickstart", {"atlas.ensembles=[1, 4]", "atlas.particle_factors=[0.5, 1]",
                              "atlas.max_overlaps=[0.01]", "atlas.steps_per_contacts=[10, 30]"});
  const ModelFamily& hard = app::model_family("particles/event_driven");
  std::vector<std::string> described;
  for (const auto& s : hard.grid(scene)) described.push_back(app::describe(s));
  EXPECT_EQ(described, (std::vector<std::string>{
                           "particles/event_driven ensemble=1", "particles/event_driven ensemble=4",
                           "particles/event_driven ensemble=2 particle_factor=0.5"}));
  EXPECT_FALSE(
      hard.may_be_reference(hard.with_knob(hard.case_setting(scene), "particle_factor", 0.5)));
  EXPECT_EQ(hard.pilot(scene).knob("ensemble"), 1);
  // LAMMPS: the overlaps x steps at the case's adaptive stiffness, then each overlap flipped.
  const ModelFamily& soft = app::model_family("particles/lammps");
  EXPECT_EQ(soft.grid(scene).size(), 3u);
  EXPECT_TRUE(soft.has_contact_map());
  EXPECT_TRUE(soft.plan_first(soft.case_setting(scene), scene));
}

TEST(ModelFamilies, ParticleCostsFollowTheEnginesOwnWorkEstimate) {
  // The pilot's wall time scaled by the engine's work model (md_bridge/particle_work.hpp).
  const AtlasScene scene = scene_of("quickstart");
  const ModelFamily& soft = app::model_family("particles/lammps");
  app::AtlasRun pilot;
  pilot.setting = soft.pilot(scene);
  pilot.cost.wall_seconds = 2.0;
  const double overlap = pilot.setting.knob("max_overlap");
  const double steps = pilot.setting.knob("steps_per_contact");
  // LAMMPS: atom-steps. Twice the members, half the overlap (half the contact time, so half the
  // step) and twice the steps per contact: 2 x 2 x 2 = 8 times the pilot's work.
  auto finer = soft.with_knob(pilot.setting, "ensemble", 2);
  finer = soft.with_knob(finer, "max_overlap", overlap / 2);
  finer = soft.with_knob(finer, "steps_per_contact", 2 * steps);
  const auto soft_estimate = soft.estimate(pilot, scene);
  EXPECT_NEAR(soft_estimate(finer), 8 * 2.0, 1e-9);
  // Adaptive stiffness lengthens the step as the gas cools: fewer steps than a fixed contact.
  const auto adaptive = soft.with_knob(pilot.setting, "adaptive_stiffness", 1);
  const auto fixed = soft.with_knob(pilot.setting, "adaptive_stiffness", 0);
  EXPECT_LT(soft_estimate(adaptive), soft_estimate(fixed));
  // A contact the schema refuses is refused before it costs anything.
  EXPECT_EQ(soft_estimate(soft.with_knob(pilot.setting, "max_overlap", 10.0)), 0.0);
  // Event-driven: collisions, proportional to the members and, at the same density, the disks.
  const ModelFamily& hard = app::model_family("particles/event_driven");
  pilot.setting = hard.pilot(scene);
  const auto hard_estimate = hard.estimate(pilot, scene);
  EXPECT_NEAR(hard_estimate(hard.with_knob(pilot.setting, "ensemble", 4)), 4 * 2.0, 1e-9);
  // Half the disks in a box of half the length: within the rounding of the disk count.
  EXPECT_NEAR(hard_estimate(hard.with_knob(pilot.setting, "particle_factor", 0.5)), 0.5 * 2.0,
              0.01 * 2.0);
}

}  // namespace
}  // namespace granvv::testing
