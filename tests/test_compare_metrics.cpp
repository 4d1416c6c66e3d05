// The pure functions of compare/ against exact answers: the ensemble mean and its standard error
// (compare/ensemble_statistics.hpp), the field norms, the k-sigma fraction and the agreement
// window (compare/field_metrics.hpp), the weighted power-law fit (compare/power_law_fit.hpp), and
// the binning of a Lagrangian state onto the particles' bins (compare/binned_fields.hpp):
// uniform states, exact conservation of mass, momentum and energy, the sub-bin flow heat
// T + u^2/6, the periodic wrap, and flow by inertia against its exact density n = 1/(1 + t v0').
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "compare/binned_fields.hpp"
#include "compare/density_modes.hpp"
#include "compare/ensemble_statistics.hpp"
#include "compare/field_metrics.hpp"
#include "compare/power_law_fit.hpp"
#include "fields/constants.hpp"

namespace {

using granvv::compare::agreement_window;
using granvv::compare::AgreementWindow;
using granvv::compare::bin_lagrangian_state;
using granvv::compare::ensemble_statistics;
using granvv::compare::EnsembleStatistics;
using granvv::compare::field_agrees;
using granvv::compare::field_difference;
using granvv::compare::FieldDifference;
using granvv::compare::FieldTrack;
using granvv::compare::fit_power_law;
using granvv::compare::flow_by_inertia_state;
using granvv::compare::PowerLawFit;
using granvv::fields::FieldSnapshot;
using granvv::hydro::InitialFields;
using granvv::hydro::LagrangianState;

using granvv::kPi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------------
// ensemble_statistics

TEST(EnsembleStatistics, MeanAndBesselCorrectedStandardErrorByHand) {
  // Ragged: the third member stopped after two elements. Element 0: {1, 3, 5}, mean 3,
  // s^2 = (4 + 0 + 4)/2 = 4, SE = 2/sqrt(3). Element 1: {2, 4, 9}, mean 5, s^2 = (9 + 1 + 16)/2
  // = 13, SE = sqrt(13/3). Element 2: {3, 5}, mean 4, s^2 = 2, SE = sqrt(2/2) = 1. Tolerance:
  // rounding of a handful of operations on O(1) numbers (1e-14).
  const EnsembleStatistics s = ensemble_statistics({{1, 2, 3}, {3, 4, 5}, {5, 9}});
  ASSERT_EQ(s.mean.size(), 3u);
  ASSERT_EQ(s.standard_error.size(), 3u);
  ASSERT_EQ(s.members.size(), 3u);
  EXPECT_NEAR(s.mean[0], 3.0, 1e-14);
  EXPECT_NEAR(s.mean[1], 5.0, 1e-14);
  EXPECT_NEAR(s.mean[2], 4.0, 1e-14);
  EXPECT_NEAR(s.standard_error[0], 2.0 / std::sqrt(3.0), 1e-14);
  EXPECT_NEAR(s.standard_error[1], std::sqrt(13.0 / 3.0), 1e-14);
  EXPECT_NEAR(s.standard_error[2], 1.0, 1e-14);
  EXPECT_EQ(s.members, (std::vector<int>{3, 3, 2}));
}

TEST(EnsembleStatistics, RaggedMembersSetTheLengthAndShortOnesDropOut) {
  // The result is as long as the longest member, wherever it is in the list; an element only one
  // member reaches has that member's value as mean and no standard error (k = 1).
  const EnsembleStatistics s = ensemble_statistics({{2.0}, {4.0, 10.0, 7.5}, {}});
  ASSERT_EQ(s.mean.size(), 3u);
  EXPECT_EQ(s.members, (std::vector<int>{2, 1, 1}));
  EXPECT_NEAR(s.mean[0], 3.0, 1e-14);
  EXPECT_NEAR(s.standard_error[0], 1.0, 1e-14);  // s^2 = 2, SE = sqrt(2/2)
  EXPECT_EQ(s.mean[1], 10.0);
  EXPECT_EQ(s.mean[2], 7.5);
  EXPECT_TRUE(std::isnan(s.standard_error[1]));
  EXPECT_TRUE(std::isnan(s.standard_error[2]));

  const EnsembleStatistics none = ensemble_statistics({});
  EXPECT_TRUE(none.mean.empty());
  EXPECT_TRUE(none.standard_error.empty());
  EXPECT_TRUE(none.members.empty());
}

TEST(EnsembleStatistics, NonFiniteEntriesAreSkipped) {
  // An empty bin (NaN) or an overflow (inf) in one member must not poison the others.
  // Element 0: {1, 3} -> mean 2, SE 1. Element 1: {4, 6, 8} -> mean 6, s^2 = 4, SE 2/sqrt(3).
  // Element 2: {2} -> mean 2, SE NaN. Element 3: nothing finite -> NaN, NaN, 0 members.
  const EnsembleStatistics s = ensemble_statistics(
      {{1, kNaN, 2, kNaN}, {3, 4, kInf, -kInf}, {kNaN, 6, kNaN, kNaN}, {kNaN, 8}});
  ASSERT_EQ(s.mean.size(), 4u);
  EXPECT_EQ(s.members, (std::vector<int>{2, 3, 1, 0}));
  EXPECT_NEAR(s.mean[0], 2.0, 1e-14);
  EXPECT_NEAR(s.standard_error[0], 1.0, 1e-14);
  EXPECT_NEAR(s.mean[1], 6.0, 1e-14);
  EXPECT_NEAR(s.standard_error[1], 2.0 / std::sqrt(3.0), 1e-14);
  EXPECT_EQ(s.mean[2], 2.0);
  EXPECT_TRUE(std::isnan(s.standard_error[2]));
  EXPECT_TRUE(std::isnan(s.mean[3]));
  EXPECT_TRUE(std::isnan(s.standard_error[3]));
}

TEST(EnsembleStatistics, OneMemberHasNoStandardError) {
  const EnsembleStatistics s = ensemble_statistics({{0.25, -3.0, kNaN}});
  EXPECT_EQ(s.members, (std::vector<int>{1, 1, 0}));
  EXPECT_EQ(s.mean[0], 0.25);
  EXPECT_EQ(s.mean[1], -3.0);
  EXPECT_TRUE(std::isnan(s.mean[2]));
  for (const double e : s.standard_error) EXPECT_TRUE(std::isnan(e));
}

TEST(EnsembleStatistics, SmallSpreadOnALargeMeanKeepsItsDigits) {
  // Temperatures of seeds that agree to 1e-8 relative: 1e8 + {1, 2, 3, 6}. Mean 1e8 + 3,
  // deviations {-2, -1, 0, 3}: s^2 = 14/3, SE = sqrt(14/12). A one-pass sum of squares would
  // cancel 1e16 against 1e16 and keep nothing; the two-pass result is exact up to the rounding of
  // the inputs (1e8 ulp ~ 1.5e-8), so 1e-7 relative.
  const double big = 1e8;
  const EnsembleStatistics s = ensemble_statistics({{big + 1}, {big + 2}, {big + 3}, {big + 6}});
  EXPECT_EQ(s.mean[0], big + 3);
  EXPECT_NEAR(s.standard_error[0] / std::sqrt(14.0 / 12.0), 1.0, 1e-7);
}

// ---------------------------------------------------------------------------------------------
// field_difference

TEST(CompareFieldDifference, NormsFractionAndWorstZByHand) {
  // d = hydro - md = {-0.5, 1, 0, -2}, errors {1, 0.5, 1, 1}, scale 2, k = 1.5:
  // L1 = (0.5 + 1 + 0 + 2)/4/2 = 0.4375; L2 = sqrt((0.25 + 1 + 0 + 4)/4)/2; Linf = 2/2 = 1;
  // |d|/e = {0.5, 2, 0, 2}: worst_z = 2, within 1.5 sigma: 2 of 4. Rounding only (1e-15).
  const std::vector<double> hydro{1, 2, 3, 4}, md{1.5, 1, 3, 6}, err{1, 0.5, 1, 1};
  const FieldDifference f = field_difference(hydro, md, err, 2.0, 1.5);
  EXPECT_EQ(f.points, 4);
  EXPECT_EQ(f.scale, 2.0);
  EXPECT_NEAR(f.l1, 0.4375, 1e-15);
  EXPECT_NEAR(f.l2, std::sqrt(5.25 / 4.0) / 2.0, 1e-15);
  EXPECT_NEAR(f.linf, 1.0, 1e-15);
  EXPECT_NEAR(f.worst_z, 2.0, 1e-15);
  EXPECT_NEAR(f.fraction_within, 0.5, 1e-15);
  // With k = 2.5 every bin is inside; with k = 0.25 only the exact bin (d = 0).
  EXPECT_EQ(field_difference(hydro, md, err, 2.0, 2.5).fraction_within, 1.0);
  EXPECT_EQ(field_difference(hydro, md, err, 2.0, 0.25).fraction_within, 0.25);
  // The norms scale as 1/scale; the fraction and worst_z do not depend on it.
  const FieldDifference g = field_difference(hydro, md, err, 0.5, 1.5);
  EXPECT_NEAR(g.l1, 4.0 * f.l1, 1e-14);
  EXPECT_NEAR(g.l2, 4.0 * f.l2, 1e-14);
  EXPECT_NEAR(g.linf, 4.0 * f.linf, 1e-14);
  EXPECT_EQ(g.fraction_within, f.fraction_within);
  EXPECT_EQ(g.worst_z, f.worst_z);
}

TEST(CompareFieldDifference, WithinMeansStrictlyLessThanKSigma) {
  // The header: |hydro - MD| < k standard errors. d = 1, e = 0.5, k = 2 is exactly on the edge
  // (all three exact in binary) and so outside.
  const FieldDifference f = field_difference({2.0}, {1.0}, {0.5}, 1.0, 2.0);
  EXPECT_EQ(f.fraction_within, 0.0);
  EXPECT_EQ(f.worst_z, 2.0);
  EXPECT_EQ(field_difference({2.0}, {1.0}, {0.5}, 1.0, std::nextafter(2.0, 3.0)).fraction_within,
            1.0);
}

TEST(CompareFieldDifference, NonFiniteBinsAreSkipped) {
  // The four bins of the hand-computed case plus bins with NaN hydro, infinite MD, NaN error and
  // infinite error: the result must be that of the four bins alone.
  const std::vector<double> hydro{kNaN, 1, 2, 0.3, 3, 0.1, 4, 0.7};
  const std::vector<double> md{0.0, 1.5, 1, kInf, 3, 0.1, 6, 0.2};
  const std::vector<double> err{1.0, 1, 0.5, 1.0, 1, kNaN, 1, kInf};
  const FieldDifference f = field_difference(hydro, md, err, 2.0, 1.5);
  EXPECT_EQ(f.points, 4);
  EXPECT_NEAR(f.l1, 0.4375, 1e-15);
  EXPECT_NEAR(f.l2, std::sqrt(5.25 / 4.0) / 2.0, 1e-15);
  EXPECT_NEAR(f.linf, 1.0, 1e-15);
  EXPECT_NEAR(f.worst_z, 2.0, 1e-15);
  EXPECT_NEAR(f.fraction_within, 0.5, 1e-15);

  // No usable bin at all: zero points and NaN norms (not zeros that would read as agreement).
  const FieldDifference none = field_difference({kNaN, 1.0}, {1.0, kNaN}, {1.0, 1.0}, 1.0, 3.0);
  EXPECT_EQ(none.points, 0);
  EXPECT_TRUE(std::isnan(none.l1));
  EXPECT_TRUE(std::isnan(none.l2));
  EXPECT_TRUE(std::isnan(none.linf));
  EXPECT_TRUE(std::isnan(none.fraction_within));
  EXPECT_TRUE(std::isnan(none.worst_z));
  EXPECT_EQ(field_difference({}, {}, {}, 1.0, 3.0).points, 0);
}

TEST(CompareFieldDifference, ThrowsOnSizeMismatchAndBadScale) {
  const std::vector<double> a{1, 2, 3}, b{1, 2}, e{1, 1, 1};
  EXPECT_THROW(field_difference(a, b, e, 1.0, 3.0), std::invalid_argument);
  EXPECT_THROW(field_difference(b, a, e, 1.0, 3.0), std::invalid_argument);
  EXPECT_THROW(field_difference(a, a, b, 1.0, 3.0), std::invalid_argument);
  for (const double scale : {0.0, -1.0, kNaN, kInf}) {
    EXPECT_THROW(field_difference(a, a, e, scale, 3.0), std::invalid_argument) << scale;
  }
  for (const double sigmas : {0.0, -3.0, kNaN}) {
    EXPECT_THROW(field_difference(a, a, e, 1.0, sigmas), std::invalid_argument) << sigmas;
  }
  EXPECT_NO_THROW(field_difference(a, a, e, 1e-300, 3.0));
}

TEST(CompareFieldDifference, GaussianNoiseOfKnownSigmaGivesTheNormalFractions) {
  // MD = hydro + sigma_i g_i with g standard normal and sigma_i varying bin to bin (the error
  // passed is the true sigma_i). Then |d|/sigma_i < k with probability erf(k/sqrt 2):
  // 0.682689, 0.954500, 0.997300 for k = 1, 2, 3. The fraction over N bins is binomial, standard
  // error sqrt(p (1 - p) / N) (3.7e-4 at k = 3, N = 20000); tolerance 4 standard errors (a
  // random seed fails with probability 6e-5; the seed here is fixed).
  const int N = 20000;
  std::mt19937_64 rng(20240611);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> spread(0.5, 2.0);
  std::vector<double> hydro(N), md(N), err(N);
  double mean_sigma = 0.0, mean_sigma2 = 0.0, mean_sigma4 = 0.0;
  for (int i = 0; i < N; ++i) {
    const double x = -0.5 + (i + 0.5) / N;
    hydro[i] = 1.0 + 0.3 * std::sin(2 * kPi * x);
    err[i] = 0.01 * spread(rng);
    md[i] = hydro[i] + err[i] * gauss(rng);
    mean_sigma += err[i] / N;
    mean_sigma2 += err[i] * err[i] / N;
    mean_sigma4 += std::pow(err[i], 4) / N;
  }
  for (const int k : {1, 2, 3}) {
    const double p = std::erf(k / std::sqrt(2.0));
    const double se = std::sqrt(p * (1 - p) / N);
    const FieldDifference f = field_difference(hydro, md, err, 1.0, k);
    EXPECT_EQ(f.points, N);
    EXPECT_NEAR(f.fraction_within, p, 4 * se) << "k = " << k;
  }
  EXPECT_NEAR(std::erf(3 / std::sqrt(2.0)), 0.9973, 1e-4);
  const FieldDifference f = field_difference(hydro, md, err, 0.01, 3.0);
  // L1: E|d| = sqrt(2/pi) <sigma>, variance of the mean (1 - 2/pi) <sigma^2> / N.
  // L2: E d^2 = <sigma^2>, variance of the mean 2 <sigma^4> / N, so L2 has relative standard
  // error sqrt(2 <sigma^4> / N) / (2 <sigma^2>). Tolerances: 4 standard errors.
  EXPECT_NEAR(f.l1 * 0.01, std::sqrt(2 / kPi) * mean_sigma,
              4 * std::sqrt((1 - 2 / kPi) * mean_sigma2 / N));
  EXPECT_NEAR(f.l2 * 0.01 / std::sqrt(mean_sigma2), 1.0,
              4 * std::sqrt(2 * mean_sigma4 / N) / (2 * mean_sigma2));
  // The largest of 20000 |g|: P(< 3.5) = 0.99953^20000 ~ 1e-4, P(> 5.5) ~ 20000 * 3.8e-8 ~ 1e-3.
  EXPECT_GT(f.worst_z, 3.5);
  EXPECT_LT(f.worst_z, 5.5);
}

// ---------------------------------------------------------------------------------------------
// agreement_window

FieldTrack track(const std::string& name, const std::vector<double>& fractions) {
  FieldTrack t;
  t.field = name;
  for (const double f : fractions) {
    FieldDifference d;
    d.fraction_within = f;
    d.points = 10;
    t.at.push_back(d);
  }
  return t;
}

TEST(FieldAgrees, AtLeastTheRequiredFractionAndNeverWithoutBins) {
  FieldDifference d;
  d.fraction_within = 0.95;
  EXPECT_TRUE(field_agrees(d, 0.95)) << "exactly the required fraction agrees";
  d.fraction_within = 0.9499;
  EXPECT_FALSE(field_agrees(d, 0.95));
  d.fraction_within = kNaN;
  EXPECT_FALSE(field_agrees(d, 0.0)) << "a field without usable bins cannot agree";
}

TEST(AgreementWindow, AllFieldsAgreeThroughout) {
  const std::vector<double> times{0.5, 1.0, 2.0};
  const AgreementWindow w =
      agreement_window(times, {track("n", {1, 0.99, 0.96}), track("T", {0.97, 1, 1})}, 0.95);
  EXPECT_TRUE(w.throughout);
  ASSERT_TRUE(w.until.has_value());
  EXPECT_EQ(*w.until, 2.0);
  EXPECT_TRUE(w.first_out.empty());
  EXPECT_FALSE(w.left_at.has_value());
  // "At least" the required fraction agrees: exactly 0.95 of 0.95 is inside.
  const AgreementWindow edge = agreement_window(times, {track("v_x", {0.95, 0.95, 0.95})}, 0.95);
  EXPECT_TRUE(edge.throughout);
  EXPECT_EQ(edge.until.value_or(kNaN), 2.0);
}

TEST(AgreementWindow, AFieldFailingAtTheThirdTimeEndsTheWindowAtTheSecond) {
  const std::vector<double> times{0.5, 1.0, 2.0, 3.0};
  // T fails at t = 2 and recovers at t = 3: the window does not reopen.
  const AgreementWindow w = agreement_window(
      times, {track("n", {1, 1, 0.99, 0.98}), track("T", {1, 0.97, 0.6, 1})}, 0.95);
  EXPECT_FALSE(w.throughout);
  ASSERT_TRUE(w.until.has_value());
  EXPECT_EQ(*w.until, 1.0);
  EXPECT_EQ(w.first_out, "T");
  ASSERT_TRUE(w.left_at.has_value());
  EXPECT_EQ(*w.left_at, 2.0);
}

TEST(AgreementWindow, FailingAtTheFirstTimeLeavesNoWindow) {
  const AgreementWindow w =
      agreement_window({0.5, 1.0}, {track("n", {1, 1}), track("v_x", {0.2, 1})}, 0.95);
  EXPECT_FALSE(w.throughout);
  EXPECT_FALSE(w.until.has_value());
  EXPECT_EQ(w.first_out, "v_x");
  EXPECT_EQ(w.left_at.value_or(kNaN), 0.5);
}

TEST(AgreementWindow, TheWorstFailingFieldIsNamedWhateverItsOrder) {
  // At t = 1 three fields fail (0.9, 0.6, 0.8) and one passes (0.97): the smallest fraction is
  // named, in every ordering of the tracks.
  const std::vector<double> times{0.5, 1.0};
  std::vector<FieldTrack> tracks{track("n", {1, 0.97}), track("v_x", {1, 0.9}),
                                 track("T", {1, 0.6}), track("v_y", {1, 0.8})};
  std::sort(tracks.begin(), tracks.end(),
            [](const FieldTrack& a, const FieldTrack& b) { return a.field < b.field; });
  do {
    const AgreementWindow w = agreement_window(times, tracks, 0.95);
    EXPECT_EQ(w.first_out, "T") << tracks[0].field << tracks[1].field << tracks[2].field;
    EXPECT_EQ(w.until.value_or(kNaN), 0.5);
    EXPECT_EQ(w.left_at.value_or(kNaN), 1.0);
  } while (std::next_permutation(
      tracks.begin(), tracks.end(),
      [](const FieldTrack& a, const FieldTrack& b) { return a.field < b.field; }));
}

TEST(AgreementWindow, ANaNFractionCountsAsFailing) {
  // A field with no usable bins (NaN fraction) cannot be said to agree; it ranks below every
  // number, so it is named even next to a field at fraction 0.
  const std::vector<double> times{0.5, 1.0, 2.0};
  const AgreementWindow w =
      agreement_window(times, {track("n", {1, 1, 1}), track("T", {1, kNaN, 1})}, 0.95);
  EXPECT_FALSE(w.throughout);
  EXPECT_EQ(w.until.value_or(kNaN), 0.5);
  EXPECT_EQ(w.first_out, "T");
  EXPECT_EQ(w.left_at.value_or(kNaN), 1.0);
  const AgreementWindow both =
      agreement_window(times, {track("n", {1, 0.0, 1}), track("T", {1, kNaN, 1})}, 0.95);
  EXPECT_EQ(both.first_out, "T");
}

TEST(AgreementWindow, ThrowsWhenATrackDoesNotMatchTheTimes) {
  EXPECT_THROW(agreement_window({0.5, 1.0}, {track("n", {1, 1}), track("T", {1})}, 0.95),
               std::invalid_argument);
  EXPECT_THROW(agreement_window({0.5}, {track("n", {1, 1})}, 0.95), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// fit_power_law

// 1 / sum_i w_i (ln x_i - <ln x>_w)^2 with w_i = (y_i / dy_i)^2: the variance of the weighted
// least-squares slope when the stated errors are right. Centred sums, computed independently.
double slope_variance(const std::vector<double>& x, const std::vector<double>& y,
                      const std::vector<double>& dy) {
  double S = 0.0, Sa = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double w = std::pow(y[i] / dy[i], 2);
    S += w, Sa += w * std::log(x[i]);
  }
  const double mean = Sa / S;
  double var = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    var += std::pow(y[i] / dy[i], 2) * std::pow(std::log(x[i]) - mean, 2);
  }
  return 1.0 / var;
}

TEST(PowerLawFit, ExactPowerLawIsRecovered) {
  // Haff-like y = 3.7 x^-2 and a non-integer power, with unequal relative errors. Exact data:
  // power and prefactor to 1e-12 (rounding of the logs and sums), chi^2 ~ 0, and the error equal
  // to the weighted-fit formula (no inflation when the scatter is below the errors).
  const std::vector<double> x{0.5, 1, 2, 5, 10, 30, 100, 1e3};
  const std::vector<double> rel{0.01, 0.02, 0.05, 0.01, 0.03, 0.1, 0.02, 0.04};
  for (const double p : {-2.0, -1.3, 0.75}) {
    std::vector<double> y, dy;
    for (std::size_t i = 0; i < x.size(); ++i) {
      y.push_back(3.7 * std::pow(x[i], p));
      dy.push_back(rel[i] * y.back());
    }
    const PowerLawFit f = fit_power_law(x, y, dy);
    EXPECT_EQ(f.points, 8);
    EXPECT_NEAR(f.power, p, 1e-12);
    EXPECT_NEAR(f.prefactor / 3.7, 1.0, 1e-12);
    EXPECT_LT(f.chi2_per_dof, 1e-20);
    EXPECT_NEAR(f.power_error / std::sqrt(slope_variance(x, y, dy)), 1.0, 1e-12);
  }
}

TEST(PowerLawFit, TwoPointsGiveTheSlopeAndItsPropagatedError) {
  // Through two points the slope is (ln y2 - ln y1)/(ln x2 - ln x1) with error
  // sqrt(e1^2 + e2^2)/|ln x2 - ln x1| (e = dy/y); chi^2 has no degree of freedom (NaN).
  const PowerLawFit f = fit_power_law({2.0, 8.0}, {5.0, 1.25}, {0.15, 0.05});
  EXPECT_EQ(f.points, 2);
  EXPECT_NEAR(f.power, -1.0, 1e-14);  // 5 * (8/2)^-1 = 1.25
  EXPECT_NEAR(f.prefactor, 10.0, 1e-13);
  EXPECT_TRUE(std::isnan(f.chi2_per_dof));
  EXPECT_NEAR(f.power_error, std::sqrt(0.03 * 0.03 + 0.04 * 0.04) / std::log(4.0), 1e-14);
}

// Points on y = C x^p with ln y scattered by scatter_i g_i exactly, reported errors
// dy_i = stated_i y_i (so dy/y = stated_i exactly).
struct NoisyPowerLaw {
  std::vector<double> x, y, dy;
};
NoisyPowerLaw noisy_power_law(double C, double p, const std::vector<double>& scatter,
                              const std::vector<double>& stated, std::mt19937_64& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  NoisyPowerLaw d;
  const int n = static_cast<int>(scatter.size());
  for (int i = 0; i < n; ++i) {
    const double x = std::pow(10.0, 3.0 * i / (n - 1));  // 1 .. 1000, evenly in ln x
    const double y = C * std::pow(x, p) * std::exp(scatter[i] * gauss(rng));
    d.x.push_back(x), d.y.push_back(y), d.dy.push_back(stated[i] * y);
  }
  return d;
}

std::vector<double> relative_errors(int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.01, 0.05);
  std::vector<double> e(n);
  for (double& v : e) v = u(rng);
  return e;
}

