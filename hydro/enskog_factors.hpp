#pragma once
// The Enskog factors of the dense hard-disk gas (docs/physics.md §9), as pure functions of the
// local area fraction phi (and the restitution r), so that the closure, its tests and the docs
// read one definition:
//   chi(phi)  = (1 - 7 phi/16) / (1 - phi)^2                   Henderson's contact value
//   F_p       = 1 + (1 + r) phi chi                            p = n T F_p (Garzo & Dufty 1999)
//   F_eta     = 1/chi + 2 phi + (1 + 24/pi) phi^2 chi          longitudinal (shear + bulk)
//   F_eta_xy  = 1/chi + 2 phi + (1 + 8/pi) phi^2 chi           shear alone (eta_xy)
//   F_kappa   = 1/chi + 3 phi + (9/4 + 4/pi) phi^2 chi         conductivity
//   F_zeta    = chi                                            cooling
// (Gass 1971; Jenkins & Richman 1985), each the dilute coefficient's multiplier: all are 1 at
// phi = 0. F_eta_xy is F_eta without the bulk viscosity (16/pi) phi^2 chi, which acts on a 1D
// compression but not on the shear of v_y(x).
//
// With the internal energy T per particle the adiabat is d ln T = F_p d ln n, so the squared
// adiabatic sound speed is c^2 = d p/d n |_s = T (F_p + F_p^2 + phi dF_p/dphi).

#include "fields/constants.hpp"

namespace granvv::hydro::enskog {

// Past this area fraction hard disks freeze (fluid-solid coexistence begins near phi = 0.69;
// docs/physics.md §9) and the fluid closure no longer applies.
inline constexpr double kFreezingAreaFraction = 0.69;

inline double chi(double phi) {
  const double hole = 1.0 - phi;
  return (1.0 - 7.0 * phi / 16.0) / (hole * hole);
}
// d chi / d phi = (25 - 7 phi) / (16 (1 - phi)^3).
inline double chi_derivative(double phi) {
  const double hole = 1.0 - phi;
  return (25.0 - 7.0 * phi) / (16.0 * hole * hole * hole);
}

inline double pressure_factor(double phi, double r) {
  return 1.0 + (1.0 + r) * phi * chi(phi);
}
// d F_p / d phi = (1 + r) (chi + phi chi').
inline double pressure_factor_derivative(double phi, double r) {
  return (1.0 + r) * (chi(phi) + phi * chi_derivative(phi));
}
// c^2 / T = F_p + F_p^2 + phi dF_p/dphi (2 in the dilute limit: adiabatic index 2).
inline double sound_speed_factor(double phi, double r) {
  const double f = pressure_factor(phi, r);
  return f + f * f + phi * pressure_factor_derivative(phi, r);
}

inline double viscosity_factor(double phi) {
  const double x = chi(phi);
  return 1.0 / x + 2.0 * phi + (1.0 + 24.0 / kPi) * phi * phi * x;
}
inline double shear_viscosity_factor(double phi) {
  const double x = chi(phi);
  return 1.0 / x + 2.0 * phi + (1.0 + 8.0 / kPi) * phi * phi * x;
}
inline double conductivity_factor(double phi) {
  const double x = chi(phi);
  return 1.0 / x + 3.0 * phi + (9.0 / 4.0 + 4.0 / kPi) * phi * phi * x;
}
inline double cooling_factor(double phi) {
  return chi(phi);
}
// d F_zeta / d phi.
inline double cooling_factor_derivative(double phi) {
  return chi_derivative(phi);
}

}  // namespace granvv::hydro::enskog
