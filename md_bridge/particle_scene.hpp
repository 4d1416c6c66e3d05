#pragma once
// The mapping between the paper's scaled description of a scene (K, q) and the particles
// that realise it (docs/physics.md §4), with sigma = m = T0 = 1: n0 sigma^2 = 4 phi / pi,
// Lx = 2 / (sqrt(pi) sigma n0 K), N = n0 Lx Ly, r = 1 - 2q. Every unit conversion between
// MD units (sigma, m, T0) and the hydro's scaled units lives here.
#include <string>

#include "hydro/physics.hpp"

namespace granvv::md {

// The disks' mass and diameter: the MD units themselves (sigma = m = 1).
inline constexpr double kDiskMass = 1.0;
inline constexpr double kDiskDiameter = 1.0;

struct ParticleScene {
  long long particles = 0;     // N
  double box_length = 0.0;     // Lx in sigma
  double box_width = 0.0;      // Ly in sigma
  double area_fraction = 0.0;  // phi = N pi sigma^2 / (4 Lx Ly)
  double restitution = 0.0;    // r

  double number_density() const;   // n0 sigma^2
  hydro::Physics physics() const;  // K, q
  // Clustering modes with pi k K < sqrt(q) (paper); shear modes with pi k K < 2 sqrt(q).
  int unstable_modes() const;
  int shear_unstable_modes() const;

  // Scaled (hydro) <-> MD units: t_md = t Lx (velocity unit sqrt(T0/m) = 1), x_md = x Lx,
  // n_md = n n0, v and T unchanged.
  double md_time(double scaled_time) const { return scaled_time * box_length; }
  double scaled_time(double md_time) const { return md_time / box_length; }
  double md_position(double scaled_x) const { return scaled_x * box_length; }
  double scaled_position(double md_x) const { return md_x / box_length; }
};

// x modulo length, into the box [-length/2, length/2) of every particle scene; non-finite x is
// returned unchanged.
double periodic_image(double x, double length);

// From the paper's terms: K, q, area fraction phi, box width Ly (sigma). N is rounded to the
// nearest integer and Lx adjusted so that phi is kept exactly.
ParticleScene scene_from_scaled(double K, double q, double area_fraction, double box_width);
// From particle terms: N, phi, Ly, r.
ParticleScene scene_from_particles(long long particles, double area_fraction, double box_width,
                                   double restitution);

// Enskog pair correlation at contact for hard disks, Henderson's form
// chi(phi) = (1 - 7 phi / 16) / (1 - phi)^2 (the hydro's, hydro/enskog_factors.hpp).
double enskog_chi(double area_fraction);

// Haff time t0 (MD units) of a homogeneous gas of smooth inelastic disks: the cooling rate
// zeta = sqrt(pi) (1 - r^2) chi n sigma sqrt(T/m) (docs/physics.md §4) gives T = T0 (1 + t/t0)^-2
// with t0 = 2 / zeta(T0). chi = 1 is the dilute limit the paper's 8q/K term uses
// (with 1 - r^2 ~ 4q).
double haff_time_md(const ParticleScene& s, double chi);

// Why this scene cannot be run (empty if it can): phi outside (0, 0.5], Ly < 4 sigma,
// r outside (0, 1], N < 2 or beyond what the machine holds.
std::string scene_problem(const ParticleScene& s);

}  // namespace granvv::md