TEST(PowerLawFit, NoisyPointsWithKnownErrors) {
  // Stated errors equal to the true scatter of ln y: the weighted fit is then the exact
  // Gaussian maximum-likelihood slope. |power - p| < 3 power_error (99.7 % for a random seed),
  // chi^2/dof within 4 standard deviations sqrt(2/dof) of 1, the prefactor's log within 4 of its
  // standard error sqrt(sum w a^2 / det), and no inflation when chi^2/dof < 1.
  const int n = 200;
  std::mt19937_64 rng(7);
  const std::vector<double> eps = relative_errors(n, rng);
  const double p = -2.0, C = 3.7;
  const NoisyPowerLaw d = noisy_power_law(C, p, eps, eps, rng);
  const PowerLawFit f = fit_power_law(d.x, d.y, d.dy);
  EXPECT_EQ(f.points, n);
  EXPECT_LT(std::abs(f.power - p), 3 * f.power_error);
  EXPECT_NEAR(f.chi2_per_dof, 1.0, 4 * std::sqrt(2.0 / (n - 2)));
  double S = 0, Sa = 0, Saa = 0;
  for (int i = 0; i < n; ++i) {
    const double w = 1 / (eps[i] * eps[i]), a = std::log(d.x[i]);
    S += w, Sa += w * a, Saa += w * a * a;
  }
  EXPECT_LT(std::abs(std::log(f.prefactor / C)), 4 * std::sqrt(Saa / (S * Saa - Sa * Sa)));
  const double uninflated = std::sqrt(slope_variance(d.x, d.y, d.dy));
  EXPECT_NEAR(f.power_error / (uninflated * std::sqrt(std::max(1.0, f.chi2_per_dof))), 1.0, 1e-12);
}

