// Binary head-on collisions inside LAMMPS (md_bridge/restitution_calibration.hpp): the
// restitution the contact model gives in the real integrator, its independence of the
// approach speed, and the overlap bound; plus the LammpsSession checks that keep bad input
// away from LAMMPS (an error there would end the test process).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "md_bridge/contact_model.hpp"
#include "md_bridge/lammps_session.hpp"
#include "md_bridge/restitution_calibration.hpp"
#include "support/contact_spec.hpp"

namespace {

using namespace granvv::md;

ContactModel model_for(double r, bool discrete_correction = true) {
  ContactSpec spec = granvv::testing::test_contact_spec();
  spec.restitution = r;
  spec.discrete_correction = discrete_correction;
  return make_contact_model(spec);
}

std::string temp_path(const std::string& name) {
  return (::testing::TempDir() + "/granvv_" + std::to_string(::getpid()) + "_" + name);
}

TEST(RestitutionCalibration, MeasuredRestitutionMatchesTheTarget) {
  // Issue acceptance: within 1e-3 of the target for r = 0.5, 0.7, 0.9, 0.98.
  for (const double r : {0.5, 0.7, 0.9, 0.98}) {
    RestitutionCalibration calibration(model_for(r));
    const RestitutionMeasurement m = calibration.measure(1.0);
    EXPECT_NEAR(m.restitution, r, 1e-3) << "r = " << r;
    EXPECT_NEAR(m.restitution_energy, r, 1e-3) << "r = " << r;
    EXPECT_EQ(m.per_phase.size(), 64u);
    EXPECT_LE(m.restitution_min, m.restitution);
    EXPECT_GE(m.restitution_max, m.restitution);
    // A contact lasts ~30 steps; the run ends as the last pair separates.
    EXPECT_GT(m.steps, 30);
    EXPECT_LT(m.steps, 45);
    std::printf(
        "[ r target %.2f ] measured %.6f (sqrt<r^2> %.6f), phases %.6f .. %.6f, "
        "%lld steps, %.3f s\n",
        r, m.restitution, m.restitution_energy, m.restitution_min, m.restitution_max, m.steps,
        m.wall_seconds);
  }
}

TEST(RestitutionCalibration, LinearSpringRestitutionDoesNotDependOnTheApproachSpeed) {
  // The overlap obeys a linear equation, so the speed only scales it: the phase-averaged r
  // is the same at every speed (a single collision's r is not, through its entry phase).
  RestitutionCalibration calibration(model_for(0.7));
  double lo = 1.0, hi = 0.0;
  for (const double u : {0.3, 1.0, 4.0, 10.0}) {
    const double r = calibration.measure(u).restitution;
    EXPECT_NEAR(r, 0.7, 1e-3) << "u = " << u;
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  EXPECT_LT(hi - lo, 5e-4);
}

TEST(RestitutionCalibration, OverlapStaysBelowTheBoundAtTheFastestSpeed) {
  // At u = u_max the largest overlap stays below delta_max = 0.01 sigma, and not far below
  // it (the stiffness is not needlessly high); the least damped contact is the worst.
  for (const double r : {0.5, 0.98, 1.0}) {
    RestitutionCalibration calibration(model_for(r));
    const RestitutionMeasurement m = calibration.measure(10.0);
    EXPECT_LE(m.max_overlap, 0.01) << "r = " << r;
    EXPECT_LE(m.max_overlap, m.undamped_overlap_bound * 1.0025) << "r = " << r;
    EXPECT_GT(m.max_overlap, (r > 0.9 ? 0.98 : 0.7) * 0.01) << "r = " << r;
    std::printf("[ r %.2f at u_max ] max overlap %.6f sigma (bound 0.01)\n", r, m.max_overlap);
  }
  // Half the speed, half the overlap.
  RestitutionCalibration calibration(model_for(0.9));
  const double full = calibration.measure(10.0).max_overlap;
  const double half = calibration.measure(5.0).max_overlap;
  EXPECT_NEAR(half / full, 0.5, 0.01);
}

TEST(RestitutionCalibration, ContinuumDampingIsLowInTheDiscreteIntegrator) {
  // Without the leapfrog correction the formula's gamma_n gives r low by O(dt/tc): in LAMMPS
  // as in the emulation (contact_model.hpp).
  const ContactModel continuum = model_for(0.5, false);
  const double r = measure_restitution(continuum, 1.0);
  EXPECT_LT(r, 0.5 - 2e-3);
  EXPECT_NEAR(r, leapfrog_restitution(continuum.gamma_n, continuum.kn, 0.5, continuum.dt), 5e-4);
  std::printf("[ continuum gamma_n, r target 0.5 ] measured %.6f\n", r);
}

TEST(RestitutionCalibration, CalibrationRefinesTheDampingToTheMeasurement) {
  const ContactModel start = model_for(0.5, false);
  RestitutionCalibrationOptions options;
  options.phases = 32;
  const ContactModel tuned = calibrate_damping(start, 1.0, 2e-4, 6, options);
  EXPECT_LT(tuned.gamma_n, start.gamma_n);
  EXPECT_NEAR(RestitutionCalibration(tuned, options).measure(1.0).restitution, 0.5, 2e-4);
  EXPECT_EQ(tuned.dt, start.dt);
}

TEST(RestitutionCalibration, CommandsAndLogFile) {
  const std::string log = temp_path("restitution.log");
  std::remove(log.c_str());
  const ContactModel model = model_for(0.9);
  RestitutionCalibrationOptions options;
  options.log_file = log;
  options.phases = 4;
  int seen = 0;
  options.on_command = [&seen](const std::string&) { ++seen; };
  RestitutionCalibration calibration(model, options);
  calibration.measure(2.0);
  const auto& commands = calibration.commands();
  EXPECT_EQ(seen, static_cast<int>(commands.size()));
  const auto has = [&](const std::string& c) {
    return std::find(commands.begin(), commands.end(), c) != commands.end();
  };
  EXPECT_TRUE(has("dimension 2"));
  EXPECT_TRUE(has("atom_style sphere"));
  EXPECT_TRUE(has("comm_modify vel yes"));
  EXPECT_TRUE(has("fix integrate all nve/sphere disc"));
  EXPECT_TRUE(has("fix planar all enforce2d"));
  EXPECT_TRUE(has(pair_style_command(model)));
  EXPECT_TRUE(has(timestep_command(model)));
  EXPECT_TRUE(has("run 1 pre yes post no"));
  for (const auto& c : commands) EXPECT_EQ(c.find("limit_damping"), std::string::npos) << c;
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("pair_style gran/hooke"), std::string::npos);
  std::remove(log.c_str());
  // Unwritable log: refused before LAMMPS sees it.
  EXPECT_THROW(measure_restitution(model, 1.0, "/nonexistent-dir/x/log.lammps"),
               std::invalid_argument);
}

TEST(RestitutionCalibration, RejectsInputThatWouldStopLammps) {
  const ContactModel model = model_for(0.9);
  RestitutionCalibration calibration(model);
  EXPECT_THROW(calibration.measure(0.0), std::invalid_argument);
  EXPECT_THROW(calibration.measure(-1.0), std::invalid_argument);
  EXPECT_THROW(calibration.measure(std::nan("")), std::invalid_argument);
  EXPECT_THROW(calibration.measure(1000.0), std::invalid_argument);  // overlap 1 sigma
  ContactModel bad = model;
  bad.dt = -1.0;
  EXPECT_THROW(RestitutionCalibration{bad}, std::invalid_argument);
  RestitutionCalibrationOptions none;
  none.phases = 0;
  EXPECT_THROW(RestitutionCalibration(model, none), std::invalid_argument);
}

TEST(RestitutionLammpsSession, RecordsCommandsAndSetsTheMassExplicitly) {
  LammpsSession lmp;
  std::vector<std::string> seen;
  lmp.set_command_callback([&seen](const std::string& c) { seen.push_back(c); });
  EXPECT_FALSE(lmp.box_exists());
  EXPECT_THROW(lmp.run(1, true), std::logic_error);
  EXPECT_THROW(lmp.create_atoms(AtomBatch{{1}, {0, 0, 0}, {}, {1.0}, {1.0}, {}, 0}),
               std::logic_error);
  lmp.commands({"units lj", "dimension 2", "atom_style sphere", "boundary p p p",
                "region box block -5 5 -5 5 -0.5 0.5", "create_box 2 box"});
  EXPECT_TRUE(lmp.box_exists());
  EXPECT_EQ(lmp.dimension(), 2);
  EXPECT_EQ(lmp.ntypes(), 2);
  EXPECT_EQ(lmp.history().size(), 6u);
  EXPECT_EQ(seen, lmp.history());

  // Rejected before LAMMPS: nothing is created.
  AtomBatch outside{{1}, {6.0, 0, 0}, {}, {1.0}, {1.0}, {}, 0};
  EXPECT_THROW(lmp.create_atoms(outside), std::invalid_argument);
  AtomBatch wrong_type{{3}, {0, 0, 0}, {}, {1.0}, {1.0}, {}, 0};
  EXPECT_THROW(lmp.create_atoms(wrong_type), std::invalid_argument);
  AtomBatch no_mass{{1}, {0, 0, 0}, {}, {1.0}, {}, {}, 0};
  EXPECT_THROW(lmp.create_atoms(no_mass), std::invalid_argument);
  AtomBatch off_plane{{1}, {0, 0, 0.1}, {}, {1.0}, {1.0}, {}, 0};
  EXPECT_THROW(lmp.create_atoms(off_plane), std::invalid_argument);
  AtomBatch bad_v{{1}, {0, 0, 0}, {std::nan(""), 0, 0}, {1.0}, {1.0}, {}, 0};
  EXPECT_THROW(lmp.create_atoms(bad_v), std::invalid_argument);
  EXPECT_EQ(lmp.natoms(), 0);

  AtomBatch two{
      {1, 2}, {-1.0, 0, 0, 1.5, 2.0, 0}, {0.5, 0, 0, -0.25, 0, 0}, {1.0, 0.8}, {1.0, 2.0}, {}, 0};
  EXPECT_EQ(lmp.create_atoms(two), 1);
  EXPECT_EQ(lmp.natoms(), 2);
  EXPECT_EQ(lmp.nlocal(), 2);
  AtomBatch third{{1}, {3.0, 3.0, 0}, {}, {1.0}, {1.0}, {}, 0};
  EXPECT_EQ(lmp.create_atoms(third), 3);  // IDs continue
  const std::vector<double> mass = lmp.gather_atoms("rmass", 1);
  const std::vector<double> radius = lmp.gather_atoms("radius", 1);
  const std::vector<double> v = lmp.gather_atoms("v", 3);
  ASSERT_EQ(mass.size(), 3u);
  // Not the 3D default pi/6 of lammps_create_atoms: the masses given.
  EXPECT_EQ(mass[0], 1.0);
  EXPECT_EQ(mass[1], 2.0);
  EXPECT_EQ(radius[1], 0.4);
  EXPECT_EQ(v[0], 0.5);
  EXPECT_EQ(v[3], -0.25);
  ASSERT_NE(lmp.id(), nullptr);
  ASSERT_NE(lmp.rmass(), nullptr);
  ASSERT_NE(lmp.radius(), nullptr);
  ASSERT_NE(lmp.x(), nullptr);
  ASSERT_NE(lmp.v(), nullptr);

  // A short free flight: x advances by v dt.
  lmp.commands({"comm_modify vel yes", "pair_style gran/hooke 1000 0 0 0 0 0", "pair_coeff * *",
                "fix integrate all nve/sphere disc", "fix planar all enforce2d", "timestep 0.01"});
  lmp.run(10, true);
  lmp.run(10, false);
  const std::vector<double> x = lmp.gather_atoms("x", 3);
  EXPECT_NEAR(x[0], -1.0 + 0.5 * 0.2, 1e-12);
  EXPECT_NEAR(x[3], 1.5 - 0.25 * 0.2, 1e-12);
  EXPECT_EQ(lmp.history().back(), "run 10 pre no post no");
  EXPECT_THROW(lmp.run(-1, false), std::invalid_argument);
  EXPECT_THROW(lmp.command("run 1\nrun 2"), std::invalid_argument);
  EXPECT_THROW(lmp.command("  "), std::invalid_argument);
}

TEST(RestitutionLammpsSession, MpiIsInitialisedAndStaysUpBetweenSessions) {
  { LammpsSession a; }
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  EXPECT_TRUE(initialised);
  EXPECT_FALSE(finalised);
  LammpsSession b;
  EXPECT_EQ(b.size(), 1);
  EXPECT_EQ(b.rank(), 0);
  EXPECT_THROW(LammpsSession(LammpsSessionOptions{"", MPI_COMM_WORLD, nullptr}),
               std::invalid_argument);
}

}  // namespace
