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

void CollisionVirialTally::finish(const std::vector<int>& id, double interval) {
  last_ = LocalVirial{};
  if (!(interval > 0.0) || sum_.size() != 2 * id.size()) return;
  last_.xx.assign(id.size(), 0.0);
  last_.yy.assign(id.size(), 0.0);
  for (std::size_t k = 0; k < id.size(); ++k) {
    last_.xx[std::size_t(id[k])] = sum_[2 * k] / interval;
    last_.yy[std::size_t(id[k])] = sum_[2 * k + 1] / interval;
  }
}

}  // namespace granvv::md
