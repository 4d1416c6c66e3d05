// The particle-engine registry and its first engine, the real LAMMPS: the registry's refusals,
// the collision-rule check from the one validated contact spec, and what an engine reports over
// an ensemble (cost, details). The contract every engine meets: tests/test_engine_conformance.cpp.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <variant>

#include "hydro/initial_conditions.hpp"
#include "md_bridge/lammps_engine.hpp"
#include "md_bridge/md_run.hpp"
#include "md_bridge/particle_engine_registry.hpp"
#include "md_bridge/restitution_calibration.hpp"
#include "support/engine_settings.hpp"

namespace granvv::md {
namespace {

ParticleEngineSetup lammps_setup(double restitution) {
  return granvv::testing::default_engine_setup("lammps",
                                               scene_from_particles(400, 0.05, 50.0, restitution));
}

std::map<std::string, double> numbers(const EngineDetails& details) {
  std::map<std::string, double> out;
  for (const auto& d : details) {
    if (const double* v = std::get_if<double>(&d.value)) out[d.key] = *v;
    if (const long long* v = std::get_if<long long>(&d.value)) out[d.key] = double(*v);
  }
  return out;
}

// What every registered engine does is checked in tests/test_engine_conformance.cpp; here the
// registry's refusals.
TEST(ParticleEngineRegistry, RefusesUnknownNamesListingTheKnownAndLammpsMissingSettings) {
  const std::vector<std::string> names = particle_engine_names();
  ASSERT_FALSE(names.empty());
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size());  // no twice
  std::string known;
  for (const std::string& name : names) known += (known.empty() ? "" : ", ") + name;
  try {
    (void)make_particle_engine("hard_disks", lammps_setup(0.9));
    FAIL() << "unknown engine accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("known: " + known), std::string::npos) << e.what();
  }
  ParticleEngineSetup missing = lammps_setup(0.9);
  missing.settings.erase("md.steps_per_contact");
  try {
    (void)make_particle_engine("lammps", missing);
    FAIL() << "missing setting accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("md.steps_per_contact"), std::string::npos) << e.what();
  }
  // A contact that cannot be made is refused when the engine is made, before LAMMPS opens.
  ParticleEngineSetup coarse = lammps_setup(0.9);
  coarse.settings["md.steps_per_contact"] = 3;
  EXPECT_THROW((void)make_particle_engine("lammps", coarse), std::invalid_argument);
  ParticleEngineSetup logged = lammps_setup(0.9);
  logged.log_dir = "/some/run";
  EXPECT_EQ(make_particle_engine("lammps", logged)->log_path(), "/some/run/log.lammps");
}

// The check measures the contact the engine itself makes (contact_for_speed, validated), so
// it equals a measurement of that model bit for bit, and it hits the target within the 1e-3
// that a run demands (the discrete correction of gamma_n, contact_model.hpp).
TEST(ParticleEngineLammps, CollisionRuleCheckMeasuresTheEnginesOwnContact) {
  for (const double r : {0.5, 0.9}) {
    SCOPED_TRACE(r);
    LammpsEngineOptions options;
    options.restitution = r;
    options.max_overlap = 0.01;  // the case schema's defaults
    options.steps_per_contact = 30;
    LammpsEngine engine(options);
    const CollisionRuleCheck check = engine.check_collision_rule();
    EXPECT_EQ(check.restitution,
              measure_restitution(engine.contact_for_speed(LammpsEngine::kCalibrationSpeed), 1.0));
    EXPECT_NEAR(check.restitution, r, 1e-3);
    EXPECT_NE(check.description.find("64 head-on collisions"), std::string::npos)
        << check.description;
  }
}

// Two runs of one engine (an ensemble of two): the work adds up, each run starts at t = 0
// with its own contact, and the details keep the first run's contacts.
TEST(ParticleEngineLammps, AnEnsembleSharesOneEngine) {
  const ParticleEngineSetup setup = lammps_setup(0.9);
  const auto engine = make_particle_engine("lammps", setup);
  MdRunSpec spec;
  spec.scene = setup.scene;
  spec.fields = hydro::uniform_fields();
  spec.t_end = 2.0;
  spec.sample_interval = 1.0;
  spec.bins = 5;
  spec.kernel = "bin";
  spec.seed = 1;
  const MdRunResult first = run_md(spec, *engine, nullptr);
  const auto after_first = numbers(engine->details());
  spec.seed = 2;
  const MdRunResult second = run_md(spec, *engine, nullptr);
  ASSERT_GE(first.series.t.size(), 3u);  // samples land on the nearest step: maybe one more
  ASSERT_GE(second.series.t.size(), 3u);
  EXPECT_EQ(second.series.t.front(), 0.0);
  EXPECT_EQ(engine->cost().work, 400.0 * double(first.steps + second.steps));
  const auto details = numbers(engine->details());
  EXPECT_EQ(details.at("contact_initial.kn"), first.series.engine.at(0).second.front());
  EXPECT_EQ(details.at("contact_initial.kn"), after_first.at("contact_initial.kn"));
  EXPECT_EQ(details.at("contact_final.kn"), after_first.at("contact_final.kn"));
  // Another seed, another fastest pair: the second run's own contact.
  EXPECT_NE(second.series.engine.at(0).second.front(), first.series.engine.at(0).second.front());
}

}  // namespace
}  // namespace granvv::md
