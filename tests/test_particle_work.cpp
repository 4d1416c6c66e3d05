// The work of a particle run as each engine estimates it (md_bridge/particle_work.hpp), against
// a real run and through the real CLI: the event-driven estimate counts the collisions an
// inelastic gas really has; a scene that LAMMPS refuses in atom-steps is cheap for the
// event-driven engine and runs; and the event-driven engine refuses beyond its own limit in
// collisions, naming the key.
#include <gtest/gtest.h>

#include "hydro/initial_conditions.hpp"
#include "md_bridge/event_driven_engine.hpp"
#include "md_bridge/mpi_environment.hpp"
#include "md_bridge/particle_engine_registry.hpp"
#include "md_bridge/particle_sampler.hpp"
#include "scene/work_estimate.hpp"
#include "support/cli_runner.hpp"
#include "support/elastic_gas.hpp"

namespace granvv::md {
namespace {

// 4000 disks at phi = 0.05, r = 0.9 to t = 60 (0.7 t0): the estimate (N/2) nu0 t0 ln(1 + t/t0)
// against the collisions counted, about 2.5e4 (Poisson error 0.6 %). Tolerance 3 %: the estimate
// leaves out the Sonine corrections of the rates (-a2/16 = +0.17 % for nu, and the slower
// cooling, 0.5 % in t0) and the relaxation from the Maxwellian start.
TEST(ParticleWork, EventDrivenEstimateCountsTheCollisionsOfACoolingGas) {
  MpiEnvironment::ensure();
  const ParticleScene scene = scene_from_particles(4000, 0.05, 200.0, 0.9);
  ParticleWorkQuestion q;
  q.scene = scene;
  q.settings["md.contact_duration"] = 0.0;
  q.t_end = 60.0;
  q.haff_time = haff_time_md(scene, enskog_chi(scene.area_fraction));
  q.ensemble = 1;
  const ParticleWorkEstimate w = estimate_particle_work("event_driven", q);
  EXPECT_EQ(w.unit, "collisions");
  EXPECT_EQ(w.first_step, 0.0);
  EventDrivenEngine engine(granvv::testing::event_driven_options(scene));
  engine.set_up(sample_particles(scene, hydro::uniform_fields(), 8));
  engine.advance_to(q.t_end);
  EXPECT_NEAR(w.work / double(engine.collisions()), 1.0, 0.03)
      << w.work << " estimated, " << engine.collisions() << " counted";
  q.ensemble = 3;  // the work of an ensemble is its members'
  EXPECT_DOUBLE_EQ(estimate_particle_work("event_driven", q).work, 3.0 * w.work);
  EXPECT_THROW(estimate_particle_work("hard_disks", q), std::invalid_argument);
}

// md_haff elastic with 10^5 disks to t = 2e4: LAMMPS needs ~5.5e13 atom-steps (refused, as
// before), the event-driven engine ~7e8 collisions (accepted); to t = 1e9 it needs ~4e13
// collisions, beyond its 3e10.
// The progress line's time left: the running member's rest at its pace so far, then the later
// members that run on the same group of ranks (member m on group m mod G), `jobs` at a time.
TEST(ParticleWork, TimeLeftCountsOnlyTheMembersOfTheRanksOwnGroup) {
  app::ParticleRunEstimate e;
  // Member 0 of 8, half done after 10 s: 10 s for its rest, then 7 members of 20 s each.
  EXPECT_DOUBLE_EQ(e.seconds_left(0, 8, 1, 0.5, 10.0), 10.0 + 7 * 20.0);
  // Two threads: the 7 later members two at a time.
  EXPECT_DOUBLE_EQ(e.seconds_left(0, 8, 2, 0.5, 10.0), 10.0 + 3.5 * 20.0);
  // Two groups of ranks: this rank runs members 0, 2, 4, 6 (3 after member 0); member 5 on
  // group 1 has member 7 after it; the last member of a group has none.
  e.member_groups = 2;
  EXPECT_DOUBLE_EQ(e.seconds_left(0, 8, 1, 0.5, 10.0), 10.0 + 3 * 20.0);
  EXPECT_DOUBLE_EQ(e.seconds_left(5, 8, 1, 0.5, 10.0), 10.0 + 1 * 20.0);
  EXPECT_DOUBLE_EQ(e.seconds_left(6, 8, 1, 1.0, 10.0), 0.0);
}

TEST(ParticleWorkCli, EachEngineIsBudgetedInItsOwnUnit) {
  const std::string scene =
      "run md_haff --dry-run --set md.restitution=1 --set md.time_unit=md "
      "--set md.sample_interval=100 --set md.particles=100000 ";
  const std::string long_run = "--set md.t_end=20000 --set 'md.output_times=[0,20000]' ";
  const auto lammps = granvv::testing::run_cli(scene + long_run + "2>&1");
  EXPECT_EQ(lammps.exit_code, 2) << lammps.output;
  EXPECT_NE(lammps.output.find("atom-steps"), std::string::npos) << lammps.output;
  const auto event_driven =
      granvv::testing::run_cli(scene + long_run + "--set md.engine=event_driven 2>&1");
  EXPECT_EQ(event_driven.exit_code, 0) << event_driven.output;
  const auto too_long = granvv::testing::run_cli(
      scene +
      "--set md.t_end=1e9 --set 'md.output_times=[0,1e9]' --set md.sample_interval=1e5 "
      "--set md.engine=event_driven 2>&1");
  EXPECT_EQ(too_long.exit_code, 2) << too_long.output;
  EXPECT_NE(too_long.output.find("md.t_end = 1e9"), std::string::npos) << too_long.output;
  EXPECT_NE(too_long.output.find("collisions; the limit is 3e+10 collisions"), std::string::npos)
      << too_long.output;
}

}  // namespace
}  // namespace granvv::md
