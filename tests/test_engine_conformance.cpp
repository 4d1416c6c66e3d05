// The particle-engine seam's contract (md_bridge/particle_engine.hpp; docs/architecture.md,
// "Particle engine"), checked for every engine of the registry: an engine is covered here by
// registering it (md_bridge/particle_engine_registry.cpp), as every closure is by
// tests/test_closure.cpp. Real engines (the real LAMMPS), made by name with the settings of a
// case that sets none of their keys (tests/support/engine_settings.hpp), on gases of 400 disks
// run for a few collisions per disk. Where engines differ in what they can promise (soft
// contacts against hard disks), the tolerance is the engine's own, stated with its reason in
// promises_of(); an engine not named there is held to round-off and bit-for-bit resumption.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "hydro/initial_conditions.hpp"
#include "md_bridge/mpi_environment.hpp"
#include "md_bridge/particle_engine_registry.hpp"
#include "md_bridge/particle_sampler.hpp"
#include "support/engine_settings.hpp"

namespace granvv::md {
namespace {

// What an engine promises beyond round-off.
struct EnginePromises {
  // How far (sigma) a position may lie outside the periodic box [-L/2, L/2) after advance_to.
  double outside_box = 0.0;
  // |K_end / K_start - 1| of the kinetic energy K of an elastic gas over the run below.
  double elastic_energy = 1e-12;
  // After save_state, restore_state into a fresh engine and advance_to: the relative difference
  // of the kinetic energy from the uninterrupted engine's at the same time (0: bit for bit).
  double resumed_energy = 0.0;
};

EnginePromises promises_of(const std::string& engine) {
  EnginePromises p;
  if (engine == "lammps") {
    // LAMMPS maps atoms back into the box only when it rebuilds its neighbour lists, which it
    // does before any atom moves half the skin (0.3 sigma, md_bridge/disk_gas.cpp).
    p.outside_box = 0.15;
    // Soft disks conserve the kinetic plus the contact energy; the kinetic energy alone lacks
    // the contact energy of the pairs touching at the end. A contact lasts tc = pi delta /
    // u_max (delta = md.max_overlap = 0.01 at the fastest relative speed u_max ~ 9 of the
    // sample: tc ~ 3.5e-3), so at phi = 0.1 (collision frequency 0.53 per disk) about
    // N nu tc / 2 ~ 0.4 pairs touch at any time, each holding up to its normal energy, ~T, of
    // the gas's N T = 400 T. Each collision's restitution also scatters by ~1e-3 around 1 with
    // the phase at which it starts within a step (restitution_calibration.hpp), which averages
    // out over the ~400 collisions of the run (~5e-5 of K). Bound: one pair of 2 T in
    // contact, 5e-3 (measured: 1.4e-5).
    p.elastic_energy = 5e-3;
    // docs/outputs.md, "What a resume reproduces": the restarted LAMMPS computes the forces
    // anew, so the pairs touching at the checkpoint see full-step velocities where the
    // uninterrupted run used half-step ones, an O(dt) change of those collisions (measured on
    // 600 disks: 3e-7 of the energy; tests/test_md_run.cpp bounds it by 1e-5).
    p.resumed_energy = 1e-5;
  }
  if (engine == "event_driven") {
    // docs/outputs.md: the engine saves its whole state (every disk's flight, cell, prediction
    // and calendar entry), so the restored engine goes on with the uninterrupted one's digits.
    p.resumed_energy = 0.0;
  }
  return p;
}

constexpr long long kDisks = 400;
constexpr double kAreaFraction = 0.1;  // collision frequency ~0.53 per disk at T = 1
constexpr double kBoxWidth = 20.0;     // box 157 x 20 sigma
constexpr double kRun = 4.0;           // ~2 collisions per disk
constexpr std::uint64_t kSeed = 7;

// The restitution a particle run demands of the engine's collision rule: scene/md_scene.cpp
// refuses a run whose check is farther than this from md.restitution.
constexpr double kRestitutionTolerance = 1e-3;

struct Totals {
  double energy = 0.0, px = 0.0, py = 0.0;
};

// Kinetic energy and momentum of the particles by ID (unit masses, as every scene has).
Totals totals(const std::vector<double>& v) {
  Totals t;
  for (std::size_t i = 0; i < v.size(); i += 3) {
    t.energy += 0.5 * (v[i] * v[i] + v[i + 1] * v[i + 1]);
    t.px += v[i];
    t.py += v[i + 1];
  }
  return t;
}

// For RecordProperty: a number with its digits.
std::string digits(double x) {
  std::ostringstream out;
  out.precision(3);
  out << x;
  return out.str();
}

// The same of this rank's particles as the engine holds them, with their masses.
Totals local_totals(ParticleEngine& engine) {
  const LocalParticles p = engine.local_particles();
  Totals t;
  for (int i = 0; i < p.count; ++i) {
    const double* v = p.v + 3 * i;
    t.energy += 0.5 * p.mass[i] * (v[0] * v[0] + v[1] * v[1]);
    t.px += p.mass[i] * v[0];
    t.py += p.mass[i] * v[1];
  }
  return t;
}

class EveryEngine : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    MpiEnvironment::ensure();
    if (replays_given_particles(GetParam())) {
      // It moves no particle it is set up with: it replays another program's frames. Its
      // replay is checked against the run that wrote them, and its refusals, in
      // tests/test_recorded_engine.cpp.
      GTEST_SKIP() << GetParam() << " replays given frames";
    }
  }

