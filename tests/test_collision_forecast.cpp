// The collision forecast (md_bridge/collision_forecast.hpp) against its known answers: a
// homogeneous gas gives Enskog's frequency integrated over Haff's law (the estimate without
// clusters), a stated two-phase density the mass-weighted sum of its phases, a packing held by
// the TC rule collides at its cap; the gathered mass of a sine mode's flow by inertia at its
// closed-form points; the linear theory's onset at its defining growth.
#include <gtest/gtest.h>

#include <cmath>

#include "fields/constants.hpp"
#include "hydro/haff.hpp"
#include "hydro/linear_stability.hpp"
#include "md_bridge/collision_forecast.hpp"
#include "md_bridge/hard_disk_theory.hpp"
#include "md_bridge/particle_engine_registry.hpp"

namespace granvv::md {
namespace {

constexpr double kN = 10000.0;

// (N/2) nu(phi, T) t0 ln(1 + t/t0): N disks at one area fraction, cooling by Haff's law.
double homogeneous(double phi, double T, double t0, double t) {
  return 0.5 * kN * enskog_collision_frequency(4.0 * phi / kPi, phi, T) * t0 * std::log1p(t / t0);
}

// Rounding only: the forecast sums the same closed forms.
constexpr double kRoundOff = 1e-12;

TEST(CollisionForecast, AHomogeneousGasMakesEnskogsCollisionsOverHaffsLaw) {
  const Cooling cooling{1.5, 400.0};
  const std::vector<DensityStage> gas = {{0.0, 1e9, {{1.0, 0.05}}}};
  for (double t : {10.0, 400.0, 1e5}) {
    EXPECT_NEAR(forecast_collisions(kN, gas, cooling, t) / homogeneous(0.05, 1.5, 400.0, t), 1.0,
                kRoundOff);
  }
  // Without cooling: N nu t / 2.
  EXPECT_NEAR(forecast_collisions(kN, gas, {1.0, 0.0}, 50.0),
              0.5 * kN * enskog_collision_frequency(4.0 * 0.05 / kPi, 0.05, 1.0) * 50.0,
              kRoundOff * kN);
  // Stages add: the same gas cut in two at t = 300.
  const std::vector<DensityStage> cut = {{0.0, 300.0, {{1.0, 0.05}}}, {300.0, 1e9, {{1.0, 0.05}}}};
  EXPECT_NEAR(
      forecast_collisions(kN, cut, cooling, 1e4) / forecast_collisions(kN, gas, cooling, 1e4), 1.0,
      kRoundOff);
}

TEST(CollisionForecast, AStatedTwoPhaseDensityGivesTheWeightedSum) {
  const Cooling cooling{1.0, 400.0};
  const double t = 2e4;
  // 30 % of the disks in packings at phi = 0.82 from t = 5000, the rest a gas at 0.02; before
  // that all at 0.05.
  const std::vector<DensityStage> stages = {{0.0, 5000.0, {{1.0, 0.05}}},
                                            {5000.0, 1e9, {{0.3, 0.82}, {0.7, 0.02}}}};
  const double expected =
      homogeneous(0.05, 1.0, 400.0, 5000.0) +
      0.3 * (homogeneous(0.82, 1.0, 400.0, t) - homogeneous(0.82, 1.0, 400.0, 5000.0)) +
      0.7 * (homogeneous(0.02, 1.0, 400.0, t) - homogeneous(0.02, 1.0, 400.0, 5000.0));
  EXPECT_NEAR(forecast_collisions(kN, stages, cooling, t) / expected, 1.0, kRoundOff);
}

TEST(CollisionForecast, APackingHeldByTheTcRuleCollidesAtItsCap) {
  const double t0 = 400.0, cap = 0.05;
  const double nu_h = enskog_collision_frequency(4.0 * 0.82 / kPi, 0.82, 1.0);
  const Cooling cooling{1.0, t0};
  const std::vector<DensityStage> packed = {{0.0, 1e9, {{1.0, 0.82, cap}}}};
  // Enskog's frequency nu_h / (1 + t/t0) stays above the cap until t_cap: the cap throughout.
  const double t_cap = t0 * (nu_h / cap - 1.0);
  EXPECT_NEAR(
      forecast_collisions(kN, packed, cooling, 0.5 * t_cap) / (0.5 * kN * cap * 0.5 * t_cap), 1.0,
      kRoundOff);
  // Past t_cap Enskog's frequency, which is below the cap.
  const double t = 3.0 * t_cap;
  EXPECT_NEAR(forecast_collisions(kN, packed, cooling, t) /
                  (0.5 * kN * (cap * t_cap + nu_h * t0 * std::log((t0 + t) / (t0 + t_cap)))),
              1.0, kRoundOff);
  // A cap above Enskog's frequency changes nothing.
  const std::vector<DensityStage> loose = {{0.0, 1e9, {{1.0, 0.82, 2.0 * nu_h}}}};
  EXPECT_NEAR(forecast_collisions(kN, loose, cooling, t) / homogeneous(0.82, 1.0, t0, t), 1.0,
              kRoundOff);
}

// x / sin x = t / tau with the label xi = x / (2 pi), and the mass within |xi| is 2 xi = x / pi.
TEST(CollisionForecast, TheFlowByInertiaGathersASineModesMass) {
  EXPECT_EQ(gathered_mass_fraction(0.9, 1.0), 0.0);
  EXPECT_EQ(gathered_mass_fraction(5.0, std::numeric_limits<double>::infinity()), 0.0);
  EXPECT_NEAR(gathered_mass_fraction(kPi / 2.0, 1.0), 0.5, 1e-12);
  // x / sin x = 2 at x = 1.895494267034 (solved independently to 1e-12).
  EXPECT_NEAR(gathered_mass_fraction(2.0, 1.0), 1.895494267034 / kPi, 1e-10);
  EXPECT_GT(gathered_mass_fraction(1e4, 1.0), 0.999);
}

// The fastest clustering mode grows by sqrt(N)/2 from 0 to the onset: (1 + t*/t0)^(lambda t0)
// = sqrt(N)/2 in scaled time; none in an elastic gas or a box without clustering modes.
TEST(CollisionForecast, TheLinearTheorysOnsetIsWhereTheFastestModeReachesOne) {
  const ParticleScene scene = scene_from_scaled(4e-4, 0.01, 0.05, 10.0);  // md_paper_scene
  const double onset = linear_clustering_onset_md(scene);
  ASSERT_TRUE(std::isfinite(onset));
  const hydro::Physics physics = scene.physics();
  double fastest = 0.0;
  for (int k = 1; k < hydro::clustering_cutoff_mode(physics); ++k) {
    fastest = std::max(fastest, hydro::hcs_modes(physics, k)[0].rate.real());
  }
  const double t0 = hydro::haff_time_scale(physics);
  EXPECT_NEAR(fastest * t0 * std::log1p(scene.scaled_time(onset) / t0),
              std::log(0.5 * std::sqrt(double(scene.particles))), 1e-9);
  EXPECT_TRUE(std::isinf(linear_clustering_onset_md(scene_from_scaled(4e-4, 0.0, 0.05, 10.0))));
  // K = 0.08, q = 0.05 (shear_wave): sqrt(q) / (pi K) < 1, no clustering mode.
  EXPECT_TRUE(std::isinf(linear_clustering_onset_md(scene_from_scaled(0.08, 0.05, 0.02, 100.0))));
}

// The engine's estimate: a scene without clustering modes is the homogeneous gas, whatever its
// initial flow, and so is a clustering scene without the TC rule (free packings cost what the
// gas does); the progress line's share of a member's work follows the same model.
TEST(CollisionForecast, TheEventDrivenEstimateOfAStableGasIsTheHomogeneousOne) {
  const ParticleScene scene = scene_from_scaled(0.08, 0.05, 0.02, 100.0);
  ParticleWorkQuestion q;
  q.scene = scene;
  q.settings["md.contact_duration"] = 0.0;
  q.t_end = 2220.0;
  q.haff_time = haff_time_md(scene, enskog_chi(scene.area_fraction));
  q.profile_collapse_time = 100.0;  // pressure stops it: no clustering mode
  const ParticleWorkEstimate w = estimate_particle_work("event_driven", q);
  const double nu0 = enskog_collision_frequency(scene.number_density(), scene.area_fraction, 1.0);
  const double expected =
      0.5 * double(scene.particles) * nu0 * q.haff_time * std::log1p(q.t_end / q.haff_time);
  EXPECT_NEAR(w.work / expected, 1.0, kRoundOff);
  EXPECT_NEAR(w.member_work_until(0.5 * q.t_end) / w.member_work_until(q.t_end),
              std::log1p(0.5 * q.t_end / q.haff_time) / std::log1p(q.t_end / q.haff_time),
              kRoundOff);
  const ParticleScene clustering = scene_from_scaled(4e-4, 0.01, 0.05, 10.0);
  q.scene = clustering;
  q.t_end = 141796.3;
  q.haff_time = haff_time_md(clustering, enskog_chi(clustering.area_fraction));
  q.profile_collapse_time = clustering.md_time(1.0 / (2.0 * kPi * 0.05));
  const double nu = enskog_collision_frequency(clustering.number_density(), 0.05, 1.0);
  EXPECT_NEAR(estimate_particle_work("event_driven", q).work /
                  (0.5 * double(clustering.particles) * nu * q.haff_time *
                   std::log1p(q.t_end / q.haff_time)),
              1.0, kRoundOff);
}

// md_paper_scene's scene clusters: the packings (held at 1/(2 t_c) by its TC rule, t_c = 10)
// make most of its collisions, several times the homogeneous gas's.
TEST(CollisionForecast, AClusteringSceneCountsItsPackings) {
  const ParticleScene scene = scene_from_scaled(4e-4, 0.01, 0.05, 10.0);
  ParticleWorkQuestion q;
  q.scene = scene;
  q.settings["md.contact_duration"] = 10.0;
  q.t_end = 141796.3;
  q.haff_time = haff_time_md(scene, enskog_chi(scene.area_fraction));
  q.profile_collapse_time = scene.md_time(1.0 / (2.0 * kPi * 0.05));
  const ParticleWorkEstimate w = estimate_particle_work("event_driven", q);
  const double nu0 = enskog_collision_frequency(scene.number_density(), scene.area_fraction, 1.0);
  const double gas =
      0.5 * double(scene.particles) * nu0 * q.haff_time * std::log1p(q.t_end / q.haff_time);
  EXPECT_GT(w.work, 3.0 * gas);
  // The packings' collisions come late: half the work is done well after half the time.
  EXPECT_LT(w.member_work_until(0.5 * q.t_end), 0.5 * w.work);
}

}  // namespace
}  // namespace granvv::md
