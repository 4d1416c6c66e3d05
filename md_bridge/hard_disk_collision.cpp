#include "md_bridge/hard_disk_collision.hpp"

#include <cmath>

namespace granvv::md {

double impact_restitution(double restitution, double approach_speed, double collapse_speed) {
  if (!(approach_speed < collapse_speed)) return restitution;
  return 1.0 - (1.0 - restitution) * std::pow(approach_speed / collapse_speed, 0.75);
}

}  // namespace granvv::md
