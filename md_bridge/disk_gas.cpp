#include "md_bridge/disk_gas.hpp"

#include <lammps/library.h>

#include <stdexcept>

namespace granvv::md {

void create_disk_box(LammpsSession& lmp, double lx, double ly) {
  auto num = [](double x) { return lammps_number(x); };
  lmp.commands({"units lj", "dimension 2", "atom_style sphere", "atom_modify map array",
                "boundary p p p", "comm_modify vel yes",
                "region box block " + num(-0.5 * lx) + " " + num(0.5 * lx) + " " + num(-0.5 * ly) +
                    " " + num(0.5 * ly) + " -0.5 0.5",
                "create_box 1 box"});
}

void add_disks(LammpsSession& lmp, const ParticleSample& sample, const ContactModel& contact,
               long long total) {
  AtomBatch atoms;
  atoms.type.assign(sample.count(), 1);
  atoms.x = sample.x;
  atoms.v = sample.v;
  atoms.diameter.assign(sample.count(), 1.0);
  atoms.mass.assign(sample.count(), 1.0);
  atoms.id.assign(sample.id.begin(), sample.id.end());
  atoms.total = total;
  lmp.create_atoms(atoms);
  // Neighbour skin 0.3 sigma, checked every step: many contact overlaps' worth of travel.
  lmp.commands({pair_style_command(contact), pair_coeff_command(), timestep_command(contact),
                "neighbor 0.3 bin", "neigh_modify delay 0 every 1 check yes",
                "fix integrate all nve/sphere disc", "fix plane all enforce2d"});
}

void set_up_disk_gas(LammpsSession& lmp, double lx, double ly, const ParticleSample& sample,
                     const ContactModel& contact) {
  create_disk_box(lmp, lx, ly);
  add_disks(lmp, sample, contact, sample.count());
}

std::pair<std::array<double, 2>, std::array<double, 2>> lammps_subdomain(LammpsSession& lmp) {
  const auto* lo = static_cast<const double*>(lammps_extract_global(lmp.handle(), "sublo"));
  const auto* hi = static_cast<const double*>(lammps_extract_global(lmp.handle(), "subhi"));
  if (!lo || !hi) throw std::runtime_error("LAMMPS gave no subdomain bounds (sublo, subhi)");
  return {{lo[0], lo[1]}, {hi[0], hi[1]}};
}

}  // namespace granvv::md
