#pragma once
// One particle run: 2D inelastic disks (LAMMPS gran/hooke, friction off) in a periodic box,
// started from fields, advanced in segments; between segments the particles are
// coarse-grained in place (moments reduced over the ranks), whole-box energies recorded, and
// the contact stiffness lowered as the gas cools (hard-disk limit at fixed restitution).
#include <mpi.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "hydro/initial_conditions.hpp"
#include "md_bridge/coarse_grainer.hpp"
#include "md_bridge/contact_model.hpp"
#include "md_bridge/particle_scene.hpp"

namespace granvv::md {

struct MdRunSpec {
  ParticleScene scene;
  hydro::InitialFields fields;  // scaled units (hydro/initial_conditions.hpp)
  std::uint64_t seed = 1;
  double t_end = 100.0;              // MD units
  double sample_interval = 1.0;      // time series every this much MD time
  std::vector<double> output_times;  // coarse-grained snapshots (nearest step), MD units
  int bins = 100;
  std::string kernel = "bin";
  double kernel_width = 0.0;  // sigma
  double max_overlap = 0.01;  // sigma, at the fastest relative speed present
  int steps_per_contact = 30;
  bool adaptive_stiffness = true;
  double adapt_below = 0.5;  // re-stiffen when the fastest speed fell below this fraction
  std::string log_file = "none";
  // H5MD particle snapshots (md_bridge/h5md_writer.hpp): every snapshot_interval of MD time
  // (0 = none), written by rank 0 to h5md_path; the whole-box observables at every sample.
  double snapshot_interval = 0.0;
  std::string h5md_path;
  std::string creator_version = "granvv";
};

// Whole-box time series (MD units). T = thermal / N: granular temperature with the local
// mean flow (both components) removed in md.bins bins, unbiased.
struct MdSeries {
  std::vector<double> t, T, energy_thermal, energy_kinetic_x, energy_kinetic_y, energy_total,
      momentum_x, momentum_y, kn, dt;
  // Expected flow energy that the sampling noise of the bin means puts into energy_kinetic_x/y
  // (BoxEnergies::macro_noise_x/y): subtract it to see the macroscopic flow itself.
  std::vector<double> kinetic_noise_x, kinetic_noise_y;
};

struct MdSnapshot {
  double t = 0.0;
  FieldProfile fields;
};

struct MdProgress {
  double t, t_end, T, wall_seconds;
  long long steps;
};

struct MdRunResult {
  std::string status = "failed";  // "ok" or "failed"
  std::string stop_reason;
  double wall_seconds = 0.0;
  long long steps = 0;
  double atom_steps = 0.0;
  int stiffness_changes = 0;
  ContactModel initial_contact, final_contact;
  MdSeries series;
  std::vector<MdSnapshot> snapshots;
};

// The fastest relative normal speed two particles of the sample can have, 2 max |v| (over
// all ranks' local atoms): the speed the contact must resolve.
double fastest_relative_speed(const double* v, int n, MPI_Comm comm);

// Validates the spec (scene_problem, contact) and throws std::invalid_argument before
// anything reaches LAMMPS. Deterministic for a seed (and a number of ranks).
MdRunResult run_md(const MdRunSpec& spec, const std::function<void(const MdProgress&)>& progress);

}  // namespace granvv::md
