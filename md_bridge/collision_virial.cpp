#include "md_bridge/collision_virial.hpp"

#include <algorithm>

namespace granvv::md {

void CollisionVirialTally::clear() {
  sum_.clear();
  last_ = LocalVirial{};
}

void CollisionVirialTally::begin(std::size_t disks) {
  sum_.assign(kPerParticle * disks, 0.0);
}

void CollisionVirialTally::finish(double interval) {
  last_ = LocalVirial{};
  if (!(interval > 0.0)) return;
  const std::size_t particles = sum_.size() / kPerParticle;
  last_.xx.resize(particles);
  last_.yy.resize(particles);
  last_.energy_flux_x.resize(particles);
  for (std::size_t k = 0; k < particles; ++k) {
    last_.xx[k] = sum_[kPerParticle * k] / interval;
    last_.yy[k] = sum_[kPerParticle * k + 1] / interval;
    last_.energy_flux_x[k] = sum_[kPerParticle * k + 2] / interval;
  }
}

}  // namespace granvv::md
