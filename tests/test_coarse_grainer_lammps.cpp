// Known answer on a real LAMMPS state: our coarse-grainer against LAMMPS's own
// `compute chunk/atom bin/1d` + `compute temp/chunk ... com yes` + `compute vcm/chunk` on the
// same atoms. LAMMPS divides the chunk's fluctuation energy by 2 N_b degrees of freedom (not
// 2 N_b - 2, docs/physics.md §10), so T_lammps = T_ours (N_b - 1) / N_b exactly.
#include <gtest/gtest.h>
#include <lammps/library.h>

#include <cmath>

#include "hydro/dilute_closure.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "md_bridge/coarse_grainer.hpp"
#include "md_bridge/contact_model.hpp"
#include "md_bridge/disk_gas.hpp"
#include "md_bridge/lammps_session.hpp"
#include "md_bridge/particle_sampler.hpp"
#include "support/contact_spec.hpp"

namespace granvv::md {
namespace {

TEST(CoarseGrainerAgainstLammps, BinsMatchChunkComputesOnTheSameState) {
  const ParticleScene scene = scene_from_particles(3000, 0.1, 30.0, 0.9);
  const auto single_mode = hydro::find_initial_condition("single_mode")
                               .generate({{"velocity_amplitude", -0.3}, {"mode", 1LL}},
                                         hydro::DiluteClosure(hydro::Physics{}));
  const auto sample = sample_particles(scene, single_mode, 3);
  const double lx = scene.box_length, ly = scene.box_width;
  const int bins = 25;

  LammpsSession lmp;
  ContactSpec c = granvv::testing::test_contact_spec();
  c.restitution = 0.9;
  set_up_disk_gas(lmp, lx, ly, sample, make_contact_model(c));
  auto num = [](double x) { return lammps_number(x); };
  lmp.run(500, true);  // collisions happen; atoms move, some across the periodic boundary
  lmp.commands({"compute cc all chunk/atom bin/1d x lower " + num(lx / bins) + " units box",
                "compute tc all temp/chunk cc temp com yes", "compute vc all vcm/chunk cc",
                "compute nc all property/chunk cc count", "run 0 post no"});

  CoarseGrainer grainer({-0.5 * lx, lx, -0.5 * ly, ly, bins, "bin", 0.0});
  const Moments m = grainer.accumulate(lmp.x()[0], lmp.v()[0], lmp.rmass(), lmp.nlocal());
  const fields::FieldSnapshot f = grainer.fields(m);

  auto* count = static_cast<double*>(
      lammps_extract_compute(lmp.handle(), "nc", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR));
  auto** temp = static_cast<double**>(
      lammps_extract_compute(lmp.handle(), "tc", LMP_STYLE_GLOBAL, LMP_TYPE_ARRAY));
  auto** vcm = static_cast<double**>(
      lammps_extract_compute(lmp.handle(), "vc", LMP_STYLE_GLOBAL, LMP_TYPE_ARRAY));
  ASSERT_NE(count, nullptr);
  ASSERT_NE(temp, nullptr);
  ASSERT_NE(vcm, nullptr);
  double total = 0.0;
  for (int b = 0; b < bins; ++b) {
    const double nb = f.count[b];
    total += nb;
    EXPECT_EQ(nb, count[b]) << "bin " << b;
    EXPECT_NEAR(f.n[b] * lx / bins * ly, nb, 1e-9);
    EXPECT_NEAR(f.v_x[b], vcm[b][0], 1e-12) << "bin " << b;
    EXPECT_NEAR(f.v_y[b], vcm[b][1], 1e-12) << "bin " << b;
    EXPECT_NEAR(f.T[b] * (nb - 1) / nb, temp[b][0], 1e-10 * temp[b][0]) << "bin " << b;
  }
  EXPECT_EQ(total, 3000.0);
}

}  // namespace
}  // namespace granvv::md