TEST(PowerLawFit, ReportedErrorMatchesTheScatterOverManySeeds) {
  // Calibration: over M = 1000 independent data sets the standard deviation of the fitted power
  // about the truth equals the mean reported power_error. The sample standard deviation has
  // relative standard error 1/sqrt(2M) = 2.2 %, and the inflation max(1, sqrt(chi^2/dof)) with
  // dof = 48 raises the mean reported error by about 4 %; tolerance 12 %. The mean pull is 0 with
  // standard error 1/sqrt(M); tolerance 4/sqrt(M).
  const int n = 50, M = 1000;
  std::mt19937_64 rng(12345);
  const std::vector<double> eps = relative_errors(n, rng);
  double sum_d2 = 0.0, sum_err = 0.0, sum_pull = 0.0;
  for (int m = 0; m < M; ++m) {
    const NoisyPowerLaw d = noisy_power_law(1.0, -0.8, eps, eps, rng);
    const PowerLawFit f = fit_power_law(d.x, d.y, d.dy);
    sum_d2 += std::pow(f.power + 0.8, 2);
    sum_err += f.power_error;
    sum_pull += (f.power + 0.8) / f.power_error;
  }
  EXPECT_NEAR(std::sqrt(sum_d2 / M) / (sum_err / M), 1.0, 0.12);
  EXPECT_NEAR(sum_pull / M, 0.0, 4.0 / std::sqrt(M));
}

