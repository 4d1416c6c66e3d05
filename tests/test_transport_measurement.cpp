// Measuring a transport coefficient from a particle ensemble (docs/physics.md §14): the mode
// projection, the jackknife over members, the fit of the hydro's factor and the normalisation by
// the elastic dilute coefficients, each against answers worked by hand or synthetic data made
// from a known factor.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "compare/jackknife.hpp"
#include "compare/mode_amplitudes.hpp"
#include "compare/transport_coefficients.hpp"
#include "compare/transport_factor_fit.hpp"
#include "fields/constants.hpp"
#include "hydro/closure.hpp"
#include "hydro/dilute_closure.hpp"
#include "hydro/enskog_closure.hpp"
#include "hydro/enskog_factors.hpp"
#include "md_bridge/particle_scene.hpp"

namespace {

using namespace granvv;
using granvv::compare::FactorGrid;
using granvv::compare::ModePhase;

constexpr int kBins = 32;

double bin_centre(int b) {
  return -0.5 + (b + 0.5) / kBins;
}

// A member of `snapshots` snapshots whose v_y and T are the given profiles.
fields::FieldSeries member(int snapshots, double (*v_y)(double), double (*T)(double)) {
  fields::FieldSeries f = fields::FieldSeries::on_bins(-0.5, 1.0, kBins);
  for (int s = 0; s < snapshots; ++s) {
    fields::FieldSnapshot snap;
    snap.t = s;
    for (int b = 0; b < kBins; ++b) {
      const double x = bin_centre(b);
      snap.x.push_back(x);
      snap.n.push_back(1.0);
      snap.v_x.push_back(0.0);
      snap.v_y.push_back(v_y(x));
      snap.T.push_back(T(x));
    }
    f.snapshots.push_back(snap);
  }
  return f;
}

TEST(ModeAmplitudes, SineAndCosinePartsOfTheFirstModeAtTheBinCentres) {
  // v_y = 0.1 sin 2 pi x + 0.05 cos 2 pi x + 0.2 sin 4 pi x + 0.3: the sine part is 0.1 and the
  // cosine part 0.05 exactly on 32 bins (discrete orthogonality); tolerance: rounding of 32
  // terms.
  auto v = [](double x) {
    return 0.1 * std::sin(kTwoPi * x) + 0.05 * std::cos(kTwoPi * x) +
           0.2 * std::sin(2 * kTwoPi * x) + 0.3;
  };
  std::vector<double> values;
  for (int b = 0; b < kBins; ++b) values.push_back(v(bin_centre(b)));
  EXPECT_NEAR(compare::mode_amplitude(values, ModePhase::sine), 0.1, 1e-15);
  EXPECT_NEAR(compare::mode_amplitude(values, ModePhase::cosine), 0.05, 1e-15);
  // v_y is read as it is; T relative to its box mean: T = 2 (1 + 0.3 cos 2 pi x) has 0.3.
  EXPECT_NEAR(compare::field_mode_amplitude(values, "v_y", ModePhase::sine), 0.1, 1e-15);
  std::vector<double> T;
  for (int b = 0; b < kBins; ++b) T.push_back(2.0 * (1.0 + 0.3 * std::cos(kTwoPi * bin_centre(b))));
  EXPECT_NEAR(compare::field_mode_amplitude(T, "T", ModePhase::cosine), 0.3, 1e-15);
  EXPECT_EQ(compare::mode_phase("sin"), ModePhase::sine);
  EXPECT_EQ(compare::mode_phase("cos"), ModePhase::cosine);
  EXPECT_THROW(compare::mode_phase("tan"), std::invalid_argument);
}

TEST(ModeAmplitudes, EveryMemberAtTheSnapshotsAllMembersHave) {
  const auto shear = [](double x) { return 0.1 * std::sin(kTwoPi * x); };
  const auto other = [](double x) { return -0.2 * std::sin(kTwoPi * x); };
  const auto hot = [](double x) { return 1.0 + 0.3 * std::cos(kTwoPi * x); };
  const std::vector<fields::FieldSeries> members = {member(4, +shear, +hot),
                                                    member(3, +other, +hot)};
  const auto a = compare::member_mode_amplitudes(members, "v_y", ModePhase::sine);
  ASSERT_EQ(a.size(), 2u);
  ASSERT_EQ(a[0].size(), 3u);  // the shorter member's three snapshots
  EXPECT_NEAR(a[0][2], 0.1, 1e-15);
  EXPECT_NEAR(a[1][0], -0.2, 1e-15);
  EXPECT_THROW(compare::member_mode_amplitudes({}, "v_y", ModePhase::sine), std::invalid_argument);
  EXPECT_THROW(compare::member_mode_amplitudes(members, "w", ModePhase::sine),
               std::invalid_argument);
}

TEST(Jackknife, HandWorkedThreeMembers) {
  // Members 1, 2, 4: leave-one-out means 3, 2.5, 1.5. For the mean, se_J = s / sqrt(3) =
  // sqrt(7/9). For f = mean^2: f_(i) = 9, 6.25, 2.25, f_(.) = 35/6, sum of squares 3318/144,
  // se_J = sqrt(2/3 * 3318/144). Tolerances: a few roundings.
  const std::vector<std::vector<double>> members = {{1.0}, {2.0}, {4.0}};
  const auto samples = compare::leave_one_out_means(members);
  ASSERT_EQ(samples.size(), 3u);
  EXPECT_DOUBLE_EQ(samples[0][0], 3.0);
  EXPECT_DOUBLE_EQ(samples[1][0], 2.5);
  EXPECT_DOUBLE_EQ(samples[2][0], 1.5);
  EXPECT_NEAR(compare::jackknife_errors(samples)[0], std::sqrt(7.0 / 9.0), 1e-15);
  std::vector<double> squared;
  for (const auto& s : samples) squared.push_back(s[0] * s[0]);
  EXPECT_NEAR(compare::jackknife_error(squared), std::sqrt(2.0 / 3.0 * 3318.0 / 144.0), 1e-14);
  EXPECT_NEAR(compare::member_mean(members)[0], 7.0 / 3.0, 1e-15);
  EXPECT_TRUE(std::isnan(compare::jackknife_error({1.0})));
  EXPECT_THROW(compare::leave_one_out_means({{1.0}}), std::invalid_argument);
  EXPECT_THROW(compare::leave_one_out_means({{1.0}, {1.0, 2.0}}), std::invalid_argument);
}

// The hydro of a decaying mode at factor F: H_s(F) = a exp(-F c t_s), on the grid of factors.
constexpr double kRate = 0.6;
std::vector<double> times() {
  std::vector<double> t;
  for (int s = 0; s <= 12; ++s) t.push_back(0.2 * s);
  return t;
}
FactorGrid exponential_grid() {
  FactorGrid grid;
  grid.factors = {0.5, 0.75, 1.0, 1.25, 1.5};
  for (double F : grid.factors) {
    std::vector<double> h;
    for (double t : times()) h.push_back(0.3 * std::exp(-F * kRate * t));
    grid.amplitudes.push_back(h);
  }
  return grid;
}

TEST(TransportFactorFit, ResponseIsInterpolatedBetweenTheFactors) {
  // ln R is linear in F for an exponential decay, so the polynomial through it is exact.
  const FactorGrid grid = exponential_grid();
  EXPECT_NEAR(compare::response_ratio(grid, 5, 0.9), std::exp(-0.9 * kRate * 1.0), 1e-13);
  EXPECT_NEAR(compare::predicted_amplitudes(grid, 2.0, 1.1)[12], 2.0 * std::exp(-1.1 * kRate * 2.4),
              1e-13);
  FactorGrid bad = grid;
  bad.factors[1] = 0.4;  // not increasing
  EXPECT_THROW(compare::response_ratio(bad, 1, 1.0), std::invalid_argument);
}

TEST(TransportFactorFit, NoiselessMembersGiveTheirFactor) {
  // Two members +-d about a0 exp(-F c t) with F = 0.87: their mean is the curve itself, and the
  // fit returns F to the golden section's precision on a flat minimum (1e-6).
  const double truth = 0.87;
  std::vector<std::vector<double>> members(2);
  for (double t : times()) {
    const double a = 0.29 * std::exp(-truth * kRate * t);
    members[0].push_back(a + 0.01);
    members[1].push_back(a - 0.01);
  }
  const auto fit = compare::fit_transport_factor(exponential_grid(), members);
  EXPECT_NEAR(fit.factor, truth, 1e-6);
  EXPECT_NEAR(fit.chi2, 0.0, 1e-9);
  EXPECT_EQ(fit.degrees_of_freedom, 11);
  EXPECT_FALSE(fit.at_grid_edge);
  EXPECT_NEAR(fit.start, 0.29, 1e-9);
  EXPECT_NEAR(fit.fitted[12], 0.29 * std::exp(-truth * kRate * 2.4), 1e-9);
  // The curve at F = 1 with its own best start: the F = 1 decay.
  EXPECT_NEAR(fit.unit_factor[12] / fit.unit_factor[0], std::exp(-kRate * 2.4), 1e-12);
}

// An ensemble of members about a0 exp(-F c t): each member's start amplitude off by a random
// relative amount that persists (its fluctuation decays with the mode: correlated across
// snapshots), plus independent noise at every snapshot.
std::vector<std::vector<double>> noisy_members(double truth, int count, std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<std::vector<double>> members;
  for (int m = 0; m < count; ++m) {
    const double start = 0.29 * (1.0 + 0.1 * normal(rng));
    std::vector<double> row;
    for (double t : times())
      row.push_back(start * std::exp(-truth * kRate * t) + 0.01 * normal(rng));
    members.push_back(row);
  }
  return members;
}

TEST(TransportFactorFit, NoisyEnsemblesRecoverTheFactorWithinTheirStatedError) {
  // 40 ensembles of 24 members from F = 0.86: each fit within 4 of its standard errors of the
  // truth (a 6e-5 chance per fit for a Gaussian), and the stated error honest: the mean stated
  // error within 25 % of the scatter of the fitted factors over the ensembles (the scatter of 40
  // values is itself uncertain by about 11 %).
  const double truth = 0.86;
  std::mt19937 rng(2026);
  std::vector<double> factors;
  double stated = 0.0;
  for (int e = 0; e < 40; ++e) {
    const auto fit =
        compare::fit_transport_factor(exponential_grid(), noisy_members(truth, 24, rng));
    EXPECT_LT(std::abs(fit.factor - truth), 4.0 * fit.error);
    factors.push_back(fit.factor);
    stated += fit.error / 40.0;
  }
  double mean = 0.0, scatter = 0.0;
  for (double f : factors) mean += f / 40.0;
  for (double f : factors) scatter += (f - mean) * (f - mean) / 39.0;
  scatter = std::sqrt(scatter);
  EXPECT_NEAR(stated / scatter, 1.0, 0.25) << "stated " << stated << ", scatter " << scatter;
  EXPECT_NEAR(mean, truth, 3.0 * scatter / std::sqrt(40.0));
}

TEST(TransportFactorFit, RefusesTooFewMembersOrSnapshots) {
  const FactorGrid grid = exponential_grid();
  EXPECT_THROW(compare::fit_transport_factor(grid, {std::vector<double>(13, 0.1)}),
               std::invalid_argument);
  EXPECT_THROW(compare::fit_transport_factor(
                   grid, std::vector<std::vector<double>>(3, std::vector<double>(12, 0.1))),
               std::invalid_argument);
}

TEST(TransportNormalisation, ElasticDiluteValuesOfHardDisks) {
  // eta0 = sqrt(m T / pi) / (2 sigma); kappa0 = 4 eta0 / m; mu0 = T kappa0 / n (k_B = 1).
  EXPECT_NEAR(compare::elastic_shear_viscosity(1.0, 1.0, 1.0), 0.5 / std::sqrt(kPi), 1e-16);
  EXPECT_NEAR(compare::elastic_shear_viscosity(2.0, 3.0, 0.5), std::sqrt(6.0 / kPi), 1e-15);
  EXPECT_NEAR(compare::elastic_conductivity(2.0, 3.0, 0.5), 2.0 * std::sqrt(6.0 / kPi), 1e-15);
  EXPECT_NEAR(compare::elastic_mu(2.0, 3.0, 0.5, 0.1), 60.0 * std::sqrt(6.0 / kPi), 1e-12);
}

TEST(TransportNormalisation, ScaledCoefficientsInTheDisksUnitsAreTheElasticOnes) {
  // The dilute closure's eta = (K/4) T^(1/2) and kappa = K T^(1/2), times the units of a scaled
  // coefficient (n0 Lx for both, m = T0 = 1), are eta0 and kappa0 of the disks the scene maps
  // to, since K n0 Lx sigma = 2 / sqrt(pi) (docs/physics.md §1, §4). mu0 scaled, times Lx, is
  // T kappa0 / n in the disks' units (n in n0). Tolerance: roundings of the mapping.
  const md::ParticleScene scene = md::scene_from_scaled(0.08, 0.05, 0.02, 100.0);
  const hydro::DiluteClosure dilute(scene.physics());
  const double K = scene.physics().K, n0 = scene.number_density();
  const auto units = compare::scaled_transport_units(n0, scene.box_length);
  for (double T : {1.0, 0.3}) {
    EXPECT_NEAR(dilute.viscosity(T) * units.viscosity / compare::elastic_shear_viscosity(1, T, 1),
                1.0, 1e-12);
    EXPECT_NEAR(
        dilute.conductivity(T) * units.conductivity / compare::elastic_conductivity(1, T, 1), 1.0,
        1e-12);
    EXPECT_NEAR(
        compare::scaled_elastic_mu(K, 0.7, T) * units.mu / compare::elastic_mu(1, T, 1, 0.7 * n0),
        1.0, 1e-12);
  }
}

TEST(TransportNormalisation, ClosuresRelativeToTheElasticDiluteValues) {
  // The dilute closure is the elastic dilute gas whatever q, n and T: 1 for every coefficient.
  // The Enskog closure at phi0: its factors at phi0 (hydro/enskog_factors.hpp).
  const hydro::Physics physics{0.08, 1e-9};
  const hydro::DiluteClosure dilute(physics);
  const hydro::EnskogClosure enskog(physics, 0.2, hydro::CoolingRate::small_q);
  for (const auto& c : compare::transport_coefficients()) {
    const double elastic = c.name == "mu" ? 0.0 : 1.0;  // the elastic gas has no mu
    EXPECT_NEAR(c.relative_value(dilute, physics.K, 1.0, 1.0), elastic, 1e-15) << c.name;
    EXPECT_NEAR(c.relative_value(dilute, physics.K, 0.7, 2.5), elastic, 1e-15) << c.name;
  }
  EXPECT_NEAR(compare::transport_coefficient("shear_viscosity").relative_value(enskog, 0.08, 1, 1),
              hydro::enskog::shear_viscosity_factor(0.2), 1e-14);
  EXPECT_NEAR(compare::transport_coefficient("conductivity").relative_value(enskog, 0.08, 1, 1),
              hydro::enskog::conductivity_factor(0.2), 1e-14);
  EXPECT_EQ(compare::transport_coefficient("shear_viscosity").factor_keys,
            std::vector<std::string>{"hydro.viscosity_factor"});
  // kappa and mu scale together in what a pressure-balanced mode sees.
  EXPECT_EQ(compare::transport_coefficient("effective_conductivity").factor_keys,
            (std::vector<std::string>{"hydro.conductivity_factor", "hydro.mu_factor"}));
  EXPECT_THROW(compare::transport_coefficient("bulk_viscosity"), std::invalid_argument);
}

// The dilute closure's coefficients with mu = 0.2 K T^(3/2): the closure seam's mu, read by the
// coefficients of a pressure-balanced mode and of mu alone.
class DiluteWithMu final : public hydro::Closure {
 public:
  explicit DiluteWithMu(const hydro::Physics& physics) : dilute_(physics), K_(physics.K) {}
  std::string name() const override { return "dilute_with_mu"; }
  void cell_coefficients(const std::vector<double>& n, const std::vector<double>& T,
                         hydro::CellCoefficients& out) const override {
    dilute_.cell_coefficients(n, T, out);
    for (size_t i = 0; i < n.size(); ++i) out.mu[i] = 0.2 * K_ * T[i] * std::sqrt(T[i]);
  }
  void sound_speed(const std::vector<double>&, const std::vector<double>&,
                   std::vector<double>&) const override {}
  void cooling_rate(const std::vector<double>&, const std::vector<double>&,
                    std::vector<double>&) const override {}
  void cool(const std::vector<double>&, const std::vector<double>&, double,
            std::vector<double>&) const override {}
  hydro::HcsLinearisation hcs_linearisation() const override { return {}; }
  hydro::ValidityScales validity_scales() const override { return {}; }

 private:
  hydro::DiluteClosure dilute_;
  double K_;
};

TEST(TransportNormalisation, EffectiveConductivityIsKappaLessMuNOverT) {
  // kappa = K T^(1/2), mu = 0.2 K T^(3/2): (kappa - mu n / T) / kappa0 = 1 - 0.2 n, and
  // mu / mu0 = 0.2 K T^(3/2) / (K T^(3/2) / n) = 0.2 n, at any T. Tolerance: a few roundings.
  const DiluteWithMu closure({0.08, 0.05});
  for (double n : {1.0, 0.6}) {
    EXPECT_NEAR(compare::transport_coefficient("effective_conductivity")
                    .relative_value(closure, 0.08, n, 1.7),
                1.0 - 0.2 * n, 1e-14);
    EXPECT_NEAR(compare::transport_coefficient("mu").relative_value(closure, 0.08, n, 1.7), 0.2 * n,
                1e-14);
    EXPECT_NEAR(
        compare::transport_coefficient("conductivity").relative_value(closure, 0.08, n, 1.7), 1.0,
        1e-14);
  }
}

}  // namespace
