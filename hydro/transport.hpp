#pragma once
// Constitutive kernels of the dilute 2D granular gas in the paper's scaling
// (Efrati, Livne & Meerson 2005, Eqs. 1-2). Pure functions, one formula each.
#include <cmath>

#include "hydro/physics.hpp"

namespace granvv::hydro {

// Ideal-gas pressure p = n T (T is the thermal energy per particle in 2D).
inline double pressure(double n, double T) {
  return n * T;
}

// Longitudinal viscosity in P = -nT + (K/4) T^{1/2} dv/dx. In 2D the xy shear viscosity
// has the same coefficient, so it also drives the transverse velocity v_y(x).
inline double viscosity(const Physics& p, double T) {
  return 0.25 * p.K * std::sqrt(T);
}

// Heat conductivity in K d/dx(T^{1/2} dT/dx).
inline double conductivity(const Physics& p, double T) {
  return p.K * std::sqrt(T);
}

// Adiabatic sound speed: in 2D T ~ n along an adiabat (gamma = 2), so c^2 = dp/dn = 2T.
inline double sound_speed(double T) {
  return std::sqrt(2.0 * T);
}

}  // namespace granvv::hydro