TEST(PowerLawFit, ErrorIsInflatedWhenTheScatterExceedsTheStatedErrors) {
  // The same points with every error understated four times: the weights scale uniformly, so
  // the power is unchanged, chi^2/dof is 16 times larger, and the inflated error
  // sqrt(chi^2/dof) x (formula error) equals what the true scatter implies, i.e. the
  // uninflated error of the honest fit times sqrt(its chi^2/dof). Errors overstated four times
  // give chi^2/dof < 1 and are not deflated: power_error is 4 times the honest formula error.
  // All relations are algebraic identities: rounding only (1e-12).
  const int n = 200;
  std::mt19937_64 rng(99);
  const std::vector<double> eps = relative_errors(n, rng);
  const NoisyPowerLaw d = noisy_power_law(2.0, 1.5, eps, eps, rng);
  const PowerLawFit honest = fit_power_law(d.x, d.y, d.dy);
  std::vector<double> under(d.dy), over(d.dy);
  for (double& e : under) e /= 4;
  for (double& e : over) e *= 4;
  const PowerLawFit fu = fit_power_law(d.x, d.y, under);
  const PowerLawFit fo = fit_power_law(d.x, d.y, over);
  const double formula = std::sqrt(slope_variance(d.x, d.y, d.dy));
  EXPECT_NEAR(fu.power - honest.power, 0.0, 1e-12);
  EXPECT_NEAR(fu.chi2_per_dof / (16 * honest.chi2_per_dof), 1.0, 1e-12);
  EXPECT_GT(fu.chi2_per_dof, 10.0);  // 16 (1 +- 4 sqrt(2/198)): in [10, 22]
  EXPECT_LT(fu.chi2_per_dof, 22.0);
  EXPECT_NEAR(fu.power_error / (formula * std::sqrt(honest.chi2_per_dof)), 1.0, 1e-12);
  EXPECT_GT(fu.power_error, 3.0 * formula / 4);  // well above the understated formula error
  EXPECT_LT(std::abs(fu.power - 1.5), 3 * fu.power_error);
  EXPECT_LT(fo.chi2_per_dof, 1.0);
  EXPECT_NEAR(fo.power_error / (4 * formula), 1.0, 1e-12);
}

