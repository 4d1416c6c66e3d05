#pragma once
// Smooth hard disks of diameter sigma and equal mass: when two of them touch, and the normal
// restitution of their impact (docs/physics.md §10). Pure functions; the event-driven engine
// (event_driven_engine.hpp) schedules and applies them.
#include <algorithm>
#include <cmath>
#include <limits>

namespace granvv::md {

constexpr double kNever = std::numeric_limits<double>::infinity();

// Two disks with relative position (dx, dy) and relative velocity (dvx, dvy) (of the first with
// respect to the second, minimum image) touch when v2 t^2 + 2 b t + gap = 0, b = r . v,
// gap = |r|^2 - sigma^2, v2 = |v|^2.
struct ContactQuadratic {
  double b, gap, discriminant;
  // Approaching (b < 0) and not missing (a real root). Positive discriminant whenever gap <= 0
  // and b < 0 (b^2 > 0 >= v2 gap): a pair that already overlaps (round-off) while approaching
  // touches, so that round-off can never let disks pass through each other.
  bool touches() const { return b < 0.0 && discriminant > 0.0; }
  // The smaller root in the form without cancellation; 0 for an overlap (gap <= 0). Meaningful
  // only if touches().
  double time() const { return std::max(gap, 0.0) / (std::sqrt(std::max(discriminant, 0.0)) - b); }
};

inline ContactQuadratic contact_quadratic(double dx, double dy, double dvx, double dvy,
                                          double sigma) {
  const double b = dx * dvx + dy * dvy;
  const double gap = dx * dx + dy * dy - sigma * sigma;
  const double v2 = dvx * dvx + dvy * dvy;
  return {b, gap, b * b - v2 * gap};
}

// Time from now until the two disks touch, or kNever if they are not approaching or miss.
// Without branches (whether a pair approaches is a coin toss that a branch would mispredict half
// the time). A disk paired with itself (r = 0, v = 0) never touches.
inline double contact_time(double dx, double dy, double dvx, double dvy, double sigma) {
  const ContactQuadratic q = contact_quadratic(dx, dy, dvx, dvy, sigma);
  const double root = q.time();
  return q.touches() ? root : kNever;
}

// Restitution that goes to 1 at vanishing impact speed, the rule of Bizon, Shattuck, Swift,
// McCormick & Swinney, Phys. Rev. Lett. 80, 57 (1998): r(u) = 1 - (1 - r) (u / u0)^(3/4) below
// the impact speed u0 (the normal approach speed), r above it. It ends inelastic collapse (a
// sequence of ever-weaker impacts cannot lose a fixed fraction of its energy each time);
// u0 = 0 switches it off.
double impact_restitution(double restitution, double approach_speed, double collapse_speed);

// The rules against inelastic collapse together (docs/physics.md §10), applied in this order:
// - elastic_speed (delta): an impact slower than delta is elastic (Ben-Naim, Chen, Doolen &
//   Redner, Phys. Rev. Lett. 83, 4069 (1999)). A packing under load whose impacts are all slower
//   than delta stops losing energy, so its collision rate stays finite (the Bizon rule alone
//   lets it cool to rest in finite time); 0 = off.
// - contact_duration (t_c): an impact within t_c of either disk's previous one is elastic (TC
//   model, Luding & McNamara, Granular Matter 1, 113 (1998)); 0 = off. With contact_speed
//   (u_c) > 0 only impacts slower than u_c: a fast impact is a binary collision of the gas,
//   whatever the interval, while a packing's disks collide slowly and often (the rule then
//   holds a loaded packing's collision rate near 1/t_c without touching the gas).
// - collapse_speed (u0): impact_restitution above.
struct CollapseRule {
  double collapse_speed = 0.0;
  double contact_duration = 0.0;
  double elastic_speed = 0.0;
  double contact_speed = 0.0;
};
// Which rule set the restitution of an impact (kNone: the scene's r, or the Bizon rule).
enum class ElasticBy { kNone, kSpeed, kContactDuration };
struct ImpactRestitution {
  double r;
  ElasticBy elastic_by;
};
// The restitution of an impact at normal approach speed u, `since` after the later of the two
// disks' previous impacts.
ImpactRestitution collision_restitution(double restitution, double approach_speed, double since,
                                        const CollapseRule& rule);

// Two equal-mass disks at contact with normal (nx, ny) (unit, from the second to the first) and
// relative normal velocity u_n = (v1 - v2) . n < 0 (approaching): the normal impulse per unit
// mass that each receives, J = (1 + r) |u_n| / 2 (first: +J n, second: -J n).
inline double normal_impulse(double approach_speed, double r) {
  return 0.5 * (1.0 + r) * approach_speed;
}

}  // namespace granvv::md
