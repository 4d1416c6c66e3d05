#pragma once
// The work of a particle run, estimated before anything runs, in each engine's own unit and
// against the most that unit can do here (scene/md_scene.cpp refuses a run beyond it, naming the
// key). The registry picks an engine's estimate by md.engine (particle_engine_registry.hpp).
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "md_bridge/particle_engine.hpp"
#include "md_bridge/particle_scene.hpp"

namespace granvv::md {

// LAMMPS: 1e13 atom-steps is about two days at the measured 6.4e7 atom-steps/s (README).
inline constexpr double kMaxAtomSteps = 1e13;
// Event-driven: 3e10 collisions is about 17 hours at kEventDrivenCollisionsPerCoreSecond below
// (two days at the 2e5 collisions per CPU second of the engine's first version).
inline constexpr double kMaxCollisions = 3e10;

// The rates a work estimate turns into wall time, per core of this machine (2 cores):
// LAMMPS 7.1e7 atom-steps per second, the bridge's md.wall_seconds for 10^4 disks at phi =
// 0.05 on one rank (docs/md_benchmarks.md §1, 2026-11-22, load < 1); event-driven 5e5
// collisions per CPU second, rounded down from the slower of the measured loads that are not
// the benchmark's dilute gas (1.0-1.1e6): md_paper_scene's clusters 6.7e5, 10^5 disks 5.4e5
// (docs/md_benchmarks.md §4, 2026-12-03, the bucket-queue calendar).
inline constexpr double kLammpsAtomStepsPerCoreSecond = 7.1e7;
inline constexpr double kEventDrivenCollisionsPerCoreSecond = 5e5;
// Resident memory of a rank: a fixed part and a part per disk it holds (engine, sample and its
// overlap grid, moments), from the peak RSS of one-rank runs of 1e5 and 2e5 disks at phi = 0.05
// (docs/md_benchmarks.md §5): LAMMPS 112 and 183 MB, event-driven 83 and 129 MB.
inline constexpr double kLammpsBytesFixed = 4.1e7;
inline constexpr double kLammpsBytesPerDisk = 710.0;
inline constexpr double kEventDrivenBytesFixed = 3.7e7;
inline constexpr double kEventDrivenBytesPerDisk = 461.0;
// A particle frame, per disk a rank holds (its own, and as many of its block of IDs): the
// exchange's send and receive buffers, the block's x and v and the writer's row buffer
// (particle_blocks.hpp, h5md_frames.hpp), counted, not measured: about 24 doubles.
inline constexpr double kFrameBytesPerDisk = 4.0 * 6.0 * sizeof(double);

struct ParticleWorkQuestion {
  ParticleScene scene;
  EngineSettings settings;           // the md.* keys, as the engine gets them
  double hottest_temperature = 1.0;  // the initial fields' largest T (at least T0 = 1)
  double fastest_flow = 0.0;         // the initial fields' largest |v|
  double t_end = 0.0;                // MD time
  // Kinetic-theory Haff time with chi(phi) (haff_time_md); infinite or 0 for a gas that does
  // not cool.
  double haff_time = std::numeric_limits<double>::infinity();
  int ensemble = 1;
  // The initial density profile n/n0 at equispaced points of the box (empty: uniform), and the
  // MD time at which the flow by inertia of the initial velocity profile collapses (+inf: it
  // does not; hydro/flow_by_inertia.hpp): where clusters will form.
  std::vector<double> initial_density;
  double profile_collapse_time = std::numeric_limits<double>::infinity();
};

struct ParticleWorkEstimate {
  double work = 0.0;   // in `unit`, over the whole ensemble
  double limit = 0.0;  // the most of it a run may ask for here
  std::string unit;    // "atom-steps", "collisions"
  // The keys the work grows with; a refusal names the one the user set last.
  std::vector<std::string> keys;
  // The engine's time step at t = 0 and at md.t_end (MD time; 0 for an engine without one): a
  // sample interval below it cannot be kept.
  double first_step = 0.0, last_step = 0.0;
  // Wall time and memory: `unit` per second on one core (the measured rates above); whether
  // the work and the disks divide over the MPI ranks (LAMMPS's domain decomposition; the
  // event-driven engine is serial and every rank runs it whole); a rank's resident memory,
  // bytes_fixed + bytes_per_disk x the disks it holds.
  double rate = 0.0;
  bool divides_over_ranks = false;
  double bytes_fixed = 0.0, bytes_per_disk = 0.0;
  // One member's work from t = 0 to MD time t by the same model (`work` is the ensemble's at
  // md.t_end): the progress line's share of the work done.
  std::function<double(double)> member_work_until;
};

// LAMMPS (docs/physics.md §5): the step is tc / md.steps_per_contact with tc ~ pi md.max_overlap
// / u for the fastest relative speed u, about twice the fastest speed of N Maxwellian disks
// (sqrt(2 T ln N), T the hottest initial temperature) plus the flow. With adaptive stiffness the
// step grows as u falls with Haff's law, u ~ 1/(1 + t/t0), so steps ~ (t0/dt0) ln(1 +
// t_end/t0). Work: particles x steps.
ParticleWorkEstimate lammps_work(const ParticleWorkQuestion& q);

// Event-driven (docs/physics.md §10): Enskog's collision frequency at the hottest initial
// temperature, falling as sqrt(T) ~ 1/(1 + t/t0) with Haff's law, summed over the densities the
// scene will reach (md_bridge/collision_forecast.hpp): the initial profile, then, past the
// clustering onset of the linear theory or of the initial flow, packings near close packing.
// A homogeneous gas makes (N/2) nu0 t0 ln(1 + t_end/t0) (N nu0 t_end / 2 without cooling).
ParticleWorkEstimate event_driven_work(const ParticleWorkQuestion& q);

}  // namespace granvv::md
