#pragma once
// The Navier-Stokes transport of a dilute gas of smooth inelastic hard disks (d = 2) with
// constant restitution r, in the standard first Sonine approximation (Brey, Dufty, Kim &
// Santos, PRE 58, 4638 (1998) for d = 3; Garzo & Dufty, PRE 59, 5895 (1999) for any d; the
// d-dimensional forms as collected by Garzo, Santos & Montanero, Physica A 376, 94 (2007)),
// as pure functions of r (docs/physics.md §9, "The garzo_dufty closure"). Each coefficient is
// reduced by the elastic dilute value of hard disks: eta* = eta/eta0, kappa* = kappa/kappa0,
// mu* = n mu/(T kappa0), with eta0 = sqrt(m T/pi)/(2 sigma), kappa0 = 4 eta0/m (k_B = 1), and
// the rates by the elastic collision frequency nu0 = p/eta0:
//   a2     = 16 (1-r)(1-2r^2) / (9 + 24d - r(41 - 8d) + 30(1-r) r^2)     (van Noije & Ernst 1998)
//   zeta*  = (d+2)/(4d) (1 - r^2) (1 + 3 a2/16)                          cooling rate
//   nu_eta*   = 3/(4d) (1 - r + 2d/3) (1 + r) (1 - a2/32)
//   nu_kappa* = (1+r)/d [(d-1)/2 + 3(d+8)(1-r)/16 + (4 + 5d - 3(4-d) r) a2/512]
//   eta*   = 1 / (nu_eta* - zeta*/2)
//   kappa* = (d-1)/d (1 + 2 a2) / (nu_kappa* - 2 zeta*)
//   mu*    = 2 zeta* [kappa* + (d-1) a2/(d zeta*)] / (2 nu_kappa* - 3 zeta*)
// All are 1, 1, 0 (and zeta* = 0) at r = 1. The mu* numerator's a2 term is (d-1)/d, not
// (d-1)/(2d): it is the heat-flux moment of the density-gradient source, -(d+2) n T^2 a2/(2m),
// over that of the temperature-gradient source, -(d+2) n T^2 (1 + 2 a2)/(2m), times kappa*'s
// prefactor (docs/physics.md §9 gives the derivation).
namespace granvv::hydro::garzo_dufty {

inline constexpr double kDimension = 2.0;

struct DiluteCoefficients {
  double a2 = 0.0;            // fourth cumulant of the homogeneous cooling state
  double cooling = 0.0;       // zeta*
  double viscosity = 1.0;     // eta*
  double conductivity = 1.0;  // kappa*
  double mu = 0.0;            // mu*
};

inline double fourth_cumulant(double r) {
  const double d = kDimension;
  return 16.0 * (1.0 - r) * (1.0 - 2.0 * r * r) /
         (9.0 + 24.0 * d - r * (41.0 - 8.0 * d) + 30.0 * (1.0 - r) * r * r);
}

inline DiluteCoefficients dilute_coefficients(double r) {
  const double d = kDimension;
  DiluteCoefficients c;
  c.a2 = fourth_cumulant(r);
  c.cooling = (d + 2.0) / (4.0 * d) * (1.0 - r * r) * (1.0 + 3.0 * c.a2 / 16.0);
  const double nu_eta =
      3.0 / (4.0 * d) * (1.0 - r + 2.0 * d / 3.0) * (1.0 + r) * (1.0 - c.a2 / 32.0);
  const double nu_kappa = (1.0 + r) / d *
                          ((d - 1.0) / 2.0 + 3.0 * (d + 8.0) * (1.0 - r) / 16.0 +
                           (4.0 + 5.0 * d - 3.0 * (4.0 - d) * r) * c.a2 / 512.0);
  c.viscosity = 1.0 / (nu_eta - c.cooling / 2.0);
  c.conductivity = (d - 1.0) / d * (1.0 + 2.0 * c.a2) / (nu_kappa - 2.0 * c.cooling);
  // 2 [zeta* kappa* + (d-1) a2/d] / (2 nu_kappa* - 3 zeta*), the form without 1/zeta* (finite
  // at r = 1, where it is 0).
  c.mu = 2.0 * (c.cooling * c.conductivity + (d - 1.0) / d * c.a2) /
         (2.0 * nu_kappa - 3.0 * c.cooling);
  return c;
}

}  // namespace granvv::hydro::garzo_dufty
