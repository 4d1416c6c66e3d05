#include "md_bridge/hard_disk_theory.hpp"

#include <cmath>

#include "fields/constants.hpp"
#include "hydro/enskog_factors.hpp"

namespace granvv::md {

double henderson_compressibility(double phi) {
  return hydro::enskog::pressure_factor(phi, 1.0);
}

double enskog_compressibility(const ParticleScene& s) {
  return hydro::enskog::pressure_factor(s.area_fraction, s.restitution);
}

double luding_compressibility(double phi) {
  const double hole = 1.0 - phi;
  const double g4 = hydro::enskog::chi(phi) - phi * phi * phi / (128.0 * hole * hole * hole * hole);
  return 1.0 + 2.0 * phi * g4;
}

double liu_compressibility(double phi) {
  const double hole = 1.0 - phi, phi2 = phi * phi;
  return (1.0 + phi2 / 8.0 + phi2 * phi / 18.0 - 4.0 * phi2 * phi2 / 21.0) / (hole * hole);
}

double sonine_a2(double r) {
  return 16.0 * (1.0 - r) * (1.0 - 2.0 * r * r) / (57.0 - 25.0 * r + 30.0 * r * r * (1.0 - r));
}

double haff_time_sonine_md(const ParticleScene& s) {
  return haff_time_md(s, enskog_chi(s.area_fraction)) /
         (1.0 + 3.0 * sonine_a2(s.restitution) / 16.0);
}

double enskog_collision_frequency(double number_density, double area_fraction, double T) {
  return 2.0 * std::sqrt(kPi) * number_density * hydro::enskog::chi(area_fraction) * std::sqrt(T);
}

}  // namespace granvv::md
