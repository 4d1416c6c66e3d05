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
  double ratio_sum = 0.0, ratio_squares = 0.0;
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
    double sum = 0.0;
    int k = 0;
    for (std::size_t i = 1; i < s.t.size(); ++i) {
      if (s.t[i - 1] < 0.25 * h.theory || s.t[i] > h.theory) continue;
      const double root_T = 0.5 * (std::sqrt(s.T[i - 1]) + std::sqrt(s.T[i]));
      sum += rate[i] / (enskog_collision_frequency(n, 0.05, 1.0) * root_T * (1.0 - a2 / 16.0));
      ++k;
    }
    ratio_sum += sum / k;
    ratio_squares += (sum / k) * (sum / k);
  }
  h.collision_ratio = ratio_sum / seeds;
  h.collision_ratio_error =
      std::sqrt((ratio_squares / seeds - h.collision_ratio * h.collision_ratio) / (seeds - 1));
  h.window = compare::homogeneous_window(ts.front(), fraction, 0.01, spec.t_end);
  h.from_start = compare::fit_haff_ensemble(ts, Ts, 0.0, h.window.t_max);
  h.after_transient = compare::fit_haff_ensemble(ts, Ts, 0.25 * h.theory, h.window.t_max);
  return h;
}

// Tolerance: 1 % (issue 13), the fit from t = 0 as the summary's md.haff_t0_measured makes it.
TEST(SlowEventDrivenPhysics, HaffTimeWithinOnePercentOfEnskogWithSonineAtRPoint9AndPoint98) {
  std::printf(
      "| r | disks x seeds | window | t0 from 0 | from 0.25 t0 | Enskog + Sonine | "
      "deviation from 0 | from 0.25 t0 | collisions / Enskog (1 - a2/16) |\n"
      "|---|---|---|---|---|---|---|---|---|\n");
  for (const double r : {0.9, 0.98}) {
    const HaffMeasurement h = measure_haff(r, 20000, 8);
    const double d0 = h.from_start.t0 / h.theory - 1.0, d1 = h.after_transient.t0 / h.theory - 1.0;
    std::printf(
        "| %.2f | 20000 x 8 | [0, %.1f] | %.2f ± %.2f | %.2f ± %.2f | %.2f | %+.2f ± %.2f %% "
        "| %+.2f ± %.2f %% | %.4f ± %.4f |\n",
        r, h.window.t_max, h.from_start.t0, h.from_start.t0_error, h.after_transient.t0,
        h.after_transient.t0_error, h.theory, 100 * d0, 100 * h.from_start.t0_error / h.theory,
        100 * d1, 100 * h.after_transient.t0_error / h.theory, h.collision_ratio,
        h.collision_ratio_error);
    RecordProperty("haff_t0_" + std::to_string(r), std::to_string(h.from_start.t0) + " +- " +
                                                       std::to_string(h.from_start.t0_error));
    EXPECT_NEAR(h.from_start.t0 / h.theory, 1.0, 0.01) << r;
  }
}

}  // namespace
}  // namespace granvv::md
