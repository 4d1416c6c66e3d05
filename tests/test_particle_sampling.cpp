// Parameter mapping (docs/physics.md §4) and particles sampled from fields: no overlaps, the
// density profile followed, Maxwellian velocities about the local mean, exact total momentum.
#include <gtest/gtest.h>

#include <cmath>

#include "hydro/dilute_closure.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "md_bridge/particle_sampler.hpp"
#include "md_bridge/particle_scene.hpp"

namespace granvv::md {
namespace {

TEST(ParticleScene, PaperTermsAndParticleTermsAreInverse) {
  const ParticleScene s = scene_from_scaled(4e-3, 0.05, 0.05, 20.0);
  // n0 = 4 phi / pi; Lx = 2 / (sqrt(pi) n0 K); N = n0 Lx Ly
  const double n0 = 4 * 0.05 / M_PI;
  EXPECT_NEAR(s.number_density(), n0, 1e-12);
  // N is rounded to an integer and Lx adjusted to keep phi: |dLx| <= 1/2 / (n0 Ly).
  EXPECT_NEAR(s.box_length, 2 / (std::sqrt(M_PI) * n0 * 4e-3), 0.5 / (n0 * 20.0));
  EXPECT_EQ(s.particles, std::llround(n0 * 2 / (std::sqrt(M_PI) * n0 * 4e-3) * 20.0));
  EXPECT_NEAR(s.restitution, 0.9, 1e-15);
  const ParticleScene back =
      scene_from_particles(s.particles, s.area_fraction, s.box_width, s.restitution);
  EXPECT_NEAR(back.box_length, s.box_length, 1e-9);
  EXPECT_NEAR(back.physics().K, 4e-3, 4e-3 * 1e-4);  // N rounded to an integer
  EXPECT_NEAR(back.physics().q, 0.05, 1e-15);
  // pi k K < sqrt(q): sqrt(0.05) / (pi 4e-3) = 17.8 -> 17 unstable modes
  EXPECT_EQ(back.unstable_modes(), 17);
}

TEST(ParticleScene, TimeScalesAndUnits) {
  const ParticleScene s = scene_from_particles(10000, 0.05, 40.0, 0.9);
  // Paper's Haff time K/(4q) in scaled units equals the dilute kinetic theory with
  // 1 - r^2 replaced by 4q (docs/physics.md §4): t0 = 2 / (sqrt(pi) 4q n0) MD units.
  const auto p = s.physics();
  const double paper_t0_md = s.md_time(p.K / (4 * p.q));
  EXPECT_NEAR(paper_t0_md, 2.0 / (std::sqrt(M_PI) * 4 * p.q * s.number_density()), 1e-9);
  const double dilute = haff_time_md(s, 1.0);
  EXPECT_NEAR(dilute / paper_t0_md, 4 * p.q / (1 - 0.81), 1e-12);  // 1 - r^2 vs 4q
  EXPECT_NEAR(enskog_chi(0.05), (1 - 7 * 0.05 / 16) / (0.95 * 0.95), 1e-15);
  EXPECT_GT(haff_time_md(s, 1.0) / haff_time_md(s, enskog_chi(0.05)), 1.07);  // ~8 %
}

TEST(ParticleScene, ImpossibleScenesAreNamed) {
  EXPECT_NE(scene_problem(scene_from_particles(1000, 0.6, 20, 0.9)).find("area fraction"),
            std::string::npos);
  EXPECT_NE(scene_problem(scene_from_particles(1000, 0.05, 2, 0.9)).find("box width"),
            std::string::npos);
  EXPECT_NE(scene_problem(scene_from_particles(1000, 0.05, 20, 1.2)).find("restitution"),
            std::string::npos);
  EXPECT_EQ(scene_problem(scene_from_particles(1000, 0.05, 20, 0.9)), "");
}

TEST(ParticleSampler, UniformGasHasNoOverlapsAndTheRightTemperatureAndMomentum) {
  const ParticleScene s = scene_from_particles(4000, 0.2, 20.0, 0.9);
  const auto sample = sample_particles(s, hydro::uniform_fields(), 7);
  ASSERT_EQ(sample.count(), 4000);
  // Brute-force minimum distance (periodic).
  double min_d2 = 1e300;
  for (long long i = 0; i < sample.count(); ++i) {
    for (long long j = i + 1; j < sample.count(); ++j) {
      double dx = sample.x[3 * i] - sample.x[3 * j], dy = sample.x[3 * i + 1] - sample.x[3 * j + 1];
      dx -= s.box_length * std::round(dx / s.box_length);
      dy -= s.box_width * std::round(dy / s.box_width);
      min_d2 = std::min(min_d2, dx * dx + dy * dy);
    }
  }
  EXPECT_GE(min_d2, 1.0);
  double px = 0, py = 0, k = 0;
  for (long long i = 0; i < sample.count(); ++i) {
    px += sample.v[3 * i], py += sample.v[3 * i + 1];
    k += 0.5 * (sample.v[3 * i] * sample.v[3 * i] + sample.v[3 * i + 1] * sample.v[3 * i + 1]);
  }
  EXPECT_NEAR(px, 0.0, 1e-9);
  EXPECT_NEAR(py, 0.0, 1e-9);
  // <T> = K / N: relative standard error 1/sqrt(N) = 1.6 %; 4 sigma.
  EXPECT_NEAR(k / 4000, 1.0, 4 / std::sqrt(4000.0));
}

TEST(ParticleSampler, FollowsTheDensityAndVelocityProfile) {
  const ParticleScene s = scene_from_particles(20000, 0.05, 20.0, 0.9);
  const auto f = hydro::find_initial_condition("random_modes")
                     .generate({{"random_modes", 3LL}, {"random_amplitude", 0.2}, {"seed", 1LL}},
                               hydro::DiluteClosure(hydro::Physics{}));
  const auto sample = sample_particles(s, f, 11);
  const int bins = 20;
  std::vector<double> count(bins, 0.0), vsum(bins, 0.0);
  for (long long i = 0; i < sample.count(); ++i) {
    const double xs = s.scaled_position(sample.x[3 * i]);
    const int b = std::min(bins - 1, int((xs + 0.5) * bins));
    count[b] += 1, vsum[b] += sample.v[3 * i];
  }
  double norm = 0;
  std::vector<double> expected(bins);
  for (int b = 0; b < bins; ++b) {
    for (int g = 0; g < 100; ++g) expected[b] += f.n(-0.5 + (b + (g + 0.5) / 100) / bins) / 100;
    norm += expected[b];
  }
  for (int b = 0; b < bins; ++b) {
    const double e = expected[b] / norm * 20000;
    EXPECT_NEAR(count[b], e, 5 * std::sqrt(e)) << "bin " << b;  // Poisson, 5 sigma
    const double xc = -0.5 + (b + 0.5) / bins;
    // Mean velocity per bin: thermal noise 1/sqrt(count), plus the profile's variation
    // across a bin (amplitude 0.2, 3 modes over 20 bins: < 0.1).
    EXPECT_NEAR(vsum[b] / count[b], f.v(xc), 5 / std::sqrt(count[b]) + 0.1) << "bin " << b;
  }
}

TEST(ParticleSampler, RefusesProfilesTooDenseToPlace) {
  const ParticleScene s = scene_from_particles(2000, 0.3, 10.0, 0.9);
  auto f = hydro::uniform_fields();
  f.n = [](double x) { return 1.0 + 0.9 * std::cos(2 * M_PI * x); };  // peak 1.9 x 0.3 > 0.5
  EXPECT_THROW(sample_particles(s, f, 1), std::invalid_argument);
}

}  // namespace
}  // namespace granvv::md
