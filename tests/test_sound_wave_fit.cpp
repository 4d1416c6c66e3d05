// The joint (kappa, mu) fit of the sound wave (docs/physics.md §14, §15) against the hydro
// itself: synthetic ensembles are made from the real garzo_dufty hydro of cases/sound_wave.toml
// at known factors (F_kappa, F_mu) plus member noise of the size and persistence the particles
// show, and fitted against the hydro on the scene's grid as `granvv run` fits the particles.
// If the scene and the fit can tell mu at all, they must give back the factors they were made
// with; the error the fit states must be the scatter of the ensembles.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "compare/mode_amplitudes.hpp"
#include "compare/transport_pair_fit.hpp"
#include "models/model.hpp"
#include "models/transport_measurement.hpp"
#include "scene/case_config.hpp"

namespace granvv::app {
namespace {

constexpr int kBins = 32;
constexpr int kSnapshots = 21;     // the scene's output times, t = 0, 0.2, ..., 4 (scaled)
constexpr double kHaffTime = 0.4;  // t0 = K/(4q) of the scene (scaled)

std::vector<double> snapshot_times() {
  std::vector<double> t;
  for (int s = 0; s < kSnapshots; ++s) t.push_back(0.2 * s);
  return t;
}

// The sound wave's hydro alone (no particles), 100 cells, at the given factors on kappa and mu.
HydroScene sound_wave(double conductivity_factor, double mu_factor) {
  std::string times = "hydro.output_times=[";
  for (double t : snapshot_times()) times += std::to_string(t) + ",";
  times.back() = ']';
  HydroScene scene = hydro_scene_from(CaseConfig::from_file(
      std::string(GRANVV_SOURCE_DIR) + "/cases/sound_wave.toml",
      {"md.enabled=false", "compare.enabled=false", "hydro.cells=100", "hydro.t_end=4.0", times}));
  set_transport_factor(scene, "hydro.conductivity_factor", conductivity_factor);
  set_transport_factor(scene, "hydro.mu_factor", mu_factor);
  return scene;
}

// The hydro's k = 1 amplitudes of the three signals at the snapshot times.
std::vector<std::vector<double>> signals_of(double conductivity_factor, double mu_factor) {
  HydroModel model(sound_wave(conductivity_factor, mu_factor), kBins);
  const fields::ModelResult result = model.run();
  std::vector<std::vector<double>> out;
  const std::vector<std::pair<std::string, compare::ModePhase>> signals = {
      {"v_x", compare::ModePhase::sine},
      {"n", compare::ModePhase::cosine},
      {"T", compare::ModePhase::cosine}};
  for (const auto& [field, phase] : signals) {
    std::vector<std::size_t> found;
    out.push_back(hydro_mode_amplitudes(*result.fields, field, phase, snapshot_times(), found));
    EXPECT_EQ(found.size(), std::size_t(kSnapshots)) << field;
  }
  return out;
}

TEST(SoundWaveFit, TheHydrosOwnKappaAndMuComeBackFromNoisyEnsembles) {
  // The scene's grid: F_kappa 0.5 ... 1.5, F_mu such that mu/mu0 = 0, 0.1, ..., 0.4 (garzo_dufty's
  // mu* = 0.167 at r = 0.9), searched one step below 0.
  compare::FactorPairGrid grid;
  grid.factors_a = {0.5, 0.75, 1.0, 1.25, 1.5};
  const double mu_star = 0.1668;
  for (double v : {0.0, 0.1, 0.2, 0.3, 0.4}) grid.factors_b.push_back(v / mu_star);
  grid.b_below = grid.factors_b[1] - grid.factors_b[0];
  std::vector<compare::PairSignal> table(3);
  for (double fa : grid.factors_a) {
    for (auto& g : table) g.hydro.emplace_back();
    for (double fb : grid.factors_b) {
      const auto h = signals_of(fa, fb);
      for (int g = 0; g < 3; ++g) table[g].hydro.back().push_back(h[g]);
    }
  }
  // The truth: the hydro at F_kappa = 1, F_mu = 1 (off the grid's nodes in mu).
  const std::vector<std::vector<double>> truth = signals_of(1.0, 1.0);
  // Member noise as the particles': 1410 disks give a k = 1 amplitude scatter of about
  // sqrt(2/N) = 0.038 per member and snapshot (v_x: times the thermal speed), persistent from
  // snapshot to snapshot (an AR(1) with correlation 0.8, the mode's own fluctuation decaying over a
  // few snapshots).
  std::mt19937 rng(29);
  std::normal_distribution<double> normal(0.0, 1.0);
  constexpr int kEnsembles = 6, kMembers = 96;
  constexpr double kNoise = 0.038, kPersistence = 0.8;
  std::vector<double> fitted_b, stated_b, fitted_a;
  for (int e = 0; e < kEnsembles; ++e) {
    std::vector<compare::PairSignal> signals = table;
    for (int m = 0; m < kMembers; ++m) {
      for (int g = 0; g < 3; ++g) {
        std::vector<double> a(kSnapshots);
        double offset = kNoise * normal(rng);
        for (int s = 0; s < kSnapshots; ++s) {
          // v_x is read in sqrt(T0/m): its noise falls with the thermal speed, 1/(1 + t/t0).
          const double thermal = g == 0 ? 1.0 / (1.0 + snapshot_times()[s] / kHaffTime) : 1.0;
          a[s] = truth[g][s] + thermal * offset;
          offset = kPersistence * offset +
                   std::sqrt(1.0 - kPersistence * kPersistence) * kNoise * normal(rng);
        }
        signals[g].members.push_back(a);
      }
    }
    const compare::PairFit fit = compare::fit_transport_factor_pair(grid, signals);
    EXPECT_FALSE(fit.at_grid_edge) << "ensemble " << e;
    fitted_a.push_back(fit.factor_a);
    fitted_b.push_back(fit.factor_b);
    stated_b.push_back(fit.error_b);
    // Each fit within 4 stated errors of the factors the members were made with.
    EXPECT_NEAR(fit.factor_a, 1.0, 4.0 * fit.error_a) << "ensemble " << e;
    EXPECT_NEAR(fit.factor_b, 1.0, 4.0 * fit.error_b) << "ensemble " << e;
  }
  // The mean over the ensembles is unbiased within 4 errors of that mean, and the stated error
  // of F_mu is the ensembles' scatter within a factor 2 (six ensembles: the scatter itself is
  // known to about 30 %).
  double mean_b = 0.0, mean_stated = 0.0;
  for (int e = 0; e < kEnsembles; ++e) mean_b += fitted_b[e] / kEnsembles;
  for (double s : stated_b) mean_stated += s / kEnsembles;
  double scatter = 0.0;
  for (double b : fitted_b) scatter += (b - mean_b) * (b - mean_b) / (kEnsembles - 1);
  scatter = std::sqrt(scatter);
  EXPECT_NEAR(mean_b, 1.0, 4.0 * mean_stated / std::sqrt(double(kEnsembles)));
  EXPECT_GT(scatter, 0.5 * mean_stated);
  EXPECT_LT(scatter, 2.0 * mean_stated);
}

}  // namespace
}  // namespace granvv::app
