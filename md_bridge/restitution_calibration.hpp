#pragma once
// Verifies a contact model inside LAMMPS by binary collisions (docs/physics.md §5): head-on
// collisions of two disks, r = -(v_n after)/(v_n before).
//
// A time-discrete contact does not have one restitution: the collision starts at some phase s
// in [0, 1) within a time step, and r(s) is piecewise linear in s with one jump where the
// number of steps in contact changes (measured at 30 steps per contact: 0.491 .. 0.516 for r =
// 0.5, 0.9798 .. 0.9813 for r = 0.98). In a gas s is uniform, so the restitution that sets the
// cooling rate is the mean over s. One LAMMPS run holds `phases` independent pairs (rows 2
// sigma apart, so no disk touches another pair), pair k starting its contact at phase s = (k +
// 1/2)/phases; the midpoint rule's error is at most the jump / (2 phases) (< 2e-4 at the
// default 64). For a linear spring the phase-averaged r does not depend on the approach speed
// (the equation of motion of the overlap is linear, so the speed only scales it); a single
// collision's r does, through its phase.
#include <mpi.h>

#include <functional>
#include <string>
#include <vector>

#include "md_bridge/contact_model.hpp"

namespace granvv::md {

struct RestitutionMeasurement {
  double approach_speed = 0.0;      // relative normal speed before, u
  double restitution = 0.0;         // mean over entry phases of r = v_n,after / u
  double restitution_energy = 0.0;  // sqrt(<r^2>): the one that sets the energy loss
  double restitution_min = 0.0;     // over entry phases
  double restitution_max = 0.0;
  std::vector<double> per_phase;        // r of pair k (phase (k + 1/2)/phases)
  double max_overlap = 0.0;             // largest overlap of any pair (length)
  double undamped_overlap_bound = 0.0;  // u sqrt(m_eff/kn)
  long long steps = 0;                  // time steps run
  double wall_seconds = 0.0;
};

struct RestitutionCalibrationOptions {
  int phases = 64;                                     // collisions per measurement, in [1, 4096]
  std::string log_file = "none";                       // LAMMPS -log
  MPI_Comm comm = MPI_COMM_WORLD;                      // collective over this communicator
  std::function<void(const std::string&)> on_command;  // sees every LAMMPS command
};

class RestitutionCalibration {
 public:
  // Throws std::invalid_argument if the model is not valid (validate(ContactModel)) or the
  // options are out of range.
  explicit RestitutionCalibration(ContactModel model, RestitutionCalibrationOptions options = {});

  // One LAMMPS run of `phases` head-on collisions at relative normal speed u (2D, atom_style
  // sphere, periodic box, fix nve/sphere disc, fix enforce2d, comm_modify vel yes). Throws
  // std::invalid_argument for u not finite and > 0 or an undamped overlap u sqrt(m_eff/kn)
  // beyond 0.25 sigma; std::runtime_error if a pair has not separated after 20 contact times.
  RestitutionMeasurement measure(double approach_speed);

  // The LAMMPS commands of the last measurement (lammps_create_atoms not included).
  const std::vector<std::string>& commands() const { return commands_; }
  const ContactModel& model() const { return model_; }

 private:
  ContactModel model_;
  RestitutionCalibrationOptions options_;
  std::vector<std::string> commands_;
};

// The phase-averaged restitution of `model` at relative normal speed u, measured in LAMMPS:
// a few hundred steps of 2 x 64 disks, about 0.1 s. Collective over MPI_COMM_WORLD.
double measure_restitution(const ContactModel& model, double approach_speed,
                           std::string log_file = "none");

// gamma_n refined by measurement until the phase-averaged r is within `tolerance` of
// model.restitution (fixed point gamma <- gamma ln r_target / ln r_measured, as ln r is
// nearly proportional to gamma); dt is kept, contact_time recomputed. Throws
// std::runtime_error if it has not converged after max_iterations measurements.
ContactModel calibrate_damping(const ContactModel& model, double approach_speed,
                               double tolerance = 1e-4, int max_iterations = 6,
                               RestitutionCalibrationOptions options = {});

}  // namespace granvv::md
