#pragma once
// Smooth hard disks of diameter sigma and equal mass: when two of them touch, and the normal
// restitution of their impact (docs/physics.md §10). Pure functions; the event-driven engine
// (event_driven_engine.hpp) schedules and applies them.
#include <limits>

namespace granvv::md {

constexpr double kNever = std::numeric_limits<double>::infinity();

// Time from now until two disks with relative position (dx, dy) and relative velocity
// (dvx, dvy) (of the first with respect to the second, minimum image) touch, or kNever if
// they are not approaching or miss. A pair that already overlaps (round-off) while
// approaching touches now (0), so that round-off can never let disks pass through each other.
double contact_time(double dx, double dy, double dvx, double dvy, double sigma);

// Restitution that goes to 1 at vanishing impact speed, the rule of Bizon, Shattuck, Swift,
// McCormick & Swinney, Phys. Rev. Lett. 80, 57 (1998): r(u) = 1 - (1 - r) (u / u0)^(3/4) below
// the impact speed u0 (the normal approach speed), r above it. It ends inelastic collapse (a
// sequence of ever-weaker impacts cannot lose a fixed fraction of its energy each time);
// u0 = 0 switches it off.
double impact_restitution(double restitution, double approach_speed, double collapse_speed);

// Two equal-mass disks at contact with normal (nx, ny) (unit, from the second to the first) and
// relative normal velocity u_n = (v1 - v2) . n < 0 (approaching): the normal impulse per unit
// mass that each receives, J = (1 + r) |u_n| / 2 (first: +J n, second: -J n).
inline double normal_impulse(double approach_speed, double r) {
  return 0.5 * (1.0 + r) * approach_speed;
}

}  // namespace granvv::md
