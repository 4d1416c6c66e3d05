#include "md_bridge/hard_disk_collision.hpp"

#include <cmath>

namespace granvv::md {

double impact_restitution(double restitution, double approach_speed, double collapse_speed) {
  if (!(approach_speed < collapse_speed)) return restitution;
  return 1.0 - (1.0 - restitution) * std::pow(approach_speed / collapse_speed, 0.75);
}

ImpactRestitution collision_restitution(double restitution, double approach_speed, double since,
                                        const CollapseRule& rule) {
  if (approach_speed < rule.elastic_speed) return {1.0, ElasticBy::kSpeed};
  const bool slow = rule.contact_speed <= 0.0 || approach_speed < rule.contact_speed;
  if (since < rule.contact_duration && slow) return {1.0, ElasticBy::kContactDuration};
  return {impact_restitution(restitution, approach_speed, rule.collapse_speed), ElasticBy::kNone};
}

}  // namespace granvv::md
