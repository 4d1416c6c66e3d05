// The density modes of a particle ensemble and the hydro against linear theory
// (compare/density_mode_evolution.hpp), on synthetic binned fields with known modes.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "compare/density_mode_evolution.hpp"
#include "hydro/dilute_closure.hpp"
#include "hydro/linear_stability.hpp"

namespace {

using granvv::compare::density_modes;
using granvv::fields::FieldSeries;
using granvv::fields::FieldSnapshot;

constexpr int kBins = 32;
constexpr double kN0 = 0.05;

double centre(int b) {
  return -0.5 + (b + 0.5) / kBins;
}

// A particle member whose every snapshot has n = n0 (1 + a cos 2 pi x), v = 0, T = 1.
FieldSeries cosine_member(double a, int snapshots) {
  FieldSeries s = FieldSeries::on_bins(-0.5, 1.0, kBins);
  for (int i = 0; i < snapshots; ++i) {
    FieldSnapshot f;
    f.t = i;
    for (int b = 0; b < kBins; ++b) {
      f.x.push_back(centre(b));
      f.n.push_back(kN0 * (1.0 + a * std::cos(2 * M_PI * centre(b))));
      f.v_x.push_back(0.0);
      f.T.push_back(1.0);
    }
    s.snapshots.push_back(f);
  }
  return s;
}

TEST(DensityModeEvolution, RmsOverMembersWithTheErrorFromTheScatterOfThePower) {
  // Members with cosine amplitudes a1, a2 carry |n_1| = a/2: rms = sqrt((a1^2 + a2^2) / 8); the
  // scatter of |n_1|^2 over two members is |a1^2 - a2^2| / 8, so the rms's error is
  // 0.5 |a1^2 - a2^2| / 8 / rms. At collision clock 0 the linear theory returns each member's
  // own perturbation: the same rms. The hydro's n = 1 + h cos 2 pi x has |n_1| = h/2. Mode 2 is
  // empty. Tolerance: the 32-bin sums round at ~1e-16 per term.
  const double a1 = 0.02, a2 = 0.04, h = 0.03;
  const granvv::hydro::DiluteClosure closure({1e-2, 0.05});
  FieldSeries hydro = cosine_member(h, 1);
  for (double& n : hydro.snapshots[0].n) n /= kN0;
  const auto m = density_modes(2, closure, {cosine_member(a1, 1), cosine_member(a2, 1)}, hydro,
                               {{0, 0}}, {0.0}, kN0);
  const double rms = std::sqrt((a1 * a1 + a2 * a2) / 8.0);
  ASSERT_EQ(m.md.size(), 1u);
  ASSERT_EQ(m.md[0].size(), 2u);
  EXPECT_NEAR(m.md[0][0], rms, 1e-15);
  EXPECT_NEAR(m.md_error[0][0], 0.5 * (a2 * a2 - a1 * a1) / 8.0 / rms, 1e-14);
  EXPECT_NEAR(m.theory[0][0], rms, 1e-15);
  EXPECT_NEAR(m.hydro[0][0], h / 2.0, 1e-15);
  EXPECT_LT(m.md[0][1], 1e-15);
  EXPECT_LT(m.hydro[0][1], 1e-15);
  EXPECT_LT(m.theory[0][1], 1e-15);
  // The rates are the most unstable branch's of the closure, mode by mode.
  for (int k = 1; k <= 2; ++k) {
    EXPECT_EQ(m.theory_rate[k - 1], granvv::hydro::hcs_modes(closure, k)[0].rate.real());
  }
}

TEST(DensityModeEvolution, AnEigenmodeGrowsAtItsRateOnTheCollisionClock) {
  // A member seeded with the unstable eigenmode e of k = 1, (nu, w, theta) = Re(eps e
  // exp(2 pi i x)), evolves in linear theory to |nu_1(s)| = eps |e_nu| exp(Re lambda s) / 2. The
  // member's T_H and mean density differ from 1 only at O(eps^2), which shifts no k = 1
  // coefficient beyond ~eps^2 relative; the tolerance 1e-9 relative leaves room for that and for
  // the 32-bin sums.
  const double eps = 1e-6, s = 0.2;
  const granvv::hydro::DiluteClosure closure({1e-2, 0.05});
  const auto mode = granvv::hydro::hcs_modes(closure, 1)[0];
  FieldSeries member = FieldSeries::on_bins(-0.5, 1.0, kBins);
  FieldSnapshot f;
  for (int b = 0; b < kBins; ++b) {
    const std::complex<double> phase = std::exp(std::complex<double>(0, 2 * M_PI * centre(b)));
    f.x.push_back(centre(b));
    f.n.push_back(kN0 * (1.0 + eps * (mode.eigenvector[0] * phase).real()));
    f.v_x.push_back(eps * (mode.eigenvector[1] * phase).real());
    f.T.push_back(1.0 + eps * (mode.eigenvector[2] * phase).real());
  }
  member.snapshots = {f, f};
  FieldSeries hydro = cosine_member(0.0, 2);
  const auto m = density_modes(1, closure, {member}, hydro, {{0, 0}, {1, 1}}, {0.0, s}, kN0);
  const double at_start = eps * std::abs(mode.eigenvector[0]) / 2.0;
  EXPECT_NEAR(m.theory[0][0] / at_start, 1.0, 1e-9);
  EXPECT_NEAR(m.theory[1][0] / at_start / std::exp(mode.rate.real() * s), 1.0, 1e-9);
  EXPECT_GT(mode.rate.real() * s, 1.0);  // grown by more than e: the clock mattered
  // One member: its rms is its own |n_1|, with no scatter to give an error.
  EXPECT_NEAR(m.md[1][0] / at_start, 1.0, 1e-9);
  EXPECT_TRUE(std::isnan(m.md_error[1][0]));
}

}  // namespace
