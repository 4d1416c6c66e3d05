// The hydro's per-step scan for the largest element and its first index
// (hydro/largest_value.hpp) against a plain running scan: ties, NaNs, values at or below the
// floor, and lengths that fill the lanes, leave a tail, or are shorter than a lane.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "hydro/largest_value.hpp"

namespace granvv::hydro {
namespace {

LargestAt running_scan(const std::vector<double>& values, double floor) {
  LargestAt out{floor, 0};
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i] > out.value) out = {values[i], int(i)};
  }
  return out;
}

TEST(LargestValue, EqualsARunningScanOnTiesNansAndEveryLength) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> pick(0, 9);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  int with_ties = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int n = trial % 67;
    std::vector<double> v(std::size_t(n), 0.0);
    for (double& x : v) {
      const int k = pick(rng);
      // Few distinct values, so that the largest is often held by several elements.
      x = k == 0 ? nan : k == 1 ? -1.0 : k == 2 ? 0.0 : k == 3 ? -0.0 : 0.25 * k;
    }
    const double floor = trial % 3 == 0 ? 0.0 : trial % 3 == 1 ? 1.5 : -2.0;
    const LargestAt expected = running_scan(v, floor), got = largest_with_index(v, floor);
    ASSERT_EQ(got.value, expected.value) << "trial " << trial;
    ASSERT_EQ(got.at, expected.at) << "trial " << trial;
    ASSERT_EQ(largest_value(v, floor), expected.value);
    int holders = 0;
    for (double x : v) holders += x == expected.value;
    with_ties += holders > 1;
  }
  EXPECT_GT(with_ties, 1000);  // the ties the first-index rule decides were exercised
}

TEST(LargestValue, AllNanOrEmptyGivesTheFloorAtZero) {
  const std::vector<double> nans(20, std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(largest_with_index(nans).value, 0.0);
  EXPECT_EQ(largest_with_index(nans).at, 0);
  EXPECT_EQ(largest_with_index({}, 3.0).value, 3.0);
}

}  // namespace
}  // namespace granvv::hydro
