// The reduction of a particle ensemble (compare/particle_ensemble.hpp): pressure and
// compressibility averaged over samples and members with their errors, the homogeneous window
// and the Haff fit of the ensemble, on synthetic members with answers worked by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "compare/particle_ensemble.hpp"
#include "compare/pressure_comparison.hpp"
#include "hydro/dilute_closure.hpp"

namespace {

using granvv::compare::MemberSamples;
using granvv::compare::reduce_particle_ensemble;

// A member cooling exactly by Haff's law T = T0 (1 + t/t0)^-2 at t = 0, 1, ..., 5, with the
// given mode-energy fractions and constant pressure samples.
MemberSamples haff_member(double T0, double t0, std::vector<double> fractions, double pxx,
                          double pyy, double stderr_p, double z) {
  MemberSamples m;
  for (int i = 0; i <= 5; ++i) {
    m.t.push_back(i);
    m.T.push_back(T0 / std::pow(1.0 + i / t0, 2));
    m.pressure_xx.push_back(pxx);
    m.pressure_yy.push_back(pyy);
    m.pressure_stderr.push_back(stderr_p);
    m.compressibility.push_back(z);
  }
  m.mode_energy_fraction = std::move(fractions);
  return m;
}

const std::vector<double> kQuiet = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};

TEST(ParticleEnsemble, PressureAndCompressibilityWithTheLargerOfScatterAndPropagatedError) {
  // Member 1: p = (2 + 4)/2 = 3, sigma_p = 0.2, Z = 1.5, sigma_Z = 0.2 * 1.5 / 3 = 0.1.
  // Member 2: p = 5, Z = 2.5, sigma_Z = 0.1. Means 4 and 2; the scatter of the members' means,
  // |3 - 5| / 2 = 1 and |1.5 - 2.5| / 2 = 0.5, exceeds the propagated 0.2 / sqrt(6) / sqrt(2)
  // and 0.1 / sqrt(6) / sqrt(2). Tolerance: a few roundings of the sums and square roots.
  const auto e = reduce_particle_ensemble({haff_member(1.0, 2.0, kQuiet, 2.0, 4.0, 0.2, 1.5),
                                           haff_member(1.0, 2.0, kQuiet, 4.0, 6.0, 0.2, 2.5)},
                                          0.1, 5.0);
  EXPECT_NEAR(e.pressure.mean, 4.0, 1e-14);
  EXPECT_NEAR(e.pressure.error, 1.0, 1e-14);
  EXPECT_EQ(e.pressure.members, 2);
  EXPECT_NEAR(e.compressibility.mean, 2.0, 1e-14);
  EXPECT_NEAR(e.compressibility.error, 0.5, 1e-14);
  // One member: the error is the propagated one, sqrt(6 * 0.2^2) / 6 = 0.2 / sqrt(6).
  const auto one =
      reduce_particle_ensemble({haff_member(1.0, 2.0, kQuiet, 2.0, 4.0, 0.2, 1.5)}, 0.1, 5.0);
  EXPECT_NEAR(one.pressure.error, 0.2 / std::sqrt(6.0), 1e-15);
  EXPECT_NEAR(one.compressibility.error, 0.1 / std::sqrt(6.0), 1e-15);
  // Without a contact virial (NaN samples) there is no average.
  const auto none =
      reduce_particle_ensemble({haff_member(1.0, 2.0, kQuiet, NAN, NAN, NAN, NAN)}, 0.1, 5.0);
  EXPECT_TRUE(std::isnan(none.pressure.mean));
  EXPECT_TRUE(std::isnan(none.compressibility.mean));
}

