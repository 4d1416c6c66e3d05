#include "md_bridge/particle_scene.hpp"

#include <cmath>
#include <sstream>

#include "fields/constants.hpp"
#include "hydro/enskog_factors.hpp"
#include "hydro/linear_stability.hpp"

namespace granvv::md {
double ParticleScene::number_density() const {
  return particles / (box_length * box_width);
}

hydro::Physics ParticleScene::physics() const {
  const double n0 = number_density();
  return {2.0 / (std::sqrt(kPi) * box_length * n0), 0.5 * (1.0 - restitution)};
}

int ParticleScene::unstable_modes() const {
  return restitution < 1.0 ? hydro::clustering_unstable_modes(physics()) : 0;
}

int ParticleScene::shear_unstable_modes() const {
  return restitution < 1.0 ? hydro::shear_unstable_modes(physics()) : 0;
}

ParticleScene scene_from_scaled(double K, double q, double area_fraction, double box_width) {
  const double n0 = 4.0 * area_fraction / kPi;
  const double length = 2.0 / (std::sqrt(kPi) * n0 * K);
  ParticleScene s;
  s.particles = std::llround(n0 * length * box_width);
  s.box_width = box_width;
  s.box_length = s.particles / (n0 * box_width);
  s.area_fraction = area_fraction;
  s.restitution = 1.0 - 2.0 * q;
  return s;
}

ParticleScene scene_from_particles(long long particles, double area_fraction, double box_width,
                                   double restitution) {
  ParticleScene s;
  s.particles = particles;
  s.area_fraction = area_fraction;
  s.box_width = box_width;
  s.box_length = particles / (4.0 * area_fraction / kPi * box_width);
  s.restitution = restitution;
  return s;
}

double enskog_chi(double phi) {
  return hydro::enskog::chi(phi);
}

double haff_time_md(const ParticleScene& s, double chi) {
  const double r = s.restitution;
  const double zeta0 = std::sqrt(kPi) * (1.0 - r * r) * chi * s.number_density();
  return 2.0 / zeta0;
}

std::string scene_problem(const ParticleScene& s) {
  std::ostringstream why;
  if (!(s.area_fraction > 0.0 && s.area_fraction <= 0.5)) {
    why << "area fraction " << s.area_fraction
        << " is outside (0, 0.5]: disks cannot be placed without overlap beyond that";
  } else if (!(s.box_width >= 4.0)) {
    why << "box width Ly = " << s.box_width << " sigma is below 4 sigma";
  } else if (!(s.restitution > 0.0 && s.restitution <= 1.0)) {
    why << "restitution " << s.restitution << " is outside (0, 1]";
  } else if (s.particles < 2) {
    why << "the scene has " << s.particles << " particles; at least 2 are needed";
  } else if (s.particles > 2'147'483'647LL) {
    why << "the scene has " << s.particles
        << " particles, more than 32-bit particle IDs can number (2^31 - 1)";
  }
  return why.str();
}

double periodic_image(double x, double length) {
  if (!std::isfinite(x)) return x;
  const double half = 0.5 * length;
  if (x >= -half && x < half) return x;
  double y = x - length * std::floor((x + half) / length);
  // Rounding can land exactly on the upper edge (x just below an image of -L/2) or a hair
  // below the lower one.
  if (y >= half) y -= length;
  if (y < -half) y = -half;
  return y;
}

}  // namespace granvv::md