  static ParticleScene scene(double restitution) {
    return scene_from_particles(kDisks, kAreaFraction, kBoxWidth, restitution);
  }
  std::unique_ptr<ParticleEngine> make(const ParticleScene& s) const {
    return make_particle_engine(GetParam(), granvv::testing::default_engine_setup(GetParam(), s));
  }
  static ParticleSample sample(const ParticleScene& s) {
    return sample_particles(s, hydro::uniform_fields(), kSeed);
  }
  const EnginePromises promises = promises_of(GetParam());
};

TEST_P(EveryEngine, IsMadeByItsNameAndSetUpFromTheSampledParticles) {
  const ParticleScene s = scene(0.9);
  const auto engine = make(s);
  EXPECT_EQ(engine->name(), GetParam());
  EXPECT_EQ(engine->log_path(), "none");  // no log_dir
  const ParticleSample given = sample(s);
  engine->set_up(given);
  EXPECT_EQ(engine->steps(), 0);
  // N and the IDs: this (one) rank holds 1 .. N, each once.
  ASSERT_EQ(engine->local_particles().count, kDisks);
  std::vector<long long> ids = engine->local_ids();
  std::sort(ids.begin(), ids.end());
  std::vector<long long> expected(std::size_t(kDisks), 0);
  std::iota(expected.begin(), expected.end(), 1LL);
  EXPECT_EQ(ids, expected);
  for (int i = 0; i < kDisks; ++i) EXPECT_EQ(engine->local_particles().mass[i], 1.0) << i;
  // Every particle where the sample put it (the box is the scene's: its images are the same
  // points), with its velocity, by ID.
  const ParticleFrame frame = engine->gather_frame();
  ASSERT_EQ(frame.x.size(), given.x.size());
  ASSERT_EQ(frame.v.size(), given.v.size());
  for (std::size_t i = 0; i < given.x.size(); i += 3) {
    EXPECT_EQ(periodic_image(frame.x[i], s.box_length), given.x[i]) << i / 3;
    EXPECT_EQ(periodic_image(frame.x[i + 1], s.box_width), given.x[i + 1]) << i / 3;
    EXPECT_EQ(frame.v[i], given.v[i]) << i / 3;
    EXPECT_EQ(frame.v[i + 1], given.v[i + 1]) << i / 3;
  }
  // The kinetic energy and momentum the coarse-grainer sees are the sample's, to round-off
  // (sums in another order: 1e-14 of the energy, and of its square root for momentum).
  const Totals sampled = totals(given.v), held = local_totals(*engine);
  const double scale = std::sqrt(2.0 * sampled.energy);
  EXPECT_NEAR(held.energy, sampled.energy, 1e-14 * sampled.energy);
  EXPECT_NEAR(held.px, sampled.px, 1e-14 * scale);
  EXPECT_NEAR(held.py, sampled.py, 1e-14 * scale);
}