TEST(ParticleEnsemble, HaffFitOfTheEnsembleIsTheMeanOfTheMembersWithTheirScatter) {
  // Exact cooling curves with t0 = 2 and 4: each member's line through T^-1/2 is exact, so
  // t0 = 3 with the standard error |2 - 4| / 2 = 1, T0 = 1. Tolerance: the least-squares sums
  // of 6 points round at ~1e-15 relative.
  const auto e = reduce_particle_ensemble(
      {haff_member(1.0, 2.0, kQuiet, 1, 1, 0, 1), haff_member(1.0, 4.0, kQuiet, 1, 1, 0, 1)}, 0.1,
      5.0);
  EXPECT_NEAR(e.haff.t0, 3.0, 1e-12);
  EXPECT_NEAR(e.haff.t0_error, 1.0, 1e-12);
  EXPECT_NEAR(e.haff.T0, 1.0, 1e-12);
  EXPECT_EQ(e.haff.runs, 2);
  EXPECT_TRUE(e.homogeneous.starts_homogeneous);
  EXPECT_TRUE(std::isnan(e.homogeneous.onset));
  EXPECT_EQ(e.haff.t_max, 5.0);  // never inhomogeneous: the whole run
  // The temperature's ensemble mean and error, sample by sample: at t = 1, (4/9 + 16/25) / 2.
  EXPECT_NEAR(e.T.mean[1], 0.5 * (4.0 / 9.0 + 16.0 / 25.0), 1e-15);
  EXPECT_NEAR(e.T.standard_error[1], 0.5 * (16.0 / 25.0 - 4.0 / 9.0), 1e-15);
}

TEST(ParticleEnsemble, TheFitStopsWhereTheModesTakeTheEnergy) {
  // The mean mode-energy fraction crosses 0.1 at t = 4 (member 1: 0.3, member 2: 0: mean 0.15),
  // so the window ends at the sample before, t = 3, and the exact curves still give t0 = 2.
  const auto e =
      reduce_particle_ensemble({haff_member(1.0, 2.0, {0, 0, 0, 0, 0.3, 0.3}, 1, 1, 0, 1),
                                haff_member(1.0, 2.0, kQuiet, 1, 1, 0, 1)},
                               0.1, 5.0);
  EXPECT_EQ(e.homogeneous.onset, 4.0);
  EXPECT_EQ(e.homogeneous.t_max, 3.0);
  EXPECT_EQ(e.haff.t_max, 3.0);
  EXPECT_EQ(e.haff.points, 4);
  EXPECT_NEAR(e.haff.t0, 2.0, 1e-12);
  EXPECT_NEAR(e.mode_energy_fraction.mean[4], 0.15, 1e-17);
  // Crossed at t = 2: the window t <= 1 holds two samples, too few for a fit: NaN, not a throw.
  const auto early = reduce_particle_ensemble(
      {haff_member(1.0, 2.0, {0, 0, 0.5, 0.5, 0.5, 0.5}, 1, 1, 0, 1)}, 0.1, 5.0);
  EXPECT_TRUE(std::isnan(early.haff.t0));
  EXPECT_TRUE(std::isnan(early.haff.t0_error));
  EXPECT_TRUE(std::isnan(early.haff.T0));
}

TEST(PressureComparison, NormalPressureAndItsErrorByHand) {
  EXPECT_EQ(granvv::compare::normal_pressure({2.0, 4.0}, {4.0, 8.0}),
            (std::vector<double>{3.0, 6.0}));
  // hypot(0.3, 0.4) / 2 = 0.25 (one rounding of hypot).
  const auto e = granvv::compare::normal_pressure_error({0.3}, {0.4});
  EXPECT_NEAR(e[0], 0.25, 1e-16);
}

TEST(PressureComparison, ClosurePressureInMdUnits) {
  // The dilute closure's p = n T (paper Eq. 1): n_md = 0.1 at n0 = 0.05 is n = 2; at T = 3,
  // p = 6 and p_md = 6 * 0.05 = 0.3. Bins without a finite, positive n or T give NaN.
  const granvv::hydro::DiluteClosure closure({1e-2, 0.05});
  const auto p = granvv::compare::closure_pressure_md(closure, {0.1, 0.0, NAN, 0.1},
                                                      {3.0, 1.0, 1.0, -1.0}, 0.05);
  ASSERT_EQ(p.size(), 4u);
  EXPECT_NEAR(p[0], 0.3, 1e-16);
  EXPECT_TRUE(std::isnan(p[1]));
  EXPECT_TRUE(std::isnan(p[2]));
  EXPECT_TRUE(std::isnan(p[3]));
}

TEST(ParticleEnsemble, NoMembersIsRefused) {
  EXPECT_THROW(reduce_particle_ensemble({}, 0.1, 1.0), std::invalid_argument);
}

}  // namespace
