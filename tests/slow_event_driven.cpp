// The event-driven engine's elastic gas over 10^7 collisions (issue 13): energy to 1e-12
// relative, momentum to round-off, no overlap beyond 1e-9 sigma, dilute and dense. The default
// suite runs 5e5 of each (tests/test_event_driven_engine.cpp).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "support/elastic_gas.hpp"

namespace {

std::string scientific(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3e", x);
  return text;
}

void check(double area_fraction) {
  const auto drift = granvv::testing::run_elastic_gas(area_fraction, 10'000'000);
  EXPECT_LT(drift.energy, 1e-12);
  EXPECT_LT(drift.momentum, 1e-14);
  EXPECT_GE(drift.closest, 1.0 - 1e-9);
  ::testing::Test::RecordProperty("energy_drift", scientific(drift.energy));
  ::testing::Test::RecordProperty("momentum_drift", scientific(drift.momentum));
  ::testing::Test::RecordProperty("closest", scientific(drift.closest - 1.0));
}

TEST(SlowEventDriven, TenMillionElasticCollisionsDilute) {
  check(0.05);
}
TEST(SlowEventDriven, TenMillionElasticCollisionsDense) {
  check(0.4);
}

}  // namespace
