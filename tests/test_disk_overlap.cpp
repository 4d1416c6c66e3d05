// The deepest overlap of disks in a periodic box (md_bridge/disk_overlap.hpp), by which a resume
// refuses a soft-contact state no run made: known answers, and an all-pairs search as its oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "md_bridge/disk_overlap.hpp"

namespace granvv::md {
namespace {

// Every pair, nearest image: the definition the cell search must reproduce.
DiskOverlap every_pair(const std::vector<double>& xyz, double lx, double ly) {
  DiskOverlap deepest;
  const std::size_t n = xyz.size() / 3;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      double dx = xyz[3 * i] - xyz[3 * j], dy = xyz[3 * i + 1] - xyz[3 * j + 1];
      dx -= lx * std::round(dx / lx);
      dy -= ly * std::round(dy / ly);
      const double depth = 1.0 - std::hypot(dx, dy);
      if (depth > deepest.depth) deepest = {(long long)i, (long long)j, depth};
    }
  }
  return deepest;
}

TEST(DiskOverlap, FindsThePairAcrossThePeriodicEdge) {
  // A lattice of spacing 2 (no contacts) in a 10 x 6 box, with disk 3 moved to 0.3 of disk 0's
  // image across the edge x = -5 | 5 and disk 7 to 0.9 of disk 8: depths 0.7 and 0.1.
  std::vector<double> xyz;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 5; ++i) xyz.insert(xyz.end(), {-4.0 + 2 * i, -2.0 + 2 * j, 0.0});
  xyz[0] = -4.9;     // disk 0 at x = -4.9
  xyz[3 * 3] = 4.8;  // disk 3 at x = 4.8 - 10 = -5.2, 0.3 from disk 0
  xyz[3 * 3 + 1] = -2.0;
  xyz[3 * 7] = xyz[3 * 8] - 0.9;
  xyz[3 * 7 + 1] = xyz[3 * 8 + 1];
  const DiskOverlap o = deepest_overlap(xyz, 10.0, 6.0);
  EXPECT_EQ(o.first, 0);
  EXPECT_EQ(o.second, 3);
  EXPECT_NEAR(o.depth, 0.7, 1e-12);
}

TEST(DiskOverlap, NoOverlapIsDepthZero) {
  const std::vector<double> xyz = {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, -2.0, 2.0, 0.0};  // touching
  const DiskOverlap o = deepest_overlap(xyz, 8.0, 8.0);
  EXPECT_EQ(o.first, -1);
  EXPECT_EQ(o.depth, 0.0);
  EXPECT_EQ(deepest_overlap({}, 8.0, 8.0).first, -1);
}

TEST(DiskOverlap, AgreesWithEveryPairOnRandomGases) {
  // Narrow and wide boxes (2, 3 and many cells per side), positions also outside the box
  // (LAMMPS keeps atoms up to half its skin outside until it rebuilds its lists).
  std::mt19937_64 random(7);
  for (const auto& [lx, ly, n] : {std::tuple{2.5, 2.0, 6}, std::tuple{3.2, 40.0, 60},
                                  std::tuple{20.0, 7.0, 120}, std::tuple{300.0, 300.0, 40}}) {
    for (int trial = 0; trial < 20; ++trial) {
      std::uniform_real_distribution<double> x(-0.6 * lx, 0.6 * lx), y(-0.6 * ly, 0.6 * ly);
      std::vector<double> xyz;
      for (int i = 0; i < n; ++i) xyz.insert(xyz.end(), {x(random), y(random), 0.0});
      const DiskOverlap found = deepest_overlap(xyz, lx, ly), all = every_pair(xyz, lx, ly);
      ASSERT_EQ(found.first, all.first) << lx << " x " << ly << ", trial " << trial;
      ASSERT_EQ(found.second, all.second);
      ASSERT_NEAR(found.depth, all.depth, 1e-12);
    }
  }
}

TEST(DiskOverlap, RefusesWhatItCannotJudge) {
  EXPECT_THROW(deepest_overlap({0.0, 0.0, 0.0}, 1.5, 10.0), std::invalid_argument);
  EXPECT_THROW(deepest_overlap({NAN, 0.0, 0.0}, 10.0, 10.0), std::invalid_argument);
}

}  // namespace
}  // namespace granvv::md
