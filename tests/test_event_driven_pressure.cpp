// The event-driven engine's pressure through the engine seam (docs/physics.md §11, §13): each
// disk's share of the collision virial adds up to the engine's own box value; through the
// coarse-grainer an elastic gas at phi = 0.1 has Henderson's P/(nT) = 1 + 2 phi chi, like the
// LAMMPS engine's (tests/test_particle_pressure.cpp); and the equation of state at phi = 0.3
// and 0.5 against the hard-disk EOS of the literature (the sweep over phi = 0.05 ... 0.5 is
// tests/slow_event_driven.cpp); the contact transfer of energy on one head-on collision.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "hydro/initial_conditions.hpp"
#include "md_bridge/event_driven_engine.hpp"
#include "md_bridge/hard_disk_theory.hpp"
#include "md_bridge/md_run.hpp"
#include "md_bridge/mpi_environment.hpp"
#include "md_bridge/particle_sampler.hpp"
#include "support/elastic_gas.hpp"

namespace granvv::md {
namespace {

// 800 disks at phi = 0.2, r = 0.8: none before the first advance; after it one share per
// particle, each >= 0 (repulsive impulses), adding up to the box's collision virial pressure
// (sum (W_xx + W_yy) / (2 A) = sum sigma J / (2 A dt)) to round-off; none again after set_up.
TEST(EventDrivenPressure, EveryDisksShareAddsUpToTheBoxCollisionVirial) {
  MpiEnvironment::ensure();
  const ParticleScene scene = scene_from_particles(800, 0.2, 40.0, 0.8);
  EventDrivenEngine engine(granvv::testing::event_driven_options(scene, 7));
  engine.set_up(sample_particles(scene, hydro::uniform_fields(), 4));
  EXPECT_TRUE(engine.local_virial().xx.empty());
  for (double t : {5.0, 12.5}) {
    engine.advance_to(t);
    const LocalVirial w = engine.local_virial();
    ASSERT_EQ(w.xx.size(), std::size_t(scene.particles));
    ASSERT_EQ(w.yy.size(), w.xx.size());
    ASSERT_EQ(w.energy_flux_x.size(), w.xx.size());
    double xx = 0.0, yy = 0.0;
    for (std::size_t i = 0; i < w.xx.size(); ++i) {
      EXPECT_GE(w.xx[i], 0.0) << i;
      EXPECT_GE(w.yy[i], 0.0) << i;
      xx += w.xx[i];
      yy += w.yy[i];
    }
    const double area = scene.box_length * scene.box_width;
    EXPECT_GT(engine.collision_virial().box, 0.0);
    EXPECT_NEAR((xx + yy) / (2.0 * area), engine.collision_virial().box,
                1e-12 * engine.collision_virial().box);
    EXPECT_NEAR(xx / yy, 1.0, 0.1);  // isotropic within the noise of ~2000 collisions
  }
  engine.set_up(sample_particles(scene, hydro::uniform_fields(), 5));
  EXPECT_TRUE(engine.local_virial().xx.empty());
}

// The contact transfer of energy (LocalVirial::energy_flux_x) on one head-on collision: a disk at
// x = -2 moving at 1 hits a disk at rest at x = 0 (at t = 1, contact at distance sigma = 1), and
// leaves with (1 - r)/2 while the other leaves with (1 + r)/2. The energy moved forward across the
// contact is (dE_a - dE_b)/2 = -(1 + r)/4 from b to a, at x_a - x_b = -1: (1 + r)/4 along +x,
// half to each disk, divided by the interval (5). Elastic and r = 0.5.
TEST(EventDrivenPressure, AHeadOnCollisionCarriesEnergyAcrossTheContact) {
  MpiEnvironment::ensure();
  for (double r : {1.0, 0.5}) {
    SCOPED_TRACE(r);
    const ParticleScene scene = scene_from_particles(2, 0.01, 10.0, r);
    EventDrivenEngine engine(granvv::testing::event_driven_options(scene, 1));
    ParticleSample two;
    two.x = {-2.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    two.v = {1.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    engine.set_up(two);
    engine.advance_to(5.0);
    const LocalVirial w = engine.local_virial();
    ASSERT_EQ(w.energy_flux_x.size(), 2u);
    const double expected = (1.0 + r) / 4.0 / 5.0;
    EXPECT_NEAR(w.energy_flux_x[0], 0.5 * expected, 1e-12);
    EXPECT_NEAR(w.energy_flux_x[1], 0.5 * expected, 1e-12);
    EXPECT_NEAR(engine.local_particles().v[3], 0.5 * (1.0 + r), 1e-12);  // b's velocity
  }
}

// An elastic gas of 1000 hard disks at phi = 0.1 through run_md (the coarse-grainer's P_xx,
// P_yy, as for LAMMPS): P/(nT) against Henderson's 1 + 2 phi chi = 1.2361, which is exact there
// to ~1e-4 (its third and fourth virial coefficients are 3.125 and 4.25 against the exact 3.128
// and 4.258). 200 samples 1 apart after 10 for the random start to relax (about 5 collisions per
// disk), each the time average over its interval: error ~0.002. Tolerance: 4 errors. The contact
// part of every sample equals the engine's collision_virial_pressure to round-off.
TEST(EventDrivenPressure, ElasticGasFollowsHendersonsEquationOfStateThroughTheCoarseGrainer) {
  MdRunSpec spec;
  const double phi = 0.1;
  spec.scene = scene_from_particles(1000, phi, std::sqrt(1000 * M_PI / (4 * phi)), 1.0);
  spec.fields = hydro::uniform_fields();
  spec.t_end = 210.0;
  spec.sample_interval = 1.0;
  spec.bins = 5;
  spec.kernel = "bin";
  spec.seed = 7;
  EventDrivenEngine engine(granvv::testing::event_driven_options(spec.scene, 5));
  const MdRunResult r = run_md(spec, engine, nullptr);
  ASSERT_EQ(r.status, "ok");
  const auto& s = r.series;
  EXPECT_TRUE(std::isnan(s.compressibility.front()));  // t = 0: no interval yet
  ASSERT_EQ(s.engine.front().first, "collision_virial_pressure");
  const auto& engine_pressure = s.engine.front().second;
  const double area = spec.scene.box_length * spec.scene.box_width;
  double sum = 0.0, squares = 0.0, anisotropy = 0.0;
  int k = 0;
  for (std::size_t i = 1; i < s.t.size(); ++i) {
    ASSERT_TRUE(std::isfinite(s.compressibility[i])) << i;
    const double total = 0.5 * (s.pressure_xx[i] + s.pressure_yy[i]);
    const double kinetic = s.energy_thermal[i] / area;  // n T, every bin with N_eff > 1
    EXPECT_NEAR(total - kinetic, engine_pressure[i], 1e-12 * total) << i;
    if (s.t[i] <= 10.0) continue;
    sum += s.compressibility[i];
    squares += s.compressibility[i] * s.compressibility[i];
    anisotropy += (s.pressure_xx[i] - s.pressure_yy[i]) / (s.pressure_xx[i] + s.pressure_yy[i]);
    ++k;
  }
  const double z = sum / k;
  const double error = std::sqrt((squares / k - z * z) / (k - 1));
  const double henderson = henderson_compressibility(phi);
  RecordProperty("compressibility", std::to_string(z) + " +- " + std::to_string(error));
  EXPECT_NEAR(z, henderson, 4.0 * error) << "error " << error;
  EXPECT_LT(error, 0.004);
  EXPECT_LT(std::abs(anisotropy / k), 0.01);
}

// The equation of state at phi = 0.3 and 0.5 (2000 disks, 40 blocks of 25 collisions per disk
// after 50 to relax): against Luding's EOS (docs/physics.md §13), within 4 standard errors plus
// 0.3 % of Z for the reference's own accuracy and the finite size (Z_N - Z is O(1/N)).
TEST(EventDrivenPressure, EquationOfStateAtPhiPoint3AndPoint5) {
  for (const double phi : {0.3, 0.5}) {
    const auto m = granvv::testing::measure_compressibility(phi, 2000, 3, 50.0, 25.0, 40);
    const double reference = luding_compressibility(phi);
    RecordProperty("z_" + std::to_string(phi),
                   std::to_string(m.z) + " +- " + std::to_string(m.error));
    EXPECT_NEAR(m.z, reference, 4.0 * m.error + 3e-3 * reference)
        << "phi " << phi << ": " << m.z << " +- " << m.error;
    EXPECT_LT(m.error, 2e-3 * reference) << phi;
  }
}

}  // namespace
}  // namespace granvv::md
