// The event-driven engine against hard-disk known answers that need long runs (issues 11, 13;
// docs/physics.md §13): the equation of state of the elastic gas over phi = 0.05 ... 0.5, and
// Haff's t0 at r = 0.9 and 0.98 over the homogeneous window against Enskog theory with chi(phi)
// and the first Sonine correction. Each test prints its table (and records it as properties).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "compare/haff_fit.hpp"
#include "compare/haff_window.hpp"
#include "hydro/initial_conditions.hpp"
#include "hydro/linear_stability.hpp"
#include "md_bridge/event_driven_engine.hpp"
#include "md_bridge/hard_disk_theory.hpp"
#include "md_bridge/md_run.hpp"
#include "support/elastic_gas.hpp"

namespace granvv::md {
namespace {

// 4000 disks, 50 collisions per disk to relax from the uniform random start, then 40 blocks of
// 50 collisions per disk (each block longer than the virial's correlation time, a few collision
// times). Tolerance against Luding's EOS: 4 standard errors plus 0.3 % of Z.
TEST(SlowEventDrivenPhysics, EquationOfStateFromPhiPoint05ToPoint5) {
  std::printf(
      "| phi | Z measured | Luding 2001 | (Z - Luding)/error | Henderson | Liu 2020 "
      "| collisions | CPU s |\n|---|---|---|---|---|---|---|---|\n");
  for (const double phi : {0.05, 0.1, 0.2, 0.3, 0.4, 0.5}) {
    const auto m = granvv::testing::measure_compressibility(phi, 4000, 5, 50.0, 50.0, 40);
    const double luding = luding_compressibility(phi);
    std::printf("| %.2f | %.5f ± %.5f | %.5f | %+.2f | %.5f | %.5f | %.3g | %.1f |\n", phi, m.z,
                m.error, luding, (m.z - luding) / m.error, henderson_compressibility(phi),
                liu_compressibility(phi), double(m.collisions), m.cpu_seconds);
    RecordProperty("z_" + std::to_string(phi),
                   std::to_string(m.z) + " +- " + std::to_string(m.error));
    EXPECT_NEAR(m.z, luding, 4.0 * m.error + 3e-3 * luding) << phi;
  }
}

struct HaffMeasurement {
  compare::HaffFit from_start, after_transient;
  compare::HomogeneousWindow window;
  double theory = 0.0;           // Enskog with chi and Sonine a2
  double collision_ratio = 0.0;  // measured collision frequency / Enskog's nu (1 - a2/16)
  double collision_ratio_error = 0.0;
  // The cooling rate per collision, -d ln T/dt / nu, over its theory (1 - r^2)/2 (1 + 3 a2/16)
  // / (1 - a2/16).
  double loss_ratio = 0.0, loss_ratio_error = 0.0;
};

struct Mean {
  double sum = 0.0, squares = 0.0;
  int k = 0;
  void add(double x) { sum += x, squares += x * x, ++k; }
  double mean() const { return sum / k; }
  double error() const { return std::sqrt((squares / k - mean() * mean()) / (k - 1)); }
};

// A square box of `disks` disks at area fraction phi and restitution r.
ParticleScene square_box(long long disks, double phi, double r) {
  return scene_from_particles(disks, phi, std::sqrt(double(disks) * M_PI / (4.0 * phi)), r);
}

// The square box at area fraction phi whose side is `fraction` of the critical size L_c, the
// side at which the first shear mode of the homogeneous cooling state turns unstable (docs/
// physics.md §2, §12; pi K < 2 sqrt(q) with K proportional to 1/L, so L/L_c is the shear cutoff
// mode number of the box).
ParticleScene square_box_of_critical(double fraction, double phi, double r) {
  const ParticleScene trial = square_box(1000, phi, r);
  const double side = fraction * trial.box_width / hydro::shear_cutoff_mode(trial.physics());
  return square_box(std::llround(4.0 * phi * side * side / M_PI), phi, r);
}

// `seeds` runs of a homogeneous scene to 2 t0, sampled 100 times; the window ends where the
// ensemble-mean mode-energy fraction first exceeds 1 % (md.haff_mode_energy_fraction's
// default). The fit from t = 0 and the fit from 0.25 t0 (after the ~10 collisions per disk in
// which a2 builds up from the Maxwellian start).
HaffMeasurement measure_haff(const ParticleScene& scene, int seeds) {
  MdRunSpec spec;
  spec.scene = scene;
  const double r = scene.restitution, phi = scene.area_fraction;
  spec.fields = hydro::uniform_fields();
  HaffMeasurement h;
  h.theory = haff_time_sonine_md(spec.scene);
  spec.t_end = 2.0 * h.theory;
  spec.sample_interval = spec.t_end / 100.0;
  spec.bins = 20;
  spec.kernel = "bin";
  EventDrivenEngine engine(granvv::testing::event_driven_options(spec.scene, spec.bins));
  std::vector<std::vector<double>> ts, Ts;
  std::vector<double> fraction;
  // A disk has N - 1 partners: Enskog's frequency at the density of the others (0.1 % in a box
  // of 1000 disks).
  const double a2 = sonine_a2(r),
               n = spec.scene.number_density() * double(scene.particles - 1) / scene.particles;
  Mean collisions, losses;
  const double loss_theory = 0.5 * (1.0 - r * r) * (1.0 + 3.0 * a2 / 16.0) / (1.0 - a2 / 16.0);
  for (int seed = 1; seed <= seeds; ++seed) {
    spec.seed = std::uint64_t(seed);
    const MdRunResult run = run_md(spec, engine, nullptr);
    const auto& s = run.series;
    ts.push_back(s.t);
    Ts.push_back(s.T);
    fraction.resize(s.t.size(), 0.0);
    for (std::size_t i = 0; i < s.t.size(); ++i) fraction[i] += s.mode_energy_fraction[i] / seeds;
    // Collisions per disk and time over each interval against Enskog's at the interval's mean
    // sqrt(T), from 0.25 t0 to t0.
    const auto& rate = s.engine[1].second;
    Mean member_collisions, member_losses;
    for (std::size_t i = 1; i < s.t.size(); ++i) {
      if (s.t[i - 1] < 0.25 * h.theory || s.t[i] > h.theory) continue;
      const double root_T = 0.5 * (std::sqrt(s.T[i - 1]) + std::sqrt(s.T[i]));
      member_collisions.add(rate[i] /
                            (enskog_collision_frequency(n, phi, 1.0) * root_T * (1.0 - a2 / 16.0)));
      const double zeta = -std::log(s.T[i] / s.T[i - 1]) / (s.t[i] - s.t[i - 1]);
      member_losses.add(zeta / rate[i] / loss_theory);
    }
    collisions.add(member_collisions.mean());
    losses.add(member_losses.mean());
  }
  h.collision_ratio = collisions.mean();
  h.collision_ratio_error = collisions.error();
  h.loss_ratio = losses.mean();
  h.loss_ratio_error = losses.error();
  h.window = compare::homogeneous_window(ts.front(), fraction, 0.01, spec.t_end);
  h.from_start = compare::fit_haff_ensemble(ts, Ts, 0.0, h.window.t_max);
  h.after_transient = compare::fit_haff_ensemble(ts, Ts, 0.25 * h.theory, h.window.t_max);
  return h;
}

void print_haff_header() {
  std::printf(
      "| r | phi | disks x seeds (box, L/L_c) | window | t0 from 0 | from 0.25 t0 | Enskog + "
      "Sonine | deviation from 0 | from 0.25 t0 | collisions / Enskog (1 - a2/16) | cooling per "
      "collision / theory |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
}

HaffMeasurement print_haff(const ParticleScene& scene, int seeds) {
  const HaffMeasurement h = measure_haff(scene, seeds);
  const double d0 = h.from_start.t0 / h.theory - 1.0, d1 = h.after_transient.t0 / h.theory - 1.0;
  std::printf(
      "| %.2f | %.3f | %lld x %d (%.0f sigma, %.2f) | [0, %.1f] | %.2f ± %.2f | %.2f ± %.2f | "
      "%.2f | %+.2f ± %.2f %% | %+.2f ± %.2f %% | %.4f ± %.4f | %.4f ± %.4f |\n",
      scene.restitution, scene.area_fraction, scene.particles, seeds, scene.box_width,
      hydro::shear_cutoff_mode(scene.physics()), h.window.t_max, h.from_start.t0,
      h.from_start.t0_error, h.after_transient.t0, h.after_transient.t0_error, h.theory, 100 * d0,
      100 * h.from_start.t0_error / h.theory, 100 * d1, 100 * h.after_transient.t0_error / h.theory,
      h.collision_ratio, h.collision_ratio_error, h.loss_ratio, h.loss_ratio_error);
  std::fflush(stdout);
  ::testing::Test::RecordProperty(
      "haff_t0_r" + std::to_string(scene.restitution) + "_phi" +
          std::to_string(scene.area_fraction) + "_N" + std::to_string(scene.particles),
      std::to_string(h.from_start.t0) + " +- " + std::to_string(h.from_start.t0_error));
  return h;
}

// Issue 13's tolerance, 1 %, on the fit from t = 0 as the summary's md.haff_t0_measured makes
// it: met at r = 0.98 at phi = 0.05.
TEST(SlowEventDrivenPhysics, HaffTimeAtRPoint98WithinOnePercentOfEnskogWithSonine) {
  print_haff_header();
  const HaffMeasurement h = print_haff(square_box(20000, 0.05, 0.98), 8);
  EXPECT_NEAR(h.from_start.t0 / h.theory, 1.0, 0.01);
}

// At r = 0.9 and phi = 0.05 the measured t0 is 1.0-1.6 % above the theory (docs/physics.md §13),
// more in larger boxes: velocity correlations that Enskog theory leaves out, growing with the
// density and with the box beyond L_c. The test holds it at 2 %.
TEST(SlowEventDrivenPhysics, HaffTimeAtRPoint9WithinTwoPercentOfEnskogWithSonine) {
  print_haff_header();
  for (const long long disks : {20000LL, 5000LL}) {
    const HaffMeasurement h = print_haff(square_box(disks, 0.05, 0.9), disks == 20000 ? 8 : 24);
    EXPECT_NEAR(h.from_start.t0 / h.theory, 1.0, 0.02) << disks;
  }
}

// Where the theory's assumptions hold, a dilute gas in a box below L_c (half of it: no mode
// grows), the 1 % of issue 13 holds at r = 0.9: phi = 0.01 and 0.02, with about 10^6 disk runs
// each so that the standard error is below 0.1 %. phi = 0.05 in the same kind of box is printed
// beside them for the trend with density (not held to 1 %).
TEST(SlowEventDrivenPhysics, HaffTimeAtRPoint9WithinOnePercentOfEnskogWithSonineWhenDilute) {
  print_haff_header();
  for (const double phi : {0.01, 0.02, 0.05}) {
    const ParticleScene scene = square_box_of_critical(0.5, phi, 0.9);
    ASSERT_EQ(scene.shear_unstable_modes(), 0) << phi;
    const int seeds = int(std::lround(1e6 / double(scene.particles)));
    const HaffMeasurement h = print_haff(scene, seeds);
    if (phi <= 0.02) {
      EXPECT_NEAR(h.from_start.t0 / h.theory, 1.0, 0.01) << phi;
    }
  }
}

}  // namespace
}  // namespace granvv::md
