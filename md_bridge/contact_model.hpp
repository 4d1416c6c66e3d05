#pragma once
// Contact law of the particle engine: the linear spring-dashpot of LAMMPS `pair_style
// gran/hooke` with friction switched off (docs/physics.md §5), mapped from a target restitution
// coefficient r. Pure functions, no LAMMPS: each is unit-tested against its formula.
//
// Normal force between two disks in contact (overlap xi = sigma - |r_ij| > 0, normal relative
// velocity v_n, positive when the disks separate):
//     F_n = kn xi - m_eff gamma_n v_n,      m_eff = m_i m_j / (m_i + m_j) = m/2,
// so xi'' = -omega0^2 xi - gamma_n xi' with omega0^2 = kn/m_eff. A head-on collision lasts
// tc = pi / sqrt(omega0^2 - gamma_n^2/4) and leaves with r = exp(-gamma_n tc / 2); inverted,
//     gamma_n = -2 ln r sqrt(kn/m_eff) / sqrt(pi^2 + ln^2 r)
// (Schaefer, Dippel & Wolf, J. Phys. I France 6, 5 (1996); Silbert et al., PRE 64, 051302
// (2001), whose model LAMMPS' gran/hooke implements).
//
// LAMMPS argument order and units, read in the LAMMPS source and docs (doc/src/pair_gran.rst,
// src/GRANULAR/pair_gran_hooke.cpp and pair_gran_hooke_history.cpp::settings(), 2021-22
// versions): `pair_style gran/hooke Kn Kt gamma_n gamma_t xmu dampflag [limit_damping]`.
// Kn is force/distance; gamma_n is 1/time: the code computes
//     damp = meff*gamman*vnnr*rsqinv;  ccel = kn*(radsum-r)*rinv - damp;
// i.e. exactly F_n above with meff = mi*mj/(mi+mj) taken from the per-atom rmass, so
// gamma_n is the rate of the equation of motion (not a force/velocity coefficient).
// Traps: Kt = NULL means 2/7 Kn and gamma_t = NULL means gamma_n/2 (friction silently on),
// so they are written as 0 with xmu = 0 and dampflag = 0; `limit_damping` clips the
// attractive end of the contact (ccel < 0 -> 0) and raises r above the formula: not used.
// `pair_coeff * *` takes no coefficients for the gran styles.
#include <limits>
#include <string>

#include "md_bridge/particle_scene.hpp"