// The particle run sets engines up from a sampler of x-ranges (md_run.cpp), each rank drawing
// the strips over its part of the box: on one rank, the particles of the whole-box sample.
TEST_P(EveryEngine, SetUpFromRangesHasTheParticlesOfTheWholeBoxSample) {
  const ParticleScene s = scene(0.9);
  const auto whole = make(s), ranged = make(s);
  whole->set_up(sample(s));
  const MPI_Comm comm = ranged->comm();
  ranged->set_up_sampled([&](double x_lo, double x_hi) {
    return sample_particles_in(s, hydro::uniform_fields(), kSeed, x_lo, x_hi,
                               [comm](std::vector<double>& momenta) {
                                 MPI_Allreduce(MPI_IN_PLACE, momenta.data(), int(momenta.size()),
                                               MPI_DOUBLE, MPI_MAX, comm);
                               });
  });
  const ParticleFrame a = whole->gather_frame(), b = ranged->gather_frame();
  EXPECT_EQ(b.x, a.x);
  EXPECT_EQ(b.v, a.v);
}

TEST_P(EveryEngine, CollisionRuleHasTheScenesRestitution) {
  for (const double r : {0.5, 0.9, 1.0}) {
    SCOPED_TRACE(r);
    const auto engine = make(scene(r));
    const CollisionRuleCheck check = engine->check_collision_rule();
    EXPECT_NEAR(check.restitution, r, kRestitutionTolerance) << check.description;
    EXPECT_FALSE(check.description.empty());
  }
}

TEST_P(EveryEngine, AdvancesToTheTimeAskedForKeepingDisksInTheBoxAndTheirIds) {
  const ParticleScene s = scene(0.9);
  const auto engine = make(s);
  engine->set_up(sample(s));
  const double resolution = engine->time_resolution();
  EXPECT_GE(resolution, 0.0);
  long long steps = engine->steps();
  for (const double t : {0.3, 1.0, 1.7, kRun}) {
    const double reached = engine->advance_to(t);
    // Within half the resolution, allowing the round-off of a clock summed over the steps.
    EXPECT_LE(std::abs(reached - t), 0.5 * resolution * (1.0 + 1e-9) + 1e-12 * t) << t;
    EXPECT_GT(engine->steps(), steps) << t;
    steps = engine->steps();
    const LocalParticles p = engine->local_particles();
    ASSERT_EQ(p.count, kDisks);
    const double half[2] = {0.5 * s.box_length, 0.5 * s.box_width};
    for (int i = 0; i < p.count; ++i) {
      for (int d = 0; d < 2; ++d) {
        const double x = p.x[3 * i + d];
        EXPECT_TRUE(x >= -half[d] - promises.outside_box && x < half[d] + promises.outside_box)
            << "t = " << t << ", particle " << i << ", axis " << d << ": " << x;
      }
    }
    std::vector<long long> ids = engine->local_ids();
    ASSERT_EQ(ids.size(), std::size_t(kDisks));
    std::sort(ids.begin(), ids.end());
    for (long long k = 0; k < kDisks; ++k) ASSERT_EQ(ids[std::size_t(k)], k + 1) << "t = " << t;
  }
}

// Momentum: every collision exchanges equal and opposite impulses, so the total is kept to
// round-off at any restitution: 1e-12 per disk of unit thermal speed.
void expect_momentum_kept(const Totals& start, const Totals& end) {
  EXPECT_NEAR(end.px, start.px, 1e-12 * double(kDisks));
  EXPECT_NEAR(end.py, start.py, 1e-12 * double(kDisks));
}

