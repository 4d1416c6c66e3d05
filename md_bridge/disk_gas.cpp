#include "md_bridge/disk_gas.hpp"

namespace granvv::md {

void set_up_disk_gas(LammpsSession& lmp, double lx, double ly, const ParticleSample& sample,
                     const ContactModel& contact) {
  auto num = [](double x) { return lammps_number(x); };
  lmp.commands({"units lj", "dimension 2", "atom_style sphere", "atom_modify map array",
                "boundary p p p", "comm_modify vel yes",
                "region box block " + num(-0.5 * lx) + " " + num(0.5 * lx) + " " + num(-0.5 * ly) +
                    " " + num(0.5 * ly) + " -0.5 0.5",
                "create_box 1 box"});
  AtomBatch atoms;
  atoms.type.assign(sample.count(), 1);
  atoms.x = sample.x;
  atoms.v = sample.v;
  atoms.diameter.assign(sample.count(), 1.0);
  atoms.mass.assign(sample.count(), 1.0);
  lmp.create_atoms(atoms);
  // Neighbour skin 0.3 sigma, checked every step: many contact overlaps' worth of travel.
  lmp.commands({pair_style_command(contact), pair_coeff_command(), timestep_command(contact),
                "neighbor 0.3 bin", "neigh_modify delay 0 every 1 check yes",
                "fix integrate all nve/sphere disc", "fix plane all enforce2d"});
}

}  // namespace granvv::md