TEST(PowerLawFit, ThrowsOnBadInput) {
  const std::vector<double> x{1, 2, 4}, y{1, 0.5, 0.25}, e{0.1, 0.1, 0.1};
  EXPECT_NO_THROW(fit_power_law(x, y, e));
  EXPECT_THROW(fit_power_law({1, 2}, y, e), std::invalid_argument);
  EXPECT_THROW(fit_power_law(x, {1, 0.5}, e), std::invalid_argument);
  EXPECT_THROW(fit_power_law(x, y, {0.1, 0.1}), std::invalid_argument);
  EXPECT_THROW(fit_power_law({}, {}, {}), std::invalid_argument);
  EXPECT_THROW(fit_power_law({2}, {1}, {0.1}), std::invalid_argument);
  for (const double bad : {0.0, -1.0, kNaN, kInf}) {
    EXPECT_THROW(fit_power_law({1, bad, 4}, y, e), std::invalid_argument) << "x = " << bad;
    EXPECT_THROW(fit_power_law(x, {1, bad, 0.25}, e), std::invalid_argument) << "y = " << bad;
    EXPECT_THROW(fit_power_law(x, y, {0.1, bad, 0.1}), std::invalid_argument) << "dy = " << bad;
  }
}

TEST(PowerLawFit, ThrowsWithoutTwoDistinctX) {
  // All points at one x determine no slope, whatever that x is (the header: "two distinct x").
  for (const double x0 : {1.0, 2.0, 3.7, 0.1, 1e5}) {
    EXPECT_THROW(fit_power_law({x0, x0, x0}, {1, 2, 3}, {0.1, 0.1, 0.1}), std::invalid_argument)
        << "x = " << x0;
    EXPECT_THROW(fit_power_law({x0, x0}, {1.3, 0.9}, {0.2, 0.1}), std::invalid_argument)
        << "x = " << x0;
  }
}

// ---------------------------------------------------------------------------------------------
// bin_lagrangian_state

LagrangianState uniform_state(int cells, double v) {
  LagrangianState s;
  for (int j = 0; j < cells; ++j) {
    s.node_x.push_back(-0.5 + double(j) / cells);
    s.node_xi.push_back(s.node_x.back());
    s.node_v.push_back(v);
    s.cell_mass.push_back(1.0 / cells);
    s.cell_T.push_back(1.0);
  }
  return s;
}