TEST_P(EveryEngine, ElasticGasKeepsItsEnergyAndMomentum) {
  const ParticleScene s = scene(1.0);
  const auto engine = make(s);
  ASSERT_NEAR(engine->check_collision_rule().restitution, 1.0, kRestitutionTolerance);
  engine->set_up(sample(s));
  const Totals start = local_totals(*engine);
  engine->advance_to(kRun);
  const Totals end = local_totals(*engine);
  EXPECT_LT(std::abs(end.energy / start.energy - 1.0), promises.elastic_energy);
  expect_momentum_kept(start, end);
  RecordProperty("elastic_energy_drift", digits(end.energy / start.energy - 1.0));
}

TEST_P(EveryEngine, InelasticGasKeepsItsMomentumAndCools) {
  const ParticleScene s = scene(0.5);
  const auto engine = make(s);
  engine->set_up(sample(s));
  const Totals start = local_totals(*engine);
  engine->advance_to(kRun);
  const Totals end = local_totals(*engine);
  // ~2 collisions per disk at r = 0.5, each taking 1 - r^2 = 3/4 of its pair's normal energy
  // (Haff's law: K(4) / K(0) ~ 0.5).
  EXPECT_LT(end.energy, 0.9 * start.energy);
  expect_momentum_kept(start, end);
}

// docs/outputs.md, "Checkpoints and resume": a state saved halfway and restored into a fresh
// engine is the saved state, and advancing it gives what the uninterrupted engine gives, within
// what the engine promises.
TEST_P(EveryEngine, ARestoredStateAdvancesAsTheUninterruptedEngine) {
  const ParticleScene s = scene(0.5);
  const auto whole = make(s);
  whole->set_up(sample(s));
  whole->advance_to(0.5 * kRun);
  EXPECT_TRUE(whole->save_state(false).particles.x.empty());  // the totals only
  const EngineState saved = whole->save_state(true);
  ASSERT_EQ(saved.particle_blocks, 1);  // one rank: every particle
  ASSERT_EQ(saved.particles.x.size(), 3 * std::size_t(kDisks));

  const auto resumed = make(s);
  resumed->restore_state(saved);
  // The round trip: the same particles (up to their images in the box) and the same numbers,
  // apart from the wall time, which goes on.
  const EngineState again = resumed->save_state(true);
  ASSERT_EQ(again.particles.x.size(), saved.particles.x.size());
  for (std::size_t i = 0; i < saved.particles.x.size(); i += 3) {
    EXPECT_EQ(periodic_image(again.particles.x[i], s.box_length),
              periodic_image(saved.particles.x[i], s.box_length));
    EXPECT_EQ(periodic_image(again.particles.x[i + 1], s.box_width),
              periodic_image(saved.particles.x[i + 1], s.box_width));
  }
  EXPECT_EQ(again.particles.v, saved.particles.v);
  ASSERT_EQ(again.numbers.size(), saved.numbers.size());
  for (std::size_t k = 0; k < saved.numbers.size(); ++k) {
    EXPECT_EQ(again.numbers[k].first, saved.numbers[k].first);
    if (saved.numbers[k].first != "wall_seconds") {
      EXPECT_EQ(again.numbers[k].second, saved.numbers[k].second) << saved.numbers[k].first;
    }
  }
  EXPECT_EQ(resumed->steps(), whole->steps());

  const double t_whole = whole->advance_to(kRun);
  const double t_resumed = resumed->advance_to(kRun);
  EXPECT_EQ(t_resumed, t_whole);
  EXPECT_EQ(resumed->steps(), whole->steps());
  EXPECT_EQ(resumed->cost().work, whole->cost().work);
  const Totals a = totals(whole->gather_frame().v), b = totals(resumed->gather_frame().v);
  EXPECT_NEAR(b.energy, a.energy, promises.resumed_energy * a.energy);
  if (promises.resumed_energy == 0.0) {
    EXPECT_EQ(resumed->gather_frame().x, whole->gather_frame().x);
  }
  RecordProperty("resumed_energy_difference", digits(b.energy / a.energy - 1.0));

  // A state of another scene is refused.
  EngineState wrong = saved;
  wrong.particles.x.resize(3);
  wrong.particles.v.resize(3);
  EXPECT_THROW(make(s)->restore_state(wrong), std::invalid_argument);
}

