// Two transport factors fitted jointly to several signals of one ensemble (docs/physics.md §14,
// compare/transport_pair_fit.hpp), against synthetic ensembles made from known factors: a
// damped oscillation whose rate is F_a + F_b (a sound wave's v, damped by kappa + mu n/T) and a
// second signal whose rate is F_a - F_b/2 (the response to mu of another sign), so the two
// factors are separable only jointly.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "compare/transport_pair_fit.hpp"

namespace {

using granvv::compare::FactorPairGrid;
using granvv::compare::PairSignal;

constexpr int kSnapshots = 16;
constexpr double kOmega = 3.0;

double time_of(int s) {
  return 0.15 * s;
}

// The two signals' exact amplitudes at factors (a, b), snapshot s.
double first(double a, double b, int s) {
  const double t = time_of(s);
  return 0.15 * std::exp(-(a + b) * t) * std::cos(kOmega * t);
}
double second(double a, double b, int s) {
  const double t = time_of(s);
  return 0.1 * std::exp(-(a - 0.5 * b) * t) * std::sin(kOmega * t);
}

const FactorPairGrid kGrid = {{0.5, 0.75, 1.0, 1.25, 1.5}, {0.0, 0.5, 1.0, 1.5, 2.0}};

PairSignal signal_of(double (*f)(double, double, int)) {
  PairSignal g;
  for (double a : kGrid.factors_a) {
    g.hydro.emplace_back();
    for (double b : kGrid.factors_b) {
      std::vector<double> h;
      for (int s = 0; s < kSnapshots; ++s) h.push_back(f(a, b, s));
      g.hydro.back().push_back(h);
    }
  }
  return g;
}

// Members about the truth: each member's amplitude off by a persistent random relative amount
// (correlated across snapshots) plus independent noise at every snapshot.
std::vector<PairSignal> noisy_ensemble(double a, double b, int members, double noise,
                                       std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<PairSignal> signals = {signal_of(first), signal_of(second)};
  for (int m = 0; m < members; ++m) {
    const double scale = 1.0 + 0.05 * normal(rng);
    std::vector<double> one, two;
    for (int s = 0; s < kSnapshots; ++s) {
      one.push_back(scale * first(a, b, s) + noise * normal(rng));
      two.push_back(scale * second(a, b, s) + noise * normal(rng));
    }
    signals[0].members.push_back(one);
    signals[1].members.push_back(two);
  }
  return signals;
}

TEST(TransportPairFit, InterpolatesTheHydroBetweenTheGridPoints) {
  // Tolerance: the 5-point polynomial's error for exp(-F t) at t <= 2.25 over a range of 1 in F
  // is below (F range * t)^5 / 5! / 2^4 ~ 3e-3 of the amplitude.
  const PairSignal g = signal_of(first);
  const auto p = granvv::compare::predicted_pair_amplitudes(kGrid, g, 2.0, 1.1, 0.7);
  for (int s = 0; s < kSnapshots; ++s) {
    EXPECT_NEAR(p[s], 2.0 * first(1.1, 0.7, s), 3e-3 * 0.3) << "snapshot " << s;
  }
  // At a grid point it is the table's value.
  EXPECT_DOUBLE_EQ(granvv::compare::predicted_pair_amplitudes(kGrid, g, 1.0, 1.25, 1.5)[7],
                   first(1.25, 1.5, 7));
}

TEST(TransportPairFit, NoiselessMembersGiveTheirFactors) {
  // Two members +-d about the exact curves: their mean is the truth; tolerance the interpolation
  // error above carried into the factors (1e-3).
  std::vector<PairSignal> signals = {signal_of(first), signal_of(second)};
  for (double d : {0.002, -0.002}) {
    std::vector<double> one, two;
    for (int s = 0; s < kSnapshots; ++s) {
      one.push_back(first(1.1, 0.7, s) + d);
      two.push_back(second(1.1, 0.7, s) - d);
    }
    signals[0].members.push_back(one);
    signals[1].members.push_back(two);
  }
  const auto fit = granvv::compare::fit_transport_factor_pair(kGrid, signals);
  EXPECT_NEAR(fit.factor_a, 1.1, 1e-3);
  EXPECT_NEAR(fit.factor_b, 0.7, 1e-3);
  EXPECT_NEAR(fit.scale, 1.0, 1e-3);
  EXPECT_EQ(fit.degrees_of_freedom, 2 * kSnapshots - 3);
  EXPECT_FALSE(fit.at_grid_edge);
  ASSERT_EQ(fit.fitted.size(), 2u);
  EXPECT_NEAR(fit.fitted[1][5], second(1.1, 0.7, 5), 1e-4);
}

TEST(TransportPairFit, ExtrapolatesBelowTheGridWhereAsked) {
  // Truth F_b = -0.3, below the grid's first factor 0: found with b_below = 0.5 (the polynomial
  // extrapolated; tolerance its error there, 1e-2), and clamped to 0 without it.
  std::vector<PairSignal> signals = {signal_of(first), signal_of(second)};
  for (double d : {0.002, -0.002}) {
    std::vector<double> one, two;
    for (int s = 0; s < kSnapshots; ++s) {
      one.push_back(first(1.1, -0.3, s) + d);
      two.push_back(second(1.1, -0.3, s) - d);
    }
    signals[0].members.push_back(one);
    signals[1].members.push_back(two);
  }
  FactorPairGrid below = kGrid;
  below.b_below = 0.5;
  const auto fit = granvv::compare::fit_transport_factor_pair(below, signals);
  EXPECT_NEAR(fit.factor_b, -0.3, 1e-2);
  EXPECT_NEAR(fit.factor_a, 1.1, 1e-2);
  EXPECT_FALSE(fit.at_grid_edge);
  const auto clamped = granvv::compare::fit_transport_factor_pair(kGrid, signals);
  EXPECT_EQ(clamped.factor_b, 0.0);
  EXPECT_TRUE(clamped.at_grid_edge);
}

TEST(TransportPairFit, NoisyEnsemblesRecoverBothFactorsWithHonestErrorsAndCorrelation) {
  // 30 ensembles of 32 members from (F_a, F_b) = (0.9, 0.6): each fit within 4 of its standard
  // errors of the truth on each factor, and the stated errors and correlation honest: the mean
  // stated error within 30 % of the scatter over the ensembles (the scatter of 30 values is
  // itself uncertain by about 13 %), the mean stated correlation within 0.25 of the correlation
  // of the fitted pairs (uncertain by about (1 - rho^2)/sqrt(30) ~ 0.15).
  const double a = 0.9, b = 0.6;
  const int ensembles = 30;
  std::mt19937 rng(29);
  std::vector<double> fa, fb;
  double stated_a = 0.0, stated_b = 0.0, stated_rho = 0.0;
  for (int e = 0; e < ensembles; ++e) {
    const auto fit =
        granvv::compare::fit_transport_factor_pair(kGrid, noisy_ensemble(a, b, 32, 0.004, rng));
    EXPECT_LT(std::abs(fit.factor_a - a), 4.0 * fit.error_a);
    EXPECT_LT(std::abs(fit.factor_b - b), 4.0 * fit.error_b);
    fa.push_back(fit.factor_a), fb.push_back(fit.factor_b);
    stated_a += fit.error_a / ensembles, stated_b += fit.error_b / ensembles;
    stated_rho += fit.correlation / ensembles;
  }
  double ma = 0.0, mb = 0.0;
  for (int e = 0; e < ensembles; ++e) ma += fa[e] / ensembles, mb += fb[e] / ensembles;
  double va = 0.0, vb = 0.0, cab = 0.0;
  for (int e = 0; e < ensembles; ++e) {
    va += (fa[e] - ma) * (fa[e] - ma) / (ensembles - 1);
    vb += (fb[e] - mb) * (fb[e] - mb) / (ensembles - 1);
    cab += (fa[e] - ma) * (fb[e] - mb) / (ensembles - 1);
  }
  EXPECT_NEAR(stated_a / std::sqrt(va), 1.0, 0.3) << stated_a << " vs " << std::sqrt(va);
  EXPECT_NEAR(stated_b / std::sqrt(vb), 1.0, 0.3) << stated_b << " vs " << std::sqrt(vb);
  EXPECT_NEAR(stated_rho, cab / std::sqrt(va * vb), 0.25);
  EXPECT_NEAR(ma, a, 3.0 * std::sqrt(va / ensembles));
  EXPECT_NEAR(mb, b, 3.0 * std::sqrt(vb / ensembles));
}

TEST(TransportPairFit, RefusesSignalsNotOfTheGridsShape) {
  std::mt19937 rng(1);
  auto signals = noisy_ensemble(1.0, 1.0, 4, 0.01, rng);
  signals[1].members.pop_back();  // member counts differ
  EXPECT_THROW(granvv::compare::fit_transport_factor_pair(kGrid, signals), std::invalid_argument);
  signals = noisy_ensemble(1.0, 1.0, 4, 0.01, rng);
  signals[0].hydro.pop_back();  // one factor a short
  EXPECT_THROW(granvv::compare::fit_transport_factor_pair(kGrid, signals), std::invalid_argument);
  FactorPairGrid flat = kGrid;
  flat.factors_b = {1.0, 1.0, 1.0, 1.0, 1.0};
  EXPECT_THROW(
      granvv::compare::fit_transport_factor_pair(flat, noisy_ensemble(1.0, 1.0, 4, 0.01, rng)),
      std::invalid_argument);
  EXPECT_THROW(granvv::compare::fit_transport_factor_pair(kGrid, {}), std::invalid_argument);
}

}  // namespace
