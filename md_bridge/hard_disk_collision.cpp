#include "md_bridge/hard_disk_collision.hpp"

#include <cmath>

namespace granvv::md {

double contact_time(double dx, double dy, double dvx, double dvy, double sigma) {
  const double b = dx * dvx + dy * dvy;  // r . v < 0 when approaching
  if (b >= 0.0) return kNever;
  const double gap = dx * dx + dy * dy - sigma * sigma;
  if (gap <= 0.0) return 0.0;  // overlapping by round-off and approaching: collide now
  const double v2 = dvx * dvx + dvy * dvy;
  const double discriminant = b * b - v2 * gap;
  if (discriminant <= 0.0) return kNever;
  // The smaller root of v2 t^2 + 2 b t + gap = 0 in the form without cancellation.
  return gap / (-b + std::sqrt(discriminant));
}

double impact_restitution(double restitution, double approach_speed, double collapse_speed) {
  if (!(approach_speed < collapse_speed)) return restitution;
  return 1.0 - (1.0 - restitution) * std::pow(approach_speed / collapse_speed, 0.75);
}

}  // namespace granvv::md