TEST_P(EveryEngine, ReportsItsCostAndAVirialPerParticle) {
  const ParticleScene s = scene(0.9);
  const auto engine = make(s);
  engine->set_up(sample(s));
  const auto virial_matches = [&] {
    const LocalVirial w = engine->local_virial();
    EXPECT_EQ(w.xx.size(), w.yy.size());
    // Empty: not measured at this state; else one value per local particle.
    if (!w.xx.empty()) {
      EXPECT_EQ(w.xx.size(), std::size_t(engine->local_particles().count));
    }
    return w;
  };
  virial_matches();
  engine->advance_to(1.0);
  const LocalVirial w = virial_matches();
  for (std::size_t i = 0; i < w.xx.size(); ++i) {
    ASSERT_TRUE(std::isfinite(w.xx[i]) && std::isfinite(w.yy[i])) << i;
  }
  const EngineCost cost = engine->cost();
  EXPECT_GT(cost.wall_seconds, 0.0);
  EXPECT_FALSE(cost.work_unit.empty());
  EXPECT_GT(cost.work, 0.0);
  for (const EngineDetail& d : engine->details()) EXPECT_FALSE(d.key.empty());
  for (const auto& [name, value] : engine->series_values()) {
    EXPECT_FALSE(name.empty());
    EXPECT_TRUE(std::isfinite(value)) << name;
  }
}

// Whether the engine declares md.ranks_per_member, with which its members run apart on groups of
// ranks.
bool declares_ranks_per_member(const std::string& engine) {
  for (const ParticleEngineKey& key : particle_engine_keys()) {
    if (key.engine == engine && key.section == "md" && key.spec.name == kRanksPerMemberKey)
      return true;
  }
  return false;
}

// An engine whose members run apart (scene/md_members.hpp): two runs on engines of their own,
// their totals added in order, give the work (its own unit) and the details of the two runs on
// one engine.
TEST_P(EveryEngine, TotalsOfMembersRunApartAddUpToThoseOfOneEngine) {
  const ParticleScene s = scene(0.5);
  const auto one = make(s);
  if (!one->independent_members() && !declares_ranks_per_member(GetParam()))
    GTEST_SKIP() << GetParam() << " runs its members in turn";
  const ParticleSample first = sample(s), second = sample_particles(s, hydro::uniform_fields(), 8);
  one->set_up(first);
  one->advance_to(kRun);
  one->set_up(second);
  one->advance_to(kRun);
  const auto a = make(s), b = make(s), merged = make(s);
  a->set_up(first);
  a->advance_to(kRun);
  b->set_up(second);
  b->advance_to(kRun);
  merged->restore_state(a->save_state(false));
  merged->add_totals(b->save_state(false));
  EXPECT_GT(one->cost().work, 0.0);
  EXPECT_EQ(merged->cost().work, one->cost().work);
  EXPECT_EQ(merged->cost().work_unit, one->cost().work_unit);
  EXPECT_EQ(merged->steps(), one->steps());  // the later run's own count
  const EngineDetails d1 = one->details(), d2 = merged->details();
  ASSERT_EQ(d1.size(), d2.size());
  for (std::size_t i = 0; i < d1.size(); ++i) {
    EXPECT_EQ(d1[i].key, d2[i].key);
    const bool clock = d1[i].key.find("per_second") != std::string::npos ||
                       d1[i].key.find("seconds") != std::string::npos;
    if (!clock) {  // a rate differs by the clock
      EXPECT_EQ(d1[i].value, d2[i].value) << d1[i].key;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Registered, EveryEngine, ::testing::ValuesIn(particle_engine_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

}  // namespace
}  // namespace granvv::md
