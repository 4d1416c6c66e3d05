#pragma once
// The LAMMPS set-up of a 2D gas of smooth inelastic disks (sigma = m = 1) in the periodic box
// [-Lx/2, Lx/2) x [-Ly/2, Ly/2): atom_style sphere, gran/hooke with friction off, velocity
// Verlet for discs (fix nve/sphere disc) kept in the plane (fix enforce2d), ghost velocities
// communicated (needed by granular pairs, docs/physics.md §10).
#include "md_bridge/contact_model.hpp"
#include "md_bridge/lammps_session.hpp"
#include "md_bridge/particle_sampler.hpp"

namespace granvv::md {

void set_up_disk_gas(LammpsSession& lmp, double box_length, double box_width,
                     const ParticleSample& sample, const ContactModel& contact);

}  // namespace granvv::md
