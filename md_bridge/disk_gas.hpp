#pragma once
// The LAMMPS set-up of a 2D gas of smooth inelastic disks (sigma = m = 1) in the periodic box
// [-Lx/2, Lx/2) x [-Ly/2, Ly/2): atom_style sphere, gran/hooke with friction off, velocity
// Verlet for discs (fix nve/sphere disc) kept in the plane (fix enforce2d), ghost velocities
// communicated (needed by granular pairs, docs/physics.md §10).
#include <array>
#include <utility>

#include "md_bridge/contact_model.hpp"
#include "md_bridge/lammps_session.hpp"
#include "md_bridge/particle_sampler.hpp"

namespace granvv::md {

void set_up_disk_gas(LammpsSession& lmp, double box_length, double box_width,
                     const ParticleSample& sample, const ContactModel& contact);

// The same in two parts, for particles drawn after the box is decomposed: the box, then (with
// this rank's subdomain known, lammps_subdomain) the disks and their contact. A sample with IDs
// may differ from rank to rank; each rank keeps the disks of its own subdomain, and `total` is
// the number all ranks create together.
void create_disk_box(LammpsSession& lmp, double box_length, double box_width);
void add_disks(LammpsSession& lmp, const ParticleSample& sample, const ContactModel& contact,
               long long total);
// The lower and upper corners {x, y} of this rank's LAMMPS subdomain [lo, hi).
std::pair<std::array<double, 2>, std::array<double, 2>> lammps_subdomain(LammpsSession& lmp);

}  // namespace granvv::md
