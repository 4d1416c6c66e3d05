#pragma once
// The transport coefficients a scene can measure (docs/physics.md §14), each named as its key
// in summary.json's transport block, with the hydro.*_factor case keys that scale it together
// in the hydro and its value for a closure, divided by the elastic dilute value of the same
// coefficient for hard disks (Chapman-Enskog, first Sonine; k_B = 1):
//   eta0 = sqrt(m T / pi) / (2 sigma),   kappa0 = 4 eta0 / m,   mu0 = T kappa0 / n.
// In the hydro's scaled units (docs/physics.md §1) a viscosity is in n0 Lx sqrt(m T0), a
// conductivity in n0 Lx sqrt(T0 / m) and a mu (heat flux -mu dn/dx) in T0 Lx sqrt(T0 / m); with
// K = 2 / (sqrt(pi) sigma n0 Lx) the elastic values are eta0 = (K/4) T^(1/2),
// kappa0 = K T^(1/2), mu0 = K T^(3/2) / n, which are the dilute closure's eta and kappa.
#include <string>
#include <vector>

#include "hydro/closure.hpp"

namespace granvv::compare {

// The elastic dilute values in the disks' units (sigma, m, T in energy), and in scaled units.
double elastic_shear_viscosity(double mass, double temperature, double diameter);
double elastic_conductivity(double mass, double temperature, double diameter);
double elastic_mu(double mass, double temperature, double diameter, double number_density);
double scaled_elastic_shear_viscosity(double K, double T);
double scaled_elastic_conductivity(double K, double T);
double scaled_elastic_mu(double K, double n, double T);

// The units of the scaled coefficients in the disks' units (m = T0 = 1): multiply a scaled
// coefficient by these to have it in sigma, m, T0 units. n0 the mean number density, Lx the
// box length (docs/physics.md §4).
struct ScaledTransportUnits {
  double viscosity = 0.0, conductivity = 0.0, mu = 0.0;
};
ScaledTransportUnits scaled_transport_units(double number_density, double box_length);

struct TransportCoefficient {
  std::string name;  // the key in summary.json's transport block
  // The case keys of the factors the hydro is run with, all set to the same F: the coefficient
  // the closure gives times F (hydro/transport_factors.hpp).
  std::vector<std::string> factor_keys;
  // The closure's value at (n, T) in scaled units over the elastic dilute one there.
  double (*relative_value)(const hydro::Closure& closure, double K, double n, double T);
};

// Every coefficient a scene can measure: shear_viscosity (eta_xy), effective_conductivity
// (kappa - mu n / T, what a pressure-balanced mode sees: at pressure balance dn/dx =
// -(n/T) dT/dx; kappa and mu scaled together), conductivity (kappa alone, mu held at the
// closure's) and mu (mu alone, kappa held at the closure's; relative to mu0, which is 0 for a
// closure without mu).
const std::vector<TransportCoefficient>& transport_coefficients();
std::vector<std::string> transport_coefficient_names();
// Throws std::invalid_argument for an unknown name, listing the known ones.
const TransportCoefficient& transport_coefficient(const std::string& name);

// Two coefficients a scene measures jointly (compare/transport_pair_fit.hpp), named as
// compare.transport; each is reported under its own name. The hydro runs on a grid of the first
// coefficient's factor (compare.transport_factors) and of the second's value in units of its
// elastic dilute value, `second_values`, so that the grid spans from zero to beyond the
// coefficient's size at any restitution whatever the closure's own value (which must not be zero).
struct TransportPair {
  std::string name, first, second;
  std::vector<double> second_values;
};

// conductivity_and_mu: kappa and mu apart, from a mode that is not at pressure balance.
const std::vector<TransportPair>& transport_pairs();
// nullptr for a name that is no pair.
const TransportPair* find_transport_pair(const std::string& name);

// Coefficients measured at their definition from the particles' own fluxes, with no hydro in the
// fit (compare/heat_flux_fit.hpp), named as compare.transport; each is reported under its own
// name, `extra` (no closure has it: its closures' value is 0) beside the `coefficients`.
struct TransportFluxFit {
  std::string name;
  std::vector<std::string> coefficients;  // transport_coefficients() names
  std::string extra;
};

// heat_flux: conductivity and mu from the kinetic heat flux, beside the linear Burnett term
// (burnett_heat_flux, theta = beta rho / eta0^2).
const std::vector<TransportFluxFit>& transport_flux_fits();
// nullptr for a name that is no flux fit.
const TransportFluxFit* find_transport_flux_fit(const std::string& name);

}  // namespace granvv::compare