TEST(BinnedFields, UniformStateGivesUniformFields) {
  // n = 1, T = 1 and v = 0 (or a uniform drift) in every bin, for bins that divide the cells
  // (1, 12, 60), that do not (7, 97), and bins finer than the cells (240). A uniform drift has no
  // sub-bin flow, so T stays 1. Tolerance 1e-12: the rounding of the node differences (~1e-16)
  // relative to the cell width 1/60.
  const int cells = 60;
  for (const double v : {0.0, 0.3}) {
    const LagrangianState s = uniform_state(cells, v);
    for (const int bins : {1, 7, 12, 60, 97, 240}) {
      const FieldSnapshot f = bin_lagrangian_state(s, bins);
      ASSERT_EQ(f.n.size(), std::size_t(bins));
      ASSERT_EQ(f.x.size(), std::size_t(bins));
      ASSERT_EQ(f.v_x.size(), std::size_t(bins));
      ASSERT_EQ(f.v_y.size(), std::size_t(bins));
      ASSERT_EQ(f.T.size(), std::size_t(bins));
      for (int b = 0; b < bins; ++b) {
        EXPECT_NEAR(f.x[b], -0.5 + (b + 0.5) / bins, 1e-15);
        EXPECT_NEAR(f.n[b], 1.0, 1e-12) << "bins " << bins << " b " << b;
        EXPECT_NEAR(f.v_x[b], v, 1e-12) << "bins " << bins << " b " << b;
        EXPECT_EQ(f.v_y[b], 0.0);
        EXPECT_NEAR(f.T[b], 1.0, 1e-12) << "bins " << bins << " b " << b;
      }
    }
  }
}

TEST(BinnedFields, ThrowsOnNoBinsOrNoCells) {
  EXPECT_THROW(bin_lagrangian_state(uniform_state(8, 0.0), 0), std::invalid_argument);
  EXPECT_THROW(bin_lagrangian_state(uniform_state(8, 0.0), -3), std::invalid_argument);
  EXPECT_THROW(bin_lagrangian_state(LagrangianState{}, 10), std::invalid_argument);
}

// A random non-uniform periodic mesh: nodes jittered by up to 40 % of a cell and the whole mesh
// shifted (unwrapped positions: node_x[0] may lie below -1/2 or the last cells beyond +1/2),
// random masses, temperatures and node velocities (and transverse velocities if asked).
LagrangianState random_mesh(int cells, double shift, bool transverse, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> jitter(-0.4, 0.4), mass(0.2, 1.8), temperature(0.5, 2.0),
      velocity(-1.0, 1.0);
  LagrangianState s;
  for (int j = 0; j < cells; ++j) {
    s.node_x.push_back(-0.5 + (j + jitter(rng)) / cells + shift);
    s.node_xi.push_back(s.node_x.back());
    s.node_v.push_back(velocity(rng));
    if (transverse) s.node_vy.push_back(velocity(rng));
    s.cell_mass.push_back(mass(rng) / cells);
    s.cell_T.push_back(temperature(rng));
  }
  return s;
}

struct Totals {
  double mass = 0, px = 0, py = 0, energy = 0;
};

// Exact integrals over the cells: n constant in a cell, v linear between its nodes, so
// int n v = m (va + vb)/2 and int n v^2 = m (va^2 + va vb + vb^2)/3.
Totals cell_totals(const LagrangianState& s) {
  Totals t;
  const int N = s.cells();
  for (int i = 0; i < N; ++i) {
    const int j = (i + 1) % N;
    const double m = s.cell_mass[i], va = s.node_v[i], vb = s.node_v[j];
    const double wa = s.has_transverse() ? s.node_vy[i] : 0.0;
    const double wb = s.has_transverse() ? s.node_vy[j] : 0.0;
    t.mass += m;
    t.px += m * (va + vb) / 2;
    t.py += m * (wa + wb) / 2;
    t.energy += m * (s.cell_T[i] + (va * va + va * vb + vb * vb + wa * wa + wa * wb + wb * wb) / 6);
  }
  return t;
}

// Bin totals: n_b / bins is the bin's mass, n_b v_b / bins its momentum, and
// n_b (T_b + |v_b|^2 / 2) / bins its thermal plus flow energy.
Totals bin_totals(const FieldSnapshot& f) {
  Totals t;
  const double dx = 1.0 / f.n.size();
  for (std::size_t b = 0; b < f.n.size(); ++b) {
    t.mass += f.n[b] * dx;
    t.px += f.n[b] * f.v_x[b] * dx;
    t.py += f.n[b] * f.v_y[b] * dx;
    t.energy += f.n[b] * (f.T[b] + (f.v_x[b] * f.v_x[b] + f.v_y[b] * f.v_y[b]) / 2) * dx;
  }
  return t;
}

TEST(BinnedFields, ConservesMassMomentumAndEnergyOnARandomPeriodicMesh) {
  // Binning is a partition of the period: the bins' mass, momentum and total (thermal + flow)
  // energy must equal the integrals over the cells exactly, whatever the bins, for a mesh that
  // straddles the periodic boundary on either side. Totals are O(1): rounding only, 1e-12.
  std::mt19937_64 rng(31415);
  for (const bool transverse : {false, true}) {
    for (const double shift : {-0.37, -0.013, 0.0, 0.23}) {
      for (const int cells : {5, 40, 301}) {
        const LagrangianState s = random_mesh(cells, shift, transverse, rng);
        if (shift < -0.1) {
          ASSERT_LT(s.node_x[0], -0.5);  // cells left of -1/2: positions are unwrapped
        }
        const Totals exact = cell_totals(s);
        for (const int bins : {1, 3, 17, 64, 1000}) {
          const FieldSnapshot f = bin_lagrangian_state(s, bins);
          const Totals got = bin_totals(f);
          const std::string where = "cells " + std::to_string(cells) + " bins " +
                                    std::to_string(bins) + " shift " + std::to_string(shift) +
                                    (transverse ? " with v_y" : "");
          EXPECT_NEAR(got.mass, exact.mass, 1e-12) << where;
          EXPECT_NEAR(got.px, exact.px, 1e-12) << where;
          EXPECT_NEAR(got.py, exact.py, 1e-12) << where;
          EXPECT_NEAR(got.energy, exact.energy, 1e-12) << where;
          for (int b = 0; b < bins; ++b) {
            EXPECT_GT(f.n[b], 0.0) << where << " b " << b;
            EXPECT_GT(f.T[b], 0.0) << where << " b " << b;
          }
          if (!transverse) {
            for (const double vy : f.v_y) EXPECT_EQ(vy, 0.0);
          }
        }
      }
    }
  }
}

