// The blow-up time from the last two samples of 1/n_max(t) (hydro/blowup_extrapolation.hpp) and
// the largest departure of the mean temperature from Haff's law (hydro/haff_deviation.hpp),
// against values worked out by hand. The inputs are dyadic, so the answers are exact.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "hydro/blowup_extrapolation.hpp"
#include "hydro/haff_deviation.hpp"

namespace {

using granvv::hydro::extrapolate_blowup_time;
using granvv::hydro::haff_max_relative_error;

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(BlowupExtrapolation, LinearInverseDensityExtrapolatesExactlyToItsRoot) {
  // 1/n_max = tau - t with tau = 2: t = {0, 1, 1.5} gives n_max = {0.5, 1, 2}; the line through
  // (1, 1) and (1.5, 0.5) reaches zero at 2: 1.5 + 0.5 * 0.5 / 0.5.
  EXPECT_EQ(extrapolate_blowup_time({0, 1, 1.5}, {0.5, 1, 2}), 2.0);
  // 1/n_max = (3 - t) / 4: t = {2, 2.5} gives n_max = {4, 8} -> tau = 3.
  EXPECT_EQ(extrapolate_blowup_time({2, 2.5}, {4, 8}), 3.0);
}

TEST(BlowupExtrapolation, OnlyTheLastTwoSamplesCount) {
  // Earlier samples off the line (pressure bends 1/n_max) do not move the estimate.
  EXPECT_EQ(extrapolate_blowup_time({0, 0.5, 1, 1.5}, {3, 0.25, 1, 2}), 2.0);
}

TEST(BlowupExtrapolation, NoEstimateWithoutAGrowingPeak) {
  EXPECT_FALSE(extrapolate_blowup_time({}, {}));
  EXPECT_FALSE(extrapolate_blowup_time({1}, {2}));
  EXPECT_FALSE(extrapolate_blowup_time({1, 2}, {2, 2}));     // flat
  EXPECT_FALSE(extrapolate_blowup_time({1, 2}, {2, 1}));     // falling
  EXPECT_FALSE(extrapolate_blowup_time({1, 2}, {1, 2, 3}));  // sizes differ
}

TEST(HaffDeviation, LargestRelativeErrorByHand) {
  // t0 = 1: T_H(t) = (1 + t)^{-2} = {1, 1/4, 1/16} at t = {0, 1, 3}. T_mean = {1, 3/8, 7/128}
  // is off by {0, +1/2, -1/8}: the largest |T / T_H - 1| is 1/2.
  EXPECT_EQ(haff_max_relative_error({0, 1, 3}, {1, 0.375, 0.0546875}, 1.0), 0.5);
  // Exactly Haff's law: 0.
  EXPECT_EQ(haff_max_relative_error({0, 1, 3}, {1, 0.25, 0.0625}, 1.0), 0.0);
  // No cooling (q = 0, t0 = inf): T_H = 1, so |T - 1|.
  EXPECT_EQ(haff_max_relative_error({0, 5}, {1, 0.75}, kInf), 0.25);
  // No samples: 0.
  EXPECT_EQ(haff_max_relative_error({}, {}, 1.0), 0.0);
}

}  // namespace
