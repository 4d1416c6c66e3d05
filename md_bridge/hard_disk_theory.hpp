#pragma once
// Known answers of the hard-disk gas that the event-driven engine is checked against
// (docs/physics.md §10, §13), as pure functions (sigma = m = 1, T per particle as in §4).
#include "md_bridge/particle_scene.hpp"

namespace granvv::md {

// Compressibility factor Z = p / (n T) of the elastic hard-disk fluid at area fraction phi.
// Henderson (Mol. Phys. 30, 971 (1975)): Z = (1 + phi^2/8) / (1 - phi)^2, i.e. 1 + 2 phi chi
// with the chi of hydro/enskog_factors.hpp.
double henderson_compressibility(double phi);
// Enskog's compressibility factor of the scene's inelastic hard disks, Z = p / (n T) =
// 1 + (1 + r) phi chi(phi) at its area fraction phi and restitution r (Garzo & Dufty 1999;
// hydro/enskog_factors.hpp, the pressure factor F_p): what the measured P/(n T) of a homogeneous
// box is compared with. Henderson's Z at r = 1.
double enskog_compressibility(const ParticleScene& s);
// Luding (Phys. Rev. E 63, 042201 (2001)), Henderson's contact value with a fourth-order
// correction: Z = 1 + 2 phi g4, g4 = (1 - 7 phi/16)/(1 - phi)^2 - phi^3 / (128 (1 - phi)^4).
double luding_compressibility(double phi);
// Liu (arXiv:2010.10624 (2020), Eq. 1, its stable-fluid branch):
// Z = (1 + phi^2/8 + phi^3/18 - 4 phi^4/21) / (1 - phi)^2.
double liu_compressibility(double phi);

// The first Sonine coefficient a2 of the homogeneous cooling state of smooth inelastic disks
// (van Noije & Ernst, Granular Matter 1, 57 (1998), d = 2):
//   a2 = 16 (1 - r)(1 - 2 r^2) / (57 - 25 r + 30 r^2 (1 - r)),
// -0.0269 at r = 0.9, -0.0089 at r = 0.98. The cooling rate is the Maxwellian one times
// (1 + 3 a2 / 16).
double sonine_a2(double restitution);
// The Haff time of the scene with Enskog's chi(phi) and the Sonine correction:
// haff_time_md(s, chi) / (1 + 3 a2 / 16).
double haff_time_sonine_md(const ParticleScene& s);

// Enskog's collision frequency per disk, nu = 2 sqrt(pi) n chi(phi) sqrt(T) (docs/physics.md §10).
double enskog_collision_frequency(double number_density, double area_fraction, double T);

}  // namespace granvv::md
