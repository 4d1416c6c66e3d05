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

// `seeds` runs of `disks` disks at phi = 0.05, restitution r, in a square box, to 2 t0, sampled
// 100 times; the window ends where the ensemble-mean mode-energy fraction first exceeds 1 %
// (md.haff_mode_energy_fraction's default). The fit from t = 0 and the fit from 0.25 t0 (after
// the ~10 collisions per disk in which a2 builds up from the Maxwellian start).
HaffMeasurement measure_haff(double r, long long disks, int seeds) {
  MdRunSpec spec;
  spec.scene = scene_from_particles(disks, 0.05, std::sqrt(double(disks) * M_PI / 0.2), r);
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
  const double a2 = sonine_a2(r), n = spec.scene.number_density();
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
      member_collisions.add(
          rate[i] / (enskog_collision_frequency(n, 0.05, 1.0) * root_T * (1.0 - a2 / 16.0)));
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
      "| r | disks x seeds (box) | window | t0 from 0 | from 0.25 t0 | Enskog + Sonine | "
      "deviation from 0 | from 0.25 t0 | collisions / Enskog (1 - a2/16) | cooling per "
      "collision / theory |\n|---|---|---|---|---|---|---|---|---|---|\n");
}

HaffMeasurement print_haff(double r, long long disks, int seeds) {
  const HaffMeasurement h = measure_haff(r, disks, seeds);
  const double d0 = h.from_start.t0 / h.theory - 1.0, d1 = h.after_transient.t0 / h.theory - 1.0;
  std::printf(
      "| %.2f | %lld x %d (%.0f sigma) | [0, %.1f] | %.2f ± %.2f | %.2f ± %.2f | %.2f | "
      "%+.2f ± %.2f %% | %+.2f ± %.2f %% | %.4f ± %.4f | %.4f ± %.4f |\n",
      r, disks, seeds, std::sqrt(double(disks) * M_PI / 0.2), h.window.t_max, h.from_start.t0,
      h.from_start.t0_error, h.after_transient.t0, h.after_transient.t0_error, h.theory, 100 * d0,
      100 * h.from_start.t0_error / h.theory, 100 * d1, 100 * h.after_transient.t0_error / h.theory,
      h.collision_ratio, h.collision_ratio_error, h.loss_ratio, h.loss_ratio_error);
  std::fflush(stdout);
  ::testing::Test::RecordProperty(
      "haff_t0_" + std::to_string(r) + "_" + std::to_string(disks),
      std::to_string(h.from_start.t0) + " +- " + std::to_string(h.from_start.t0_error));
  return h;
}

// Issue 13's tolerance, 1 %, on the fit from t = 0 as the summary's md.haff_t0_measured makes
// it: met at r = 0.98.
TEST(SlowEventDrivenPhysics, HaffTimeAtRPoint98WithinOnePercentOfEnskogWithSonine) {
  print_haff_header();
  const HaffMeasurement h = print_haff(0.98, 20000, 8);
  EXPECT_NEAR(h.from_start.t0 / h.theory, 1.0, 0.01);
}

// At r = 0.9 the measured t0 is 1.4 % above the theory (docs/physics.md §13), in two box sizes:
// the test holds it at 2 %, and the 1 % of issue 13 is not met.
TEST(SlowEventDrivenPhysics, HaffTimeAtRPoint9WithinTwoPercentOfEnskogWithSonine) {
  print_haff_header();
  for (const long long disks : {20000LL, 5000LL}) {
    const HaffMeasurement h = print_haff(0.9, disks, disks == 20000 ? 8 : 24);
    EXPECT_NEAR(h.from_start.t0 / h.theory, 1.0, 0.02) << disks;
  }
}

}  // namespace
}  // namespace granvv::md
