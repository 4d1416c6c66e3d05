// The paper's own scene in particles (cases/md_paper_scene.toml, docs/physics.md §8): the
// measures of a flow by inertia that survive noise (compare/inertia_measures.hpp) against known
// answers, and a shortened run of the scene through the real CLI and the event-driven engine.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "compare/binned_fields.hpp"
#include "compare/inertia_measures.hpp"
#include "hydro/flow_by_inertia.hpp"
#include "support/cli_runner.hpp"

namespace granvv::compare {
namespace {

std::vector<double> on_bin_centres(int bins, double (*f)(double)) {
  std::vector<double> v;
  for (int b = 0; b < bins; ++b) v.push_back(f(-0.5 + (b + 0.5) / bins));
  return v;
}

TEST(InertiaMeasures, ModeAmplitudesOfASingleModeAreExact) {
  // Sampled at the bin centres, sin and cos of mode 1 are orthogonal to each other and to the
  // constant on any bins > 2: the amplitudes come out exact to round-off.
  for (int bins : {7, 20, 100, 101}) {
    const auto s =
        on_bin_centres(bins, [](double x) { return 1.0 - 0.05 * std::sin(2 * M_PI * x); });
    const auto c =
        on_bin_centres(bins, [](double x) { return 2.0 + 0.3 * std::cos(2 * M_PI * x); });
    EXPECT_NEAR(sine_mode_amplitude(s, 1), -0.05, 1e-15) << bins;
    EXPECT_NEAR(cosine_mode_amplitude(s, 1), 0.0, 1e-15) << bins;
    EXPECT_NEAR(cosine_mode_amplitude(c, 1), 0.3, 1e-14) << bins;
    EXPECT_NEAR(sine_mode_amplitude(c, 1), 0.0, 1e-14) << bins;
    EXPECT_NEAR(sine_mode_amplitude(s, 2), 0.0, 1e-15) << bins;
  }
}

TEST(InertiaMeasures, CentralDensityAndWindowMass) {
  EXPECT_DOUBLE_EQ(central_density({1, 2, 7, 2, 1}), 7.0);  // odd: the bin holding x = 0
  EXPECT_DOUBLE_EQ(central_density({1, 3, 5, 1}), 4.0);     // even: the two bins at x = 0
  // Uniform n = 1 on 100 bins: the window |x| < 0.05 is 10 whole bins, a tenth of the mass.
  EXPECT_NEAR(central_window_mass(std::vector<double>(100, 1.0), kCentralWindowHalfWidth), 0.1,
              1e-15);
}

TEST(InertiaMeasures, WindowMassOfFlowByInertiaIsTheExactLagrangianMass) {
  // Flow by inertia of v0 = a sin 2 pi xi, n0 = 1 (paper Eq. 5): the mass within |x| < w is that
  // of the labels |xi| < xi(w, t), i.e. 2 xi(w, t). The binned state (10^4 elements of exact
  // mass, piecewise uniform density) must give it up to the elements' size squared: 1e-7.
  const double a = -0.05, w = kCentralWindowHalfWidth;
  const auto flow = hydro::FlowByInertia::single_mode(a);
  hydro::InitialFields initial;
  initial.n = [](double) { return 1.0; };
  initial.T = [](double) { return 1.0; };
  initial.vy = [](double) { return 0.0; };
  initial.v = [a](double x) { return a * std::sin(2 * M_PI * x); };
  initial.dv = [a](double x) { return 2 * M_PI * a * std::cos(2 * M_PI * x); };
  for (double t : {0.0, 1.0, 2.0, 3.0, 3.15}) {
    const auto binned = bin_lagrangian_state(flow_by_inertia_state(initial, t, 10000), 100);
    const double exact = 2.0 * flow.lagrangian_label(w, t);
    EXPECT_NEAR(central_window_mass(binned.n, w), exact, 1e-7) << t;
  }
  // At t = 3 (0.94 tau) the window holds 38 % of the mass (10 % at t = 0).
  EXPECT_NEAR(2.0 * flow.lagrangian_label(w, 3.0), 0.378, 0.001);
}

// The scene itself, shortened to t_MD = 40 (two seeds, a few seconds): it resolves to N = 28 209
// event-driven disks, states its signals against the noise (docs/physics.md §8) with the values
// of their formulas, and writes the flow by inertia's measures, whose t = 0 values are known.
TEST(PaperSceneCli, ShortenedSceneStatesSignalToNoiseAndInertiaMeasures) {
  const auto dir = granvv::testing::fresh_directory("md-paper-scene-short");
  const auto r = granvv::testing::run_cli(
      "run md_paper_scene --quiet --no-report --set md.t_end=40 --set md.ensemble=2 "
      "--set md.sample_interval=20 --set 'md.output_times=[0, 20, 40]' --out " +
      dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = nlohmann::json::parse(granvv::testing::read_text(dir / "summary.json"));
  const auto& md = s["md"];
  EXPECT_EQ(md["status"], "ok");
  EXPECT_EQ(md["engine"], "event_driven");
  const double n = md["particles"].get<double>();
  EXPECT_EQ(n, 28209);
  EXPECT_EQ(md["unstable_modes"], 79);
  EXPECT_TRUE(md["collapse_rule"]["fraction_changed"].is_number());
  // Gradient form: 2 pi |a| against k_max (k_max/N)^{1/2}; the sampled max|v0'| is within 1e-6.
  EXPECT_NEAR(md["signal_to_noise_gradient_initial"].get<double>(),
              2 * M_PI * 0.05 / (79 * std::sqrt(79 / n)), 1e-6);
  // Mode form: |a| against sqrt(2/N) (the midpoint rule is exact for one mode).
  EXPECT_NEAR(md["signal_to_noise_mode_initial"].get<double>(), 0.05 / std::sqrt(2 / n), 1e-9);
  const auto& f = s["compare"]["flow_by_inertia"];
  EXPECT_EQ(f["central_window"], kCentralWindowHalfWidth);
  // t = 0: flow by inertia and the hydro are the initial state on 100 bins; the bin average of
  // sin 2 pi x is sin(pi/100)/(pi/100) of it.
  const double bin_average = std::sin(M_PI / 100) / (M_PI / 100);
  EXPECT_NEAR(f["v_mode"]["inertia"][0].get<double>(), -0.05 * bin_average, 1e-6);
  EXPECT_NEAR(f["v_mode"]["hydro"][0].get<double>(), -0.05 * bin_average, 1e-5);
  EXPECT_NEAR(f["window_mass"]["inertia"][0].get<double>(), 0.1, 1e-9);
  EXPECT_NEAR(f["n_centre"]["hydro"][0].get<double>(), 1.0, 1e-9);
  // The particles: the imposed mode and the window mass within 5 standard errors of the mean of
  // 2 seeds (noise sqrt(2/N) on b1; binomial sqrt(p(1-p)/N) on the window's mass fraction p).
  EXPECT_NEAR(f["v_mode"]["md"][0].get<double>(), -0.05, 5 * std::sqrt(2 / n / 2));
  EXPECT_NEAR(f["window_mass"]["md"][0].get<double>(), 0.1, 5 * std::sqrt(0.1 * 0.9 / n / 2));
  EXPECT_EQ(f["n_mode"]["md"].size(), 3u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace granvv::compare
