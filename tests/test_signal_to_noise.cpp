// The initial signal-to-noise of an imposed flow in its three forms (compare/signal_to_noise.hpp,
// docs/physics.md §8), against answers worked by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "compare/signal_to_noise.hpp"

namespace {

using granvv::compare::gradient_signal_to_noise;
using granvv::compare::mode_signal_to_noise;
using granvv::compare::profile_maximum;
using granvv::compare::velocity_signal_to_noise;

TEST(SignalToNoise, ProfileMaximumIsTakenOnTheCellCentres) {
  // sin 2 pi x peaks at x = 1/4, half a cell from the nearest centre x = 1/4 - 1/8192, where it
  // is cos(pi / 4096). Tolerance: one rounding of sin.
  EXPECT_NEAR(profile_maximum([](double x) { return std::sin(2 * M_PI * x); }),
              std::cos(M_PI / 4096), 1e-15);
  // A linear profile's largest centre is the last, 1/2 - 1/8192: exact in binary.
  EXPECT_EQ(profile_maximum([](double x) { return x; }), 0.5 - 1.0 / 8192);
}

TEST(SignalToNoise, VelocityFormIsTheLargestSpeedOverTheNoiseOfABinMean) {
  // n0 = 0.5, Ly = 8, Lx = 10 in 5 bins: l = 2, n0 Ly l = 8, noise 1/sqrt(8) (one rounding).
  const double a = -0.3;
  const auto s = velocity_signal_to_noise([&](double x) { return a * std::sin(2 * M_PI * x); }, 0.5,
                                          8.0, 10.0, 5);
  EXPECT_NEAR(s.noise, 1.0 / std::sqrt(8.0), 1e-16);
  EXPECT_NEAR(s.signal, 0.3 * std::cos(M_PI / 4096), 1e-15);
  EXPECT_NEAR(s.ratio(), 0.3 * std::cos(M_PI / 4096) * std::sqrt(8.0), 1e-14);
  // No flow: signal 0.
  EXPECT_EQ(velocity_signal_to_noise([](double) { return 0.0; }, 0.5, 8.0, 10.0, 5).signal, 0.0);
}

TEST(SignalToNoise, GradientFormComparesWithTheNoiseOnTheShortestUnstableWavelength) {
  // k_max = 4, N = 100: noise 4 sqrt(4/100) = 0.8 (sqrt(0.04) rounds once).
  const auto s =
      gradient_signal_to_noise([](double x) { return 2.0 * std::cos(2 * M_PI * x); }, 4, 100);
  EXPECT_NEAR(s.noise, 0.8, 1e-15);
  EXPECT_NEAR(s.signal, 2.0 * std::cos(M_PI / 4096), 1e-15);  // |cos| peaks half a cell off 0
  // Without a smooth imposed velocity: signal 0; without unstable modes: NaN noise and ratio.
  EXPECT_EQ(gradient_signal_to_noise({}, 4, 100).signal, 0.0);
  EXPECT_EQ(gradient_signal_to_noise({}, 4, 100).ratio(), 0.0);
  EXPECT_TRUE(std::isnan(gradient_signal_to_noise({}, 0, 100).noise));
  EXPECT_TRUE(std::isnan(gradient_signal_to_noise({}, 0, 100).ratio()));
}

TEST(SignalToNoise, ModeFormIsTheSineAmplitudeOverItsThermalNoise) {
  // b1 of a sin 2 pi x + c cos 4 pi x + d is exactly |a| by the midpoint rule (discrete
  // orthogonality); 4096 summed terms leave ~1e-15 of rounding.
  const auto s = mode_signal_to_noise(
      [](double x) { return -0.25 * std::sin(2 * M_PI * x) + 0.1 * std::cos(4 * M_PI * x) + 3.0; },
      200);
  EXPECT_NEAR(s.signal, 0.25, 1e-14);
  EXPECT_NEAR(s.noise, 0.1, 1e-16);  // sqrt(2 / 200)
  EXPECT_NEAR(s.ratio(), 2.5, 1e-13);
}

}  // namespace
