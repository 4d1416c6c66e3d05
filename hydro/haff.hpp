#pragma once
// Homogeneous cooling state (HCS) of the scaled granular hydrodynamics of
// Efrati, Livne & Meerson, PRL 94, 088001 (2005). With n = 1 and v = 0, Eq. (2) reduces to
// dT/dt = -Lambda(1, T) = -c T^{3/2} (dilute closure: c = 8q/K), whose solution with T(0) = 1
// is Haff's law T_H(t) = (1 + t/t0)^{-2}, t0 = 2/c (dilute: K/(4q), paper, paragraph after
// Eq. (2)).

#include <cmath>

#include "hydro/closure.hpp"
#include "hydro/physics.hpp"

namespace granvv::hydro {

// Haff time t0 of the closure: 1/t0 is the initial cooling rate of the thermal speed T^{1/2}.
// +inf for an elastic gas (no cooling).
double haff_time_scale(const Closure& closure);
// The same for the paper's dilute closure: t0 = K/(4q).
double haff_time_scale(const Physics& physics);

// Haff's law T_H(t) = (1 + t/t0)^{-2}, for t > -t0. t0 = +inf gives T_H = 1.
double haff_temperature(double t, double t0);

// Collision clock s(t) = int_0^t T_H^{1/2}(t') dt' = t0 ln(1 + t/t0): time counted in units of
// the (scaled) mean free time, which grows as T_H^{-1/2}. The HCS-linearised Eqs. (1)-(2) have
// constant coefficients in s, so a mode exp(lambda s) grows algebraically,
// exp(lambda s) = (1 + t/t0)^{lambda t0}. Returns t for t0 = +inf.
double collision_clock(double t, double t0);

// Exact solution of dT/dt = -c n T^{3/2} at frozen density n, after a time dt:
// T / (1 + c n sqrt(T) dt / 2)^2. Used for operator-split cooling (dilute closure: c = 8q/K);
// with n = 1, T = 1 it reproduces Haff's law. Inline: it runs once per cell and half step.
inline double cool_exactly(double T, double n, double c, double dt) {
  // d(T^{-1/2})/dt = c n / 2, so T^{-1/2} grows linearly in time.
  const double g = 1.0 + 0.5 * c * n * std::sqrt(T) * dt;
  return T / (g * g);
}

}  // namespace granvv::hydro
