// The particles' pressure (docs/physics.md §11) and the box's Fourier modes (§12), against
// known answers: the kinetic pressure is n T exactly without contacts; a given contact virial is
// added exactly; an elastic LAMMPS gas at phi = 0.1 has Henderson's P/(nT) = 1 + 2 phi chi; an
// imposed shear flow carries its share of the kinetic energy in the modes; the Haff window ends
// before the first sample above the threshold; and the CLI states window, onsets and pressure at
// the extremes of the restitution the cooling scenes accept.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <vector>

#include "compare/haff_window.hpp"
#include "compare/sample_average.hpp"
#include "hydro/enskog_factors.hpp"
#include "hydro/haff.hpp"
#include "hydro/linear_stability.hpp"
#include "md_bridge/box_modes.hpp"
#include "md_bridge/coarse_grainer.hpp"
#include "md_bridge/lammps_engine.hpp"
#include "md_bridge/md_run.hpp"
#include "support/cli_runner.hpp"

namespace granvv::md {
namespace {

struct Gas {
  std::vector<double> x, v, mass;
  int count() const { return int(mass.size()); }
};

// n particles uniform in [-lx/2, lx/2) x [-ly/2, ly/2), Maxwellian at T, unequal masses.
Gas random_gas(int n, double lx, double ly, double T, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(-0.5 * lx, 0.5 * lx), uy(-0.5 * ly, 0.5 * ly),
      um(0.5, 2.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  Gas g;
  for (int p = 0; p < n; ++p) {
    const double m = um(rng);
    g.mass.push_back(m);
    g.x.insert(g.x.end(), {ux(rng), uy(rng), 0.0});
    g.v.insert(g.v.end(),
               {std::sqrt(T / m) * gauss(rng) + 0.3, std::sqrt(T / m) * gauss(rng), 0.0});
  }
  return g;
}

TEST(ParticlePressure, KineticPressureIsNTExactlyWithoutContacts) {
  const Gas g = random_gas(4000, 50.0, 20.0, 1.7, 3);
  CoarseGrainer grainer({-25.0, 50.0, -10.0, 20.0, 8, "bin", 0.0});
  const std::vector<double> zero(g.mass.size(), 0.0);
  Moments m(8);
  grainer.accumulate(m, g.x.data(), g.v.data(), g.mass.data(), g.count(), 3, zero.data(),
                     zero.data());
  const auto f = grainer.fields(m);
  for (int i = 0; i < 8; ++i) {
    // The identity (T_x + T_y)/2 = T of the same unbiased denominators, to round-off.
    EXPECT_NEAR(0.5 * (f.P_xx[i] + f.P_yy[i]), f.n[i] * f.T[i], 1e-13 * f.n[i] * f.T[i]) << i;
    EXPECT_GT(f.P_xx_stderr[i], 0.0);
  }
  const BoxPressure box = grainer.pressure(m);
  EXPECT_NEAR(box.compressibility(), 1.0, 1e-13);
  // Without a virial the pressure is undefined, not the kinetic part alone.
  const Moments bare = grainer.accumulate(g.x.data(), g.v.data(), g.mass.data(), g.count());
  EXPECT_TRUE(std::isnan(grainer.fields(bare).P_xx[0]));
  EXPECT_TRUE(std::isnan(grainer.pressure(bare).mean()));
}

TEST(ParticlePressure, ContactVirialIsAddedPerBinArea) {
  const Gas g = random_gas(2000, 40.0, 10.0, 1.0, 5);
  CoarseGrainer grainer({-20.0, 40.0, -5.0, 10.0, 4, "bin", 0.0});
  const std::vector<double> wxx(g.mass.size(), 0.25), wyy(g.mass.size(), -0.5), zero(g.mass.size());
  Moments with(4), without(4);
  grainer.accumulate(with, g.x.data(), g.v.data(), g.mass.data(), g.count(), 3, wxx.data(),
                     wyy.data());
  grainer.accumulate(without, g.x.data(), g.v.data(), g.mass.data(), g.count(), 3, zero.data(),
                     zero.data());
  const auto a = grainer.fields(with), b = grainer.fields(without);
  const double bin_area = 10.0 * 10.0;
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(a.P_xx[i] - b.P_xx[i], 0.25 * a.count[i] / bin_area, 1e-12) << i;
    EXPECT_NEAR(a.P_yy[i] - b.P_yy[i], -0.5 * a.count[i] / bin_area, 1e-12) << i;
  }
  const BoxPressure box = grainer.pressure(with);
  EXPECT_NEAR(box.mean() - grainer.pressure(without).mean(), -0.125 * 2000 / (40.0 * 10.0), 1e-12);
}

// An elastic gas of soft disks at phi = 0.1 against the hard-disk equation of state with
// Henderson's chi, P/(nT) = 1 + 2 phi chi = 1.2361 (the elastic limit of F_p). 1000 disks, 120
// samples 0.25 apart (longer than a contact, 0.02, so the instantaneous virials are nearly
// independent: the error is their scatter / sqrt(120), about 0.015). Tolerance: 4 errors plus
// 0.01 for the soft contact (overlaps up to 1 % of sigma shorten the lever arm r_ij and add
// the time in contact, a few per cent of the contact part 0.236) .
TEST(ParticlePressure, ElasticGasFollowsHendersonsEquationOfState) {
  MdRunSpec spec;
  const double phi = 0.1;
  spec.scene = scene_from_particles(1000, phi, std::sqrt(1000 * 3.14159265358979 / (4 * phi)), 1.0);
  spec.fields = hydro::uniform_fields();
  spec.t_end = 30.0;
  spec.sample_interval = 0.25;
  spec.bins = 5;
  spec.kernel = "bin";
  spec.seed = 7;
  LammpsEngineOptions o;
  o.restitution = 1.0;
  o.box_length = spec.scene.box_length;
  o.box_width = spec.scene.box_width;
  o.particles = spec.scene.particles;
  o.max_overlap = 0.01;
  o.steps_per_contact = 30;
  o.adaptive_stiffness = false;
  LammpsEngine engine(o);
  const MdRunResult r = run_md(spec, engine, nullptr);
  ASSERT_EQ(r.status, "ok");
  const auto& s = r.series;
  EXPECT_TRUE(std::isnan(s.compressibility.front()));  // t = 0: no step, no contact measured
  double sum = 0.0, squares = 0.0, anisotropy = 0.0;
  int k = 0;
  for (std::size_t i = 1; i < s.t.size(); ++i) {
    ASSERT_TRUE(std::isfinite(s.compressibility[i])) << i;
    sum += s.compressibility[i];
    squares += s.compressibility[i] * s.compressibility[i];
    anisotropy += (s.pressure_xx[i] - s.pressure_yy[i]) / (s.pressure_xx[i] + s.pressure_yy[i]);
    ++k;
  }
  const double z = sum / k;
  const double error = std::sqrt((squares / k - z * z) / (k - 1));
  const double henderson = hydro::enskog::pressure_factor(phi, 1.0);
  RecordProperty("compressibility", std::to_string(z) + " +- " + std::to_string(error));
  EXPECT_NEAR(z, henderson, 4.0 * error + 0.01) << "error " << error;
  EXPECT_LT(error, 0.03);
  // Isotropy: P_xx = P_yy within the same noise.
  EXPECT_LT(std::abs(anisotropy / k), 0.02);
}

TEST(BoxModes, ImposedShearFlowCarriesItsShareOfTheKineticEnergy) {
  const double lx = 60.0, ly = 60.0, U = 1.0, T = 0.5;
  Gas g = random_gas(20000, lx, ly, T, 9);
  for (std::size_t p = 0; p < g.mass.size(); ++p) {
    g.v[3 * p] -= 0.3;  // no mean drift
    g.v[3 * p + 1] += U * std::sin(2.0 * 3.14159265358979 * g.x[3 * p] / lx);
  }
  const BoxModes m =
      box_modes(box_mode_sums(g.x.data(), g.v.data(), g.mass.data(), g.count(), lx, ly));
  // Flow energy sum m U^2 sin^2 / 2 = M U^2 / 4; thermal N T.
  double mass = 0.0;
  for (double mp : g.mass) mass += mp;
  const double flow = mass * U * U / 4.0, expected = flow / (flow + g.count() * T);
  // Noise: the thermal part is about 3.5 / N of the energy (docs/physics.md §12) and the
  // random positions put 1/sqrt(N) into the sine's projection.
  EXPECT_NEAR(m.energy_fraction, expected, 0.02 * expected + 5.0 * 3.5 / g.count());
  // Random positions: every density mode has |rho_k|^2 / N ~ 1.
  EXPECT_NEAR(m.structure_factor, 1.0, 0.8);

  const Gas still = random_gas(20000, lx, ly, T, 10);
  const BoxModes h =
      box_modes(box_mode_sums(still.x.data(), still.v.data(), still.mass.data(), 20000, lx, ly));
  EXPECT_NEAR(h.energy_fraction, 0.0, 5.0 * 3.5 / 20000);  // noise subtracted
}

TEST(BoxModes, LinearOnsetInvertsTheGrowthOfTheFirstShearMode) {
  const double threshold = 0.01;
  const ParticleScene elastic = scene_from_particles(10000, 0.05, 396.0, 1.0);
  EXPECT_TRUE(std::isinf(linear_mode_onset_md(elastic, threshold)));
  for (double r : {0.02, 0.5, 0.9, 0.99}) {
    const ParticleScene sc = scene_from_particles(10000, 0.05, 396.0, r);
    const double onset = linear_mode_onset_md(sc, threshold);
    ASSERT_FALSE(std::isnan(onset)) << r;
    if (std::isinf(onset)) continue;
    // f0 exp(2 lambda s(t*)) = threshold, with s the collision clock of the dilute hydro.
    const hydro::Physics ph = sc.physics();
    const double rate = std::max(hydro::shear_rate(ph, 1), hydro::hcs_modes(ph, 1)[0].rate.real());
    const double s = hydro::collision_clock(sc.scaled_time(onset), hydro::haff_time_scale(ph));
    EXPECT_NEAR(2.0 / 10000 * std::exp(2.0 * rate * s), threshold, 1e-9) << r;
  }
}

TEST(HaffWindow, EndsAtTheLastSampleBeforeTheThreshold) {
  const std::vector<double> t = {0, 1, 2, 3, 4};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto w = compare::homogeneous_window(t, {0.0, nan, 0.005, 0.02, 0.0}, 0.01, 4.0);
  EXPECT_TRUE(w.starts_homogeneous);
  EXPECT_EQ(w.onset, 3.0);
  EXPECT_EQ(w.t_max, 2.0);
  w = compare::homogeneous_window(t, {0.5, 0.5, 0.5, 0.5, 0.5}, 0.01, 4.0);  // an imposed flow
  EXPECT_FALSE(w.starts_homogeneous);
  EXPECT_EQ(w.t_max, 4.0);
  w = compare::homogeneous_window(t, {0, 0, 0, 0, 0}, 0.01, 4.0);
  EXPECT_TRUE(std::isnan(w.onset));
  EXPECT_EQ(w.t_max, 4.0);
}

TEST(SampleAverage, MembersScatterOrPropagatedErrors) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto a = compare::sample_average({{nan, 1.0, 3.0}}, {{nan, 0.4, 0.3}});
  EXPECT_EQ(a.mean, 2.0);
  EXPECT_NEAR(a.error, 0.25, 1e-15);  // sqrt(0.16 + 0.09) / 2
  a = compare::sample_average({{1.0, 1.0}, {3.0, 3.0}}, {{0.1, 0.1}, {0.1, 0.1}});
  EXPECT_EQ(a.mean, 2.0);
  EXPECT_NEAR(a.error, 1.0, 1e-15);  // the scatter sqrt(2 / 1 / 2) beats the model 0.05
  a = compare::sample_average({{1.0, 1.0}, {1.2, 1.2}}, {{2.0, 2.0}, {2.0, 2.0}});
  // each member sqrt(4 + 4) / 2, their mean sqrt(2 + 2) / 2 = 1 beats the scatter 0.1
  EXPECT_NEAR(a.error, 1.0, 1e-15);
}

// md_cooling_sweep (1000 disks, 2 seeds) shortened to 5 sigma sqrt(m/T0) (0.07 Haff times at
// r = 0.02) at the ends of the restitution range it accepts (r = 1, which
// cannot run in Haff times, below): window, onsets and pressure in the summary, the window
// never past the measured onset.
TEST(HaffWindowCli, StatesWindowOnsetsAndPressureAtTheEndsOfTheRestitutionRange) {
  for (const char* r : {"0.02", "0.999"}) {
    const auto dir = granvv::testing::fresh_directory(std::string("haff_window_") + r);
    const auto run = granvv::testing::run_cli(
        "run md_cooling_sweep --quiet --set md.time_unit=md --set md.t_end=5 --set md.ensemble=2 "
        "--set md.sample_interval=0.5 --set md.restitution=" +
        std::string(r) + " --out " + dir.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const auto md = nlohmann::json::parse(granvv::testing::read_text(dir / "summary.json"))["md"];
    EXPECT_EQ(md["haff_mode_energy_fraction"], 0.01);
    EXPECT_TRUE(md["haff_starts_homogeneous"].get<bool>()) << r;
    ASSERT_TRUE(md["pressure"].is_number()) << r;
    EXPECT_GT(md["pressure_error"].get<double>(), 0.0);
    // Within 30 % of Enskog at any r: short, noisy runs of 1000 disks (the EOS test is above).
    EXPECT_NEAR(md["compressibility"].get<double>(), md["compressibility_enskog"].get<double>(),
                0.3 * (md["compressibility_enskog"].get<double>() - 1.0) +
                    4.0 * md["compressibility_error"].get<double>())
        << r;
    const auto window = md["haff_fit_window"];
    if (md["haff_onset_measured"].is_number()) {
      EXPECT_LT(window[1].get<double>(), md["haff_onset_measured"].get<double>()) << r;
    }
    EXPECT_TRUE(md["haff_onset_linear"].is_number() || md["haff_onset_linear"].is_null());
  }
  // r = 1 does not cool: no linear onset.
  const auto dir = granvv::testing::fresh_directory("haff_window_elastic");
  const auto run = granvv::testing::run_cli(
      "run md_cooling_sweep --quiet --set md.time_unit=md --set md.t_end=10 "
      "--set md.sample_interval=1 --set md.ensemble=1 --set md.restitution=1 --out " +
      dir.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto md = nlohmann::json::parse(granvv::testing::read_text(dir / "summary.json"))["md"];
  EXPECT_TRUE(md["haff_onset_linear"].is_null());
  // The threshold key is refused outside (0, 1), with one line and nothing written.
  const auto refused = granvv::testing::fresh_directory("haff_window_refused");
  const auto bad =
      granvv::testing::run_cli("run md_cooling_sweep --set md.haff_mode_energy_fraction=0 --out " +
                               refused.string() + " 2>&1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("md.haff_mode_energy_fraction = 0"), std::string::npos) << bad.output;
  EXPECT_FALSE(std::filesystem::exists(refused / "summary.json"));
}

}  // namespace
}  // namespace granvv::md