TEST(BinnedFields, SubBinFlowIsHeatWithTheTwoDimensionalFactorOneHalf) {
  // Two equal cells [-1/2, 0) and [0, 1/2) with node velocities v0 - u and v0 + u: v rises
  // linearly over one cell and falls over the other. One bin over the pair (or one bin per
  // cell) sees mean flow v0 and, as heat, the mean of (v - v0)^2 / 2 over a linear profile from
  // -u to +u: u^2/6 (for a 2D gas, thermal energy T per particle). So T_b = T + u^2/6; a
  // transverse profile -w..+w adds w^2/6. Rounding only: 1e-14.
  const double T = 0.7, v0 = 0.1, u = 0.2, w0 = -0.05, w = 0.3;
  LagrangianState s;
  s.node_x = {-0.5, 0.0};
  s.node_xi = s.node_x;
  s.node_v = {v0 - u, v0 + u};
  s.cell_mass = {0.5, 0.5};
  s.cell_T = {T, T};
  for (const int bins : {1, 2}) {
    const FieldSnapshot f = bin_lagrangian_state(s, bins);
    for (int b = 0; b < bins; ++b) {
      EXPECT_NEAR(f.n[b], 1.0, 1e-14);
      EXPECT_NEAR(f.v_x[b], v0, 1e-14);
      EXPECT_NEAR(f.T[b], T + u * u / 6, 1e-14) << "bins " << bins;
    }
  }
  s.node_vy = {w0 - w, w0 + w};
  for (const int bins : {1, 2}) {
    const FieldSnapshot f = bin_lagrangian_state(s, bins);
    for (int b = 0; b < bins; ++b) {
      EXPECT_NEAR(f.v_y[b], w0, 1e-14);
      EXPECT_NEAR(f.T[b], T + (u * u + w * w) / 6, 1e-14) << "bins " << bins;
    }
  }
  // Four bins over the same pair: each bin holds half a cell, where v spans u (not 2u), so the
  // heat is (u/2)^2/6 and the bin velocities are v0 -+ u/2 on the rising cell.
  s.node_vy.clear();
  const FieldSnapshot f = bin_lagrangian_state(s, 4);
  EXPECT_NEAR(f.v_x[0], v0 - u / 2, 1e-14);
  EXPECT_NEAR(f.v_x[1], v0 + u / 2, 1e-14);
  EXPECT_NEAR(f.v_x[2], v0 + u / 2, 1e-14);
  EXPECT_NEAR(f.v_x[3], v0 - u / 2, 1e-14);
  for (int b = 0; b < 4; ++b) EXPECT_NEAR(f.T[b], T + u * u / 24, 1e-14);
}

