#include "md_bridge/collision_virial.hpp"

#include <algorithm>

namespace granvv::md {

void CollisionVirialTally::clear() {
  sum_.clear();
  last_ = LocalVirial{};
}

void CollisionVirialTally::begin(std::size_t disks) {
  sum_.assign(2 * disks, 0.0);
}

void CollisionVirialTally::finish(double interval) {
  last_ = LocalVirial{};
  if (!(interval > 0.0)) return;
  const std::size_t particles = sum_.size() / 2;
  last_.xx.resize(particles);
  last_.yy.resize(particles);
  for (std::size_t k = 0; k < particles; ++k) {
    last_.xx[k] = sum_[2 * k] / interval;
    last_.yy[k] = sum_[2 * k + 1] / interval;
  }
}

}  // namespace granvv::md