namespace granvv::md {

// What the caller asks for (MD units: sigma, m, sqrt(T0/m)). The case's knobs (md.restitution,
// md.max_overlap, md.steps_per_contact: their defaults are the case keys') and the speed to
// resolve have no default here: they are unset (NaN, 0) until the caller sets them, and
// validate() refuses a spec that leaves one unset.
struct ContactSpec {
  static constexpr double kUnset = std::numeric_limits<double>::quiet_NaN();
  double restitution = kUnset;         // target normal restitution r in (0, 1]
  double mass = kDiskMass;             // m of each disk (> 0)
  double diameter = kDiskDiameter;     // sigma (> 0)
  double max_overlap = kUnset;         // delta_max, a length
  double max_relative_speed = kUnset;  // u_max: fastest relative normal speed to resolve
  int steps_per_contact = 0;           // n = tc/dt, at least 10
  // Correct gamma_n for the discrete integrator (see leapfrog_restitution); false gives the
  // continuum formula, whose r is low by O(1/n) (0.4966 for r = 0.5 at n = 30).
  bool discrete_correction = true;
};

// What LAMMPS gets.
struct ContactModel {
  double kn = 0.0;                  // normal stiffness (force/distance)
  double gamma_n = 0.0;             // normal damping rate (1/time) passed to gran/hooke
  double contact_time = 0.0;        // tc = pi / sqrt(kn/m_eff - gamma_n^2/4)
  double dt = 0.0;                  // time step tc / steps_per_contact
  double restitution = 1.0;         // target r
  double mass = kDiskMass;          // m of each disk
  double diameter = kDiskDiameter;  // sigma
  double gamma_n_continuum = 0.0;   // the continuum formula's gamma_n, for reference
};

// m_eff = m/2 for two equal masses.
double effective_mass(double mass);
// Continuum gamma_n for restitution r (formula above); 0 for r = 1.
double damping_for_restitution(double restitution, double kn, double m_eff);
// Continuum duration of a head-on contact, pi / sqrt(kn/m_eff - gamma_n^2/4).
double contact_duration(double kn, double gamma_n, double m_eff);
// Continuum restitution exp(-gamma_n tc / 2) (inverse of damping_for_restitution).
double restitution_for_damping(double gamma_n, double kn, double m_eff);
// Hard-disk limit: an undamped spring reaches the overlap u sqrt(m_eff/kn) (an upper bound
// for the damped one), so kn = m_eff (u_max/delta_max)^2 keeps every collision with relative
// normal speed <= u_max below delta_max.
double stiffness_for_overlap(double m_eff, double max_relative_speed, double max_overlap);
double undamped_max_overlap(double kn, double m_eff, double relative_speed);
// The time-discrete restitution of LAMMPS' velocity Verlet (fix nve/sphere). The force of step
// k uses the overlap xi_k and the half-step velocity (xi_k - xi_{k-1})/h, so inside a contact
// xi_{k+1} = (2 - omega0^2 h^2 - gamma h) xi_k - (1 - gamma h) xi_{k-1}, whose roots are rho
// e^{+-i theta}, rho = sqrt(1 - gamma h), cos theta = (2 - omega0^2 h^2 - gamma h) / (2 rho).
// Over a half oscillation (pi/theta steps) the amplitude falls by
//     r_h = rho^(pi/theta) = exp(pi ln(1 - gamma h) / (2 theta)),
// which tends to exp(-gamma tc/2) as h -> 0. Expanding rho and theta, ln r_h = ln r [1 + gamma
// h (1/2 - omega0^2/(4 omega^2))] + O(h^2), omega = pi/tc: low by O(gamma h) because the
// damping sees a velocity half a step old (r = 0.5 at n = 30: 0.4959); for weak damping the
// O(h^2) terms compete and r_h can be a hair high (r = 0.98: 0.980002). This is the restitution
// averaged over the phase at which a contact starts within a step; a single collision scatters
// around it by O(gamma h) (see restitution_calibration.hpp). Returns 0 where the discrete
// motion is not oscillatory.
double leapfrog_restitution(double gamma_n, double kn, double m_eff, double dt);
// gamma_n such that leapfrog_restitution(gamma_n, kn, m_eff, tc(gamma_n)/n) = r (bisection).
double leapfrog_damping_for_restitution(double restitution, double kn, double m_eff,
                                        int steps_per_contact);

// Throws std::invalid_argument naming the key (md.restitution, md.mass, md.diameter,
// md.max_overlap, md.max_relative_speed, md.steps_per_contact), the value and what is allowed.
void validate(const ContactSpec& spec);
// Throws std::invalid_argument unless every field is finite and the model can be integrated
// (kn > 0, gamma_n >= 0 and underdamped, contact_time = its formula, dt > 0 with at least 10
// steps per contact, mass and diameter > 0, r in (0, 1]). Run before anything reaches LAMMPS.
void validate(const ContactModel& model);

// kn, gamma_n, tc, dt for the spec. kn carries a margin (1 + pi^2/(6 n^2))^2 over
// stiffness_for_overlap: started at an arbitrary phase within a step, the leapfrog
// oscillation has an amplitude up to about u/(omega0 cos(theta/2)) ~ (u/omega0)(1 + (pi/n)^2/8)
// (worst for r = 1: +1.25 % at n = 10, +0.14 % at n = 30), so the bound holds in LAMMPS.
ContactModel make_contact_model(const ContactSpec& spec);

// LAMMPS commands (units lj) for the model, every number with 17 significant digits:
// "pair_style gran/hooke KN 0 GAMMA_N 0 0 0" (Kt = gamma_t = xmu = dampflag = 0),
// "pair_coeff * *", "timestep DT".
std::string pair_style_command(const ContactModel& model);
std::string pair_coeff_command();
std::string timestep_command(const ContactModel& model);

// A finite double as LAMMPS reads it back exactly (%.17g); throws std::invalid_argument
// for NaN or infinity, so a bad number never reaches a command.
std::string lammps_number(double value);

}  // namespace granvv::md