TEST(BinnedFields, ShiftByOneBinRollsTheFields) {
  // Translating every node by one bin width moves the content of bin b into bin b + 1
  // (periodically); by a whole period changes nothing. Bin edges shift by rounding only: 1e-12.
  std::mt19937_64 rng(2718);
  const int bins = 25;
  for (const double shift : {-0.3, 0.0, 0.2}) {
    const LagrangianState s = random_mesh(83, shift, true, rng);
    const FieldSnapshot f = bin_lagrangian_state(s, bins);
    for (const int by : {1, -1, bins}) {
      LagrangianState moved = s;
      for (double& x : moved.node_x) x += double(by) / bins;
      const FieldSnapshot g = bin_lagrangian_state(moved, bins);
      for (int b = 0; b < bins; ++b) {
        const int to = ((b + by) % bins + bins) % bins;
        EXPECT_NEAR(g.x[b], f.x[b], 1e-15);
        EXPECT_NEAR(g.n[to], f.n[b], 1e-12) << "by " << by << " b " << b;
        EXPECT_NEAR(g.v_x[to], f.v_x[b], 1e-12) << "by " << by << " b " << b;
        EXPECT_NEAR(g.v_y[to], f.v_y[b], 1e-12) << "by " << by << " b " << b;
        EXPECT_NEAR(g.T[to], f.T[b], 1e-12) << "by " << by << " b " << b;
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// flow_by_inertia_state + bin_lagrangian_state

// The label xi of the element at x when x = xi + t v0(xi), v0 = a sin(2 pi xi), monotonic for
// t < tau: bisection on [x - t|a|, x + t|a|], then Newton to rounding.
double label_at(double x, double a, double t) {
  const auto g = [=](double xi) { return xi + t * a * std::sin(2 * kPi * xi) - x; };
  double lo = x - t * std::abs(a) - 1e-12, hi = x + t * std::abs(a) + 1e-12;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) < 0 ? lo : hi) = mid;
  }
  double xi = 0.5 * (lo + hi);
  for (int i = 0; i < 3; ++i) xi -= g(xi) / (1 + t * a * 2 * kPi * std::cos(2 * kPi * xi));
  return xi;
}

TEST(BinnedFlowByInertia, BinnedDensityMatchesTheExactBinAverage) {
  // Single mode v0 = a sin(2 pi xi), n0 = 1, a = -0.05, at t = tau/2 (tau = 1/(2 pi |a|)): the
  // density at x = 0 has doubled, n = 1/(1 + t v0'(0)) = 1/(1 - t/tau) = 2. The reference bin
  // average is computed two independent ways: the mass between the labels of the bin edges
  // (n0 = 1, so M = xi(x_hi) - xi(x_lo)), and Gauss-Legendre quadrature of
  // n(x) = 1/(1 + t v0'(xi(x))) over the bin; they agree to rounding (1e-12).
  // The 4000-label state (label spacing d = 2.5e-4) carries n piecewise constant and v linear
  // in x per cell, so a bin's mass is wrong only through the partial cells at its two edges, by
  // at most |xi''| w^2 / 8 per edge (xi(x) the exact label, w = d x' the cell width). With
  // x' = 1 - (t/tau) cos(2 pi xi), x'' = pi sin(2 pi xi): |xi''| w^2 / 8 = pi |sin| d^2 / (8 x').
  // At the centre bin's edges (xi ~ 0.047) that is 1.4e-8 per edge, < 3e-7 of its mass 0.094:
  // tolerance 1e-6 relative. The maximum over xi is pi 1.155 d^2 / 8 = 2.8e-8 per edge, < 1.8e-6
  // of the lightest bin's mass (0.667/21): tolerance 2e-6 for every other bin.
  const double a = -0.05, tau = 1.0 / (2 * kPi * std::abs(a)), t = 0.5 * tau;
  InitialFields init;
  init.n = [](double) { return 1.0; };
  init.v = [a](double xi) { return a * std::sin(2 * kPi * xi); };
  init.vy = [](double) { return 0.0; };
  init.T = [](double) { return 1.0; };
  init.dv = [a](double xi) { return 2 * kPi * a * std::cos(2 * kPi * xi); };
  const int labels = 4000, bins = 21, centre = bins / 2;
  const LagrangianState s = flow_by_inertia_state(init, t, labels);
  ASSERT_EQ(s.cells(), labels);
  const FieldSnapshot f = bin_lagrangian_state(s, bins);
  ASSERT_EQ(f.n.size(), std::size_t(bins));
  EXPECT_NEAR(f.x[centre], 0.0, 1e-15);

  const double dx = 1.0 / bins;
  // 10-point Gauss-Legendre nodes/weights on [-1, 1] (positive half).
  const double gx[5] = {0.1488743389816312, 0.4333953941292472, 0.6794095682990244,
                        0.8650633666889845, 0.9739065285171717};
  const double gw[5] = {0.2955242247147529, 0.2692667193099963, 0.2190863625159820,
                        0.1494513491505806, 0.0666713443086881};
  const auto n_exact = [&](double x) {
    return 1.0 / (1.0 + t * a * 2 * kPi * std::cos(2 * kPi * label_at(x, a, t)));
  };
  double total = 0.0;
  for (int b = 0; b < bins; ++b) {
    const double lo = -0.5 + b * dx, hi = lo + dx;
    const double xi_lo = label_at(lo, a, t), xi_hi = label_at(hi, a, t);
    const double n_mass = (xi_hi - xi_lo) / dx;
    double n_quad = 0.0;
    const int pieces = 40;
    for (int k = 0; k < pieces; ++k) {
      const double c = lo + (k + 0.5) * dx / pieces, h = 0.5 * dx / pieces;
      for (int q = 0; q < 5; ++q) {
        n_quad += gw[q] * h * (n_exact(c - h * gx[q]) + n_exact(c + h * gx[q]));
      }
    }
    n_quad /= dx;
    EXPECT_NEAR(n_quad / n_mass, 1.0, 1e-12) << "b " << b;
    EXPECT_NEAR(f.n[b] / n_mass, 1.0, b == centre ? 1e-6 : 2e-6) << "b " << b;
    // Mean velocity: momentum int v0 dxi over the labels in the bin over their mass. The
    // piecewise-linear v integrates v0 by the trapezoid rule on the labels: error
    // d^2 |v0''| / 12 <= 6.25e-8 * 1.97 / 12 = 1e-8 = 2e-7 |a|; tolerance 1e-6 |a|.
    const double v_exact =
        a / (2 * kPi) * (std::cos(2 * kPi * xi_lo) - std::cos(2 * kPi * xi_hi)) / (xi_hi - xi_lo);
    EXPECT_NEAR(f.v_x[b], v_exact, 1e-6 * std::abs(a)) << "b " << b;
    // Temperature: T0 = 1 plus the sub-bin flow seen as heat, (1/2)(<v0^2> - <v0>^2) over the
    // labels in the bin, with int sin^2(2 pi xi) dxi = xi/2 - sin(4 pi xi)/(8 pi). The heat is
    // 1.2e-7 .. 3.6e-5 here; the trapezoid error of <v^2> is d^2 |(v0^2)''| / 12 <= 1e-9:
    // tolerance 1e-9 absolute (dropping the factor 1/2 would be off by >= 1.2e-7 in every bin).
    const auto sin2 = [](double xi) { return xi / 2 - std::sin(4 * kPi * xi) / (8 * kPi); };
    const double heat =
        0.5 * (a * a * (sin2(xi_hi) - sin2(xi_lo)) / (xi_hi - xi_lo) - v_exact * v_exact);
    EXPECT_NEAR(f.T[b] - 1.0, heat, 1e-9) << "b " << b;
    total += f.n[b] * dx;
  }
  // The binned density is the bin average, not the point value 2: they differ by ~0.03 here.
  EXPECT_GT(std::abs(f.n[centre] - 2.0), 1e-2);
  EXPECT_LT(f.n[centre], 2.0);
  EXPECT_NEAR(f.v_x[centre], 0.0, 1e-12);  // odd v about x = 0
  EXPECT_NEAR(total, 1.0, 1e-12);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Bin interpolation and Fourier modes of binned fields.
// ---------------------------------------------------------------------------------------------
namespace {

TEST(BinnedInterpolant, ThroughTheCentresLinearBetweenPeriodicAcrossTheEnds) {
  const std::vector<double> v = {1.0, 3.0, 2.0, -1.0};  // centres -3/8, -1/8, 1/8, 3/8
  const auto f = granvv::compare::bin_interpolant(v);
  for (int b = 0; b < 4; ++b) EXPECT_NEAR(f(-0.5 + (b + 0.5) / 4), v[b], 1e-15);
  EXPECT_NEAR(f(-0.25), 2.0, 1e-15);        // midway between 1 and 3
  EXPECT_NEAR(f(0.5), 0.0, 1e-15);          // midway between -1 (last) and 1 (first)
  EXPECT_NEAR(f(-0.5), f(0.5), 1e-15);      // periodic
  EXPECT_NEAR(f(0.125 + 3.0), 2.0, 1e-12);  // any period
  EXPECT_THROW(granvv::compare::bin_interpolant({}), std::invalid_argument);
}

TEST(DensityModes, CosineOnBinsHasCoefficientOneHalfAndNoOtherModes) {
  // Discrete orthogonality on B equal bins: exact for |k|, |m| < B/2 (round-off only).
  const int B = 40;
  for (int m = 1; m < B / 2; m += 3) {
    std::vector<double> f;
    for (int b = 0; b < B; ++b) f.push_back(std::cos(2 * M_PI * m * (-0.5 + (b + 0.5) / B)));
    for (int k = 1; k < B / 2; ++k) {
      const auto c = granvv::compare::bin_fourier_coefficient(f, k);
      EXPECT_NEAR(std::abs(c), k == m ? 0.5 : 0.0, 1e-13) << "m = " << m << ", k = " << k;
    }
  }
}

TEST(DensityModes, HcsPerturbationTakesDensityAndTemperatureRelativeToTheirMeans) {
  // n = n0 (1 + e cos 2 pi x), v = u sin 2 pi x, T = T_H (1 - e cos 2 pi x) with T_H the
  // mass-weighted mean: nu_1 = e/2, w_1 = u/(2i sqrt(T_H)), theta_1 = -e/2 up to the O(e^2)
  // shift of the mass-weighted mean temperature.
  const int B = 64;
  const double n0 = 0.06, e = 1e-3, u = 0.2, TH = 0.25;
  std::vector<double> n, v, T;
  for (int b = 0; b < B; ++b) {
    const double x = -0.5 + (b + 0.5) / B;
    n.push_back(n0 * (1 + e * std::cos(2 * M_PI * x)));
    v.push_back(u * std::sin(2 * M_PI * x));
    T.push_back(TH * (1 - e * std::cos(2 * M_PI * x)));
  }
  const Eigen::Vector3cd p = granvv::compare::hcs_perturbation(n, v, T, 1);
  EXPECT_NEAR(p[0].real(), e / 2, 1e-12);
  EXPECT_NEAR(p[1].imag(), -u / (2 * std::sqrt(TH)), 1e-3 * u);  // T mean shifted by e^2/2
  EXPECT_NEAR(p[2].real(), -e / 2, 1e-6);
  EXPECT_THROW(granvv::compare::hcs_perturbation(n, v, {1.0}, 1), std::invalid_argument);
}

}  // namespace
