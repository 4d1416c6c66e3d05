#include "compare/transport_coefficients.hpp"

#include <cmath>
#include <stdexcept>

#include "fields/constants.hpp"

namespace granvv::compare {
namespace {

hydro::CellCoefficients coefficients_at(const hydro::Closure& closure, double n, double T) {
  hydro::CellCoefficients c;
  closure.cell_coefficients({n}, {T}, c);
  return c;
}

double relative_shear_viscosity(const hydro::Closure& closure, double K, double n, double T) {
  return coefficients_at(closure, n, T).shear_viscosity[0] / scaled_elastic_shear_viscosity(K, T);
}

double relative_conductivity(const hydro::Closure& closure, double K, double n, double T) {
  return coefficients_at(closure, n, T).conductivity[0] / scaled_elastic_conductivity(K, T);
}

// kappa - mu n / T over kappa0.
double relative_effective_conductivity(const hydro::Closure& closure, double K, double n,
                                       double T) {
  const hydro::CellCoefficients c = coefficients_at(closure, n, T);
  return (c.conductivity[0] - c.mu[0] * n / T) / scaled_elastic_conductivity(K, T);
}

double relative_mu(const hydro::Closure& closure, double K, double n, double T) {
  return coefficients_at(closure, n, T).mu[0] / scaled_elastic_mu(K, n, T);
}

}  // namespace

double elastic_shear_viscosity(double mass, double temperature, double diameter) {
  return std::sqrt(mass * temperature / kPi) / (2.0 * diameter);
}

double elastic_conductivity(double mass, double temperature, double diameter) {
  return 4.0 * elastic_shear_viscosity(mass, temperature, diameter) / mass;
}

double elastic_mu(double mass, double temperature, double diameter, double number_density) {
  return temperature * elastic_conductivity(mass, temperature, diameter) / number_density;
}

double scaled_elastic_shear_viscosity(double K, double T) {
  return 0.25 * K * std::sqrt(T);
}

double scaled_elastic_conductivity(double K, double T) {
  return K * std::sqrt(T);
}

double scaled_elastic_mu(double K, double n, double T) {
  return T * scaled_elastic_conductivity(K, T) / n;
}

ScaledTransportUnits scaled_transport_units(double number_density, double box_length) {
  // stress n0 T0 = eta dv/dx with v in sqrt(T0/m), x in Lx; heat flux n0 T0 sqrt(T0/m) =
  // kappa dT/dx with T in T0 = mu dn/dx with n in n0 (m = T0 = 1).
  return {number_density * box_length, number_density * box_length, box_length};
}

const std::vector<TransportCoefficient>& transport_coefficients() {
  static const std::vector<TransportCoefficient> table = {
      {"shear_viscosity", {"hydro.viscosity_factor"}, &relative_shear_viscosity},
      {"effective_conductivity",
       {"hydro.conductivity_factor", "hydro.mu_factor"},
       &relative_effective_conductivity},
      {"conductivity", {"hydro.conductivity_factor"}, &relative_conductivity},
      {"mu", {"hydro.mu_factor"}, &relative_mu},
  };
  return table;
}

std::vector<std::string> transport_coefficient_names() {
  std::vector<std::string> names;
  for (const auto& c : transport_coefficients()) names.push_back(c.name);
  return names;
}

const TransportCoefficient& transport_coefficient(const std::string& name) {
  std::string known;
  for (const auto& c : transport_coefficients()) {
    if (c.name == name) return c;
    known += (known.empty() ? "" : ", ") + c.name;
  }
  throw std::invalid_argument("unknown transport coefficient \"" + name + "\" (known: " + known +
                              ")");
}

const std::vector<TransportPair>& transport_pairs() {
  // mu / mu0 from 0 to 0.4: the first-Sonine mu of dilute disks is 0.016 mu0 at r = 0.99, 0.16
  // at r = 0.9 and 0.33 at r = 0.8 (docs/physics.md §9). Not below 0, nor so far above that
  // p_n kappa - p_T mu <= 0 at the grid's smallest conductivity factor (0.5): the hydro refuses
  // both (its cooling state's clustering mode has no cut-off then).
  static const std::vector<TransportPair> table = {
      {"conductivity_and_mu", "conductivity", "mu", {0.0, 0.1, 0.2, 0.3, 0.4}},
  };
  return table;
}

const TransportPair* find_transport_pair(const std::string& name) {
  for (const auto& p : transport_pairs()) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

const std::vector<TransportFluxFit>& transport_flux_fits() {
  static const std::vector<TransportFluxFit> table = {
      {"heat_flux", {"conductivity", "mu"}, "burnett_heat_flux"},
  };
  return table;
}

const TransportFluxFit* find_transport_flux_fit(const std::string& name) {
  for (const auto& f : transport_flux_fits()) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

}  // namespace granvv::compare
