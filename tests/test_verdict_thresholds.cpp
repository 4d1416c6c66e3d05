// The thresholds that decide a verdict, each defined once in the library that owns the verdict,
// and the small judgements and theory values the writers report beside them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "compare/cooling_sweep.hpp"
#include "compare/haff_fit.hpp"
#include "hydro/linear_mode_measurement.hpp"
#include "hydro/singularity_analysis.hpp"
#include "md_bridge/hard_disk_theory.hpp"
#include "md_bridge/particle_engine.hpp"

namespace {

namespace compare = granvv::compare;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(VerdictThresholds, TheDocumentedValues) {
  EXPECT_EQ(compare::kHaffTimeTolerance, 0.03);               // docs/physics.md §4
  EXPECT_EQ(granvv::md::kRestitutionTolerance, 1e-3);         // docs/outputs.md
  EXPECT_EQ(granvv::hydro::kSingularityTimeTolerance, 0.02);  // paper Fig. 4a
  EXPECT_EQ(granvv::hydro::kLinearRateTolerance, 1e-3);
  EXPECT_EQ(compare::kCoolsDifferentlyRelative, 0.1);
  EXPECT_EQ(compare::kCoolsDifferentlySigmas, 3.0);
  EXPECT_EQ(compare::kCoolingSweepSigmas, 3.0);
}

TEST(VerdictThresholds, HaffTimeWithinToleranceIsInclusiveAndNullWithoutAFit) {
  EXPECT_EQ(compare::haff_time_within_tolerance(0.03), true);
  EXPECT_EQ(compare::haff_time_within_tolerance(-0.03), true);
  EXPECT_EQ(compare::haff_time_within_tolerance(0.0301), false);
  EXPECT_FALSE(compare::haff_time_within_tolerance(kNaN).has_value());
}

TEST(VerdictThresholds, ADeviationFromAHaffTimeNeedsAFiniteTheory) {
  EXPECT_DOUBLE_EQ(compare::relative_deviation(1.1, 1.0), 1.1 - 1.0);
  // An elastic gas: the theory's t0 is infinite (no cooling), so there is no deviation (not -1).
  EXPECT_TRUE(
      std::isnan(compare::relative_deviation(5.0, std::numeric_limits<double>::infinity())));
  EXPECT_TRUE(std::isnan(compare::relative_deviation(5.0, 0.0)));
  EXPECT_TRUE(std::isnan(compare::relative_deviation(5.0, std::nan(""))));
  // A measured t0 that is absent stays absent.
  EXPECT_TRUE(std::isnan(compare::relative_deviation(std::nan(""), 1.0)));
}

TEST(VerdictThresholds, HaffCurveIsHaffsLawWithTheFittedAmplitude) {
  // T0 (1 + t/t0)^-2 at t = 0, t0, 3 t0: T0, T0/4, T0/16, exact in binary.
  const auto T = compare::haff_curve({0.0, 2.0, 6.0}, 0.5, 2.0);
  ASSERT_EQ(T.size(), 3u);
  EXPECT_EQ(T[0], 0.5);
  EXPECT_EQ(T[1], 0.125);
  EXPECT_EQ(T[2], 0.03125);
}

TEST(VerdictThresholds, AModelCoolsDifferentlyOnlyBeyondBothTenPercentAndThreeErrors) {
  compare::HaffFit fit;
  fit.t0 = 10.0;
  fit.t0_error = 0.2;
  EXPECT_EQ(compare::cools_differently(12.0, fit), true);   // 20 %, 10 errors
  EXPECT_EQ(compare::cools_differently(10.5, fit), false);  // 5 %, 2.5 errors
  fit.t0_error = 1.0;
  EXPECT_EQ(compare::cools_differently(12.0, fit), false);  // 20 %, but 2 errors
  fit.t0_error = 0.0;
  EXPECT_FALSE(compare::cools_differently(12.0, fit).has_value());  // no error to judge by
  fit.t0 = kNaN;
  fit.t0_error = 0.2;
  EXPECT_FALSE(compare::cools_differently(12.0, fit).has_value());  // no fit
}

TEST(VerdictThresholds, RestitutionMissesBeyondItsTolerance) {
  granvv::md::CollisionRuleCheck check;
  check.restitution = 0.9005;
  EXPECT_FALSE(granvv::md::misses_restitution(check, 0.9));
  check.restitution = 0.8985;
  EXPECT_TRUE(granvv::md::misses_restitution(check, 0.9));
  check.restitution = kNaN;
  EXPECT_FALSE(granvv::md::misses_restitution(check, 0.9));
}

TEST(VerdictThresholds, EnskogCompressibilityOfTheScene) {
  // phi = 1/4: chi = (1 - 7/64) / (9/16) = 57/36; r = 0.5: Z = 1 + 1.5 * 0.25 * 57/36 = 1.59375.
  // r = 1 gives Henderson's Z. Tolerance: a few roundings.
  granvv::md::ParticleScene s;
  s.area_fraction = 0.25;
  s.restitution = 0.5;
  EXPECT_NEAR(granvv::md::enskog_compressibility(s), 1.59375, 1e-15);
  s.restitution = 1.0;
  EXPECT_NEAR(granvv::md::enskog_compressibility(s), granvv::md::henderson_compressibility(0.25),
              1e-15);
}

TEST(VerdictThresholds, CoolingSweepJudgesEachPointAndThePowerAgainstSigmas) {
  // Point 1: t0 = 10 +- 0.5 against Enskog 11: deviation -1/11, -2 errors, within 3. Point 2:
  // t0 = 5 +- 0.1 against 5.5: -5 errors, beyond. Exact rates zeta = 2/t0.
  std::vector<compare::CoolingPoint> points(2);
  points[0] = {0.9, 10.0, 0.5, 11.0, 12.0, 9.0};
  points[1] = {0.8, 5.0, 0.1, 5.5, 6.0, 4.0};
  const auto s = compare::analyse_cooling_sweep(points, 0.0, 3.0);
  EXPECT_EQ(s.sigmas, 3.0);
  EXPECT_NEAR(s.enskog_deviation[0], -1.0 / 11.0, 1e-15);
  EXPECT_NEAR(s.enskog_deviation_sigmas[0], -2.0, 1e-15);
  EXPECT_FALSE(s.enskog_beyond_sigmas[0]);
  EXPECT_NEAR(s.enskog_deviation_sigmas[1], -5.0, 1e-13);
  EXPECT_TRUE(s.enskog_beyond_sigmas[1]);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(bool(s.paper_beyond_sigmas[i]), std::abs(s.paper_deviation_sigmas[i]) > 3.0);
  }
  // Two points: the power law through them, and its deviation from kinetic theory's 1.
  ASSERT_TRUE(s.power.has_value());
  ASSERT_TRUE(s.power_deviation_from_one_sigmas.has_value());
  const double z = (s.power->power - 1.0) / s.power->power_error;
  EXPECT_EQ(*s.power_deviation_from_one_sigmas, z);
  EXPECT_EQ(s.power_consistent_with_one, std::abs(z) <= 3.0);
  // One point: no power law, nothing to judge.
  const auto one = compare::analyse_cooling_sweep({points[0]}, 0.0, 3.0);
  EXPECT_FALSE(one.power_deviation_from_one_sigmas.has_value());
  EXPECT_FALSE(one.power_consistent_with_one.has_value());
}

}  // namespace
