// The heat-flux fit (compare/heat_flux_fit.hpp) on synthetic ensembles whose fields carry a
// prescribed heat flux q = -kappa dT/dx - mu dn/dx + beta d2v/dx2 inside the box-frame energy
// flux the coarse-grainer writes (J = q + v (e + p) + rho v^3 / 2, e = p = n T in 2D):
// - without noise beyond a small persistent scatter of the members, the coefficients come back
//   to 1e-3 (3e-3 for the Burnett term; the fit is linear in the mode amplitudes, what is left
//   is second order in them);
// - with noise, 20 ensembles of 32 members: every estimate within 4 stated errors of the truth,
//   and the stated errors within a factor 0.6-1.6 of the estimates' scatter (20 ensembles give
//   a scatter to about 16 %);
// - a pressure-balanced mode (T = -n) and too few members or snapshots are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "compare/heat_flux_fit.hpp"
#include "fields/constants.hpp"

namespace granvv {
namespace {

using compare::fit_heat_flux;
using compare::heat_flux_amplitudes;
using compare::HeatFluxFit;

constexpr double kLength = 500.0, kDensity = 0.025, kMass = 1.0, kDiameter = 1.0;
constexpr int kBins = 32, kSnapshots = 30;

struct Truth {
  double conductivity = 1.05, mu = 0.15, theta = -6.0;
};

// The mode amplitudes at snapshot s (smooth, not proportional to each other) and the box's T.
double density_mode(int s) {
  return 0.02 * std::exp(-s / 20.0);
}
double temperature_mode(int s) {
  return 0.015 * std::sin(0.2 * s + 0.3);
}
double flow_mode(int s) {
  return 0.01 * std::cos(0.3 * s);
}
double box_temperature(int s) {
  return 1.0 / std::pow(1.0 + s / 10.0, 2);
}

// One member: its modes offset by (dn, dT, dv) for all snapshots, q's k = 1 part by noise.
fields::FieldSeries member(const Truth& truth, double dn, double dT, double dv,
                           const std::vector<double>& q_noise, bool pressure_balanced) {
  fields::FieldSeries series = fields::FieldSeries::on_bins(-0.5 * kLength, kLength, kBins);
  const double k = kTwoPi / kLength;
  for (int s = 0; s < kSnapshots; ++s) {
    fields::FieldSnapshot f;
    f.t = 10.0 * s;
    const double T0 = box_temperature(s);
    const double n_c = density_mode(s) + dn;
    const double T_c = pressure_balanced ? -n_c : temperature_mode(s) + dT;
    const double v_s = flow_mode(s) + dv;
    const double kappa0 = 2.0 * std::sqrt(T0 / (kPi * kMass)) / kDiameter;
    const double eta0 = std::sqrt(kMass * T0 / kPi) / (2.0 * kDiameter);
    const double beta = truth.theta * eta0 * eta0 / (kMass * kDensity);
    // q = q_s sin(2 pi x): -kappa dT/dx = kappa k T0 T_c sin, -mu dn/dx = mu k n0 n_c sin,
    // beta d2v/dx2 = -beta k^2 v_s sin.
    const double q_s = truth.conductivity * kappa0 * k * T0 * T_c +
                       truth.mu * (T0 * kappa0 / kDensity) * k * kDensity * n_c -
                       beta * k * k * v_s + q_noise[static_cast<std::size_t>(s)];
    for (int b = 0; b < kBins; ++b) {
      const double x = -0.5 + (b + 0.5) / kBins;  // scaled bin centre
      const double n = kDensity * (1.0 + n_c * std::cos(kTwoPi * x));
      const double T = T0 * (1.0 + T_c * std::cos(kTwoPi * x));
      const double v = v_s * std::sin(kTwoPi * x);
      const double e = n * T, rho = kMass * n;
      f.x.push_back(x * kLength);
      f.n.push_back(n);
      f.v_x.push_back(v);
      f.v_y.push_back(0.0);
      f.T.push_back(T);
      f.kinetic_energy.push_back(e + 0.5 * rho * v * v);
      f.energy_flux_x.push_back(q_s * std::sin(kTwoPi * x) + v * 2.0 * e + 0.5 * rho * v * v * v);
    }
    series.snapshots.push_back(std::move(f));
  }
  return series;
}

// An ensemble of M members with persistent offsets (scale `offset`) and per-snapshot flux noise
// (scale `noise` relative to the typical heat flux).
std::vector<fields::FieldSeries> ensemble(const Truth& truth, int M, double offset, double noise,
                                          std::mt19937_64& rng, bool pressure_balanced = false) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<fields::FieldSeries> members;
  for (int m = 0; m < M; ++m) {
    std::vector<double> q_noise;
    for (int s = 0; s < kSnapshots; ++s) {
      const double T0 = box_temperature(s);
      const double scale = 2.0 * std::sqrt(T0 / kPi) * (kTwoPi / kLength) * T0 * 0.02;
      q_noise.push_back(noise * scale * g(rng));
    }
    members.push_back(member(truth, offset * 0.02 * g(rng), offset * 0.015 * g(rng),
                             offset * 0.01 * g(rng), q_noise, pressure_balanced));
  }
  return members;
}

HeatFluxFit fit(const std::vector<fields::FieldSeries>& members, std::size_t start = 1) {
  return fit_heat_flux(heat_flux_amplitudes(members, kMass), kTwoPi / kLength, kMass, kDiameter,
                       start, true);
}

TEST(HeatFluxFit, RecoversThePrescribedCoefficientsToSecondOrder) {
  std::mt19937_64 rng(11);
  const Truth truth;
  const HeatFluxFit f = fit(ensemble(truth, 16, 0.2, 0.0, rng));
  EXPECT_NEAR(f.conductivity, truth.conductivity, 1e-3 * truth.conductivity);
  EXPECT_NEAR(f.mu, truth.mu, 1e-3);
  // The flow's enthalpy flux 2 e v carries a k = 1 part of second order, (n_c T_c / 4) of it,
  // that the fit reads as Burnett flux, the smallest of the three terms: 3e-3 there.
  EXPECT_NEAR(f.burnett, truth.theta, 3e-3 * std::abs(truth.theta));
  EXPECT_EQ(f.degrees_of_freedom, kSnapshots - 1 - 3);
  EXPECT_EQ(f.snapshots.front(), 1u);
}

TEST(HeatFluxFit, NoisyEnsemblesLandWithinTheirStatedErrors) {
  std::mt19937_64 rng(12);
  const Truth truth;
  const int ensembles = 20;
  std::vector<double> kappa, mu, theta;
  double stated_kappa = 0.0, stated_mu = 0.0, stated_theta = 0.0;
  for (int e = 0; e < ensembles; ++e) {
    const HeatFluxFit f = fit(ensemble(truth, 32, 1.0, 3.0, rng));
    EXPECT_NEAR(f.conductivity, truth.conductivity, 4.0 * f.conductivity_error);
    EXPECT_NEAR(f.mu, truth.mu, 4.0 * f.mu_error);
    EXPECT_NEAR(f.burnett, truth.theta, 4.0 * f.burnett_error);
    kappa.push_back(f.conductivity), mu.push_back(f.mu), theta.push_back(f.burnett);
    stated_kappa += f.conductivity_error / ensembles;
    stated_mu += f.mu_error / ensembles;
    stated_theta += f.burnett_error / ensembles;
  }
  const auto scatter = [](const std::vector<double>& v) {
    double mean = 0.0, var = 0.0;
    for (double x : v) mean += x / double(v.size());
    for (double x : v) var += (x - mean) * (x - mean) / double(v.size() - 1);
    return std::sqrt(var);
  };
  for (const auto& [name, values, stated] :
       {std::tuple{"kappa", kappa, stated_kappa}, std::tuple{"mu", mu, stated_mu},
        std::tuple{"theta", theta, stated_theta}}) {
    SCOPED_TRACE(name);
    const double ratio = stated / scatter(values);
    EXPECT_GT(ratio, 0.6);
    EXPECT_LT(ratio, 1.6);
  }
}

TEST(HeatFluxFit, RefusesAPressureBalancedModeAndTooLittleData) {
  std::mt19937_64 rng(13);
  const Truth truth;
  try {
    fit(ensemble(truth, 16, 0.2, 1.0, rng, true));
    FAIL() << "a pressure-balanced mode was fitted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("proportional"), std::string::npos) << e.what();
  }
  EXPECT_THROW(heat_flux_amplitudes(ensemble(truth, 7, 0.2, 1.0, rng), kMass),
               std::invalid_argument);
  EXPECT_THROW(fit(ensemble(truth, 16, 0.2, 1.0, rng), kSnapshots - 5), std::invalid_argument);
  EXPECT_THROW(heat_flux_amplitudes(ensemble(truth, 16, 0.2, 1.0, rng), 0.0),
               std::invalid_argument);
  auto missing = ensemble(truth, 16, 0.2, 1.0, rng);
  missing[3].snapshots[2].energy_flux_x.clear();
  EXPECT_THROW(heat_flux_amplitudes(missing, kMass), std::invalid_argument);
}

}  // namespace
}  // namespace granvv
