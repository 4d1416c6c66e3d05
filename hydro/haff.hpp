#pragma once
// Homogeneous cooling state (HCS) of the scaled dilute granular hydrodynamics of
// Efrati, Livne & Meerson, PRL 94, 088001 (2005). With n = 1 and v = 0, Eq. (2) reduces to
// dT/dt = -(8q/K) T^{3/2}, whose solution with T(0) = 1 is Haff's law
// T_H(t) = (1 + t/t0)^{-2}, t0 = K/(4q) (paper, paragraph after Eq. (2)).

#include "hydro/physics.hpp"

namespace granvv::hydro {

// Haff time t0 = K/(4q): 1/t0 is the initial cooling rate of the thermal speed T^{1/2}.
// +inf for q = 0 (elastic gas, no cooling).
double haff_time_scale(const Physics& physics);

// Haff's law T_H(t) = (1 + t/t0)^{-2}, for t > -t0. t0 = +inf gives T_H = 1.
double haff_temperature(double t, double t0);

// Collision clock s(t) = int_0^t T_H^{1/2}(t') dt' = t0 ln(1 + t/t0): time counted in units of
// the (scaled) mean free time, which grows as T_H^{-1/2}. The HCS-linearised Eqs. (1)-(2) have
// constant coefficients in s, so a mode exp(lambda s) grows algebraically,
// exp(lambda s) = (1 + t/t0)^{lambda t0}. Returns t for t0 = +inf.
double collision_clock(double t, double t0);

// Coefficient c = 8q/K of the collisional loss term -c n^2 T^{3/2} of Eq. (2) (per unit n).
double cooling_rate_coefficient(const Physics& physics);

// Exact solution of dT/dt = -c n T^{3/2} at frozen density n, after a time dt:
// T / (1 + c n sqrt(T) dt / 2)^2. Used for operator-split cooling; with n = 1, c = 8q/K,
// T = 1 it reproduces Haff's law.
double cool_exactly(double T, double n, double c, double dt);

}  // namespace granvv::hydro
