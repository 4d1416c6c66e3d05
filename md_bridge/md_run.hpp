#pragma once
// One particle run, engine-neutral: 2D inelastic disks in a periodic box, sampled from
// fields, moved by a particle engine (particle_engine.hpp) in segments; between segments the
// particles are coarse-grained in place (moments reduced over the ranks), whole-box energies
// recorded and, at the snapshot interval, particle frames written in H5MD layout.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "hydro/initial_conditions.hpp"
#include "md_bridge/coarse_grainer.hpp"
#include "md_bridge/particle_engine.hpp"
#include "md_bridge/particle_scene.hpp"

namespace granvv::md {

struct MdRunSpec {
  ParticleScene scene;
  hydro::InitialFields fields;  // scaled units (hydro/initial_conditions.hpp)
  // Set from the case's md.* keys (their defaults are in the case schema only).
  std::uint64_t seed = 0;
  double t_end = 0.0;                // MD units
  double sample_interval = 0.0;      // time series every this much MD time
  std::vector<double> output_times;  // coarse-grained snapshots (nearest step), MD units
  int bins = 0;
  std::string kernel;
  double kernel_width = 0.0;  // sigma
  // H5MD particle snapshots (md_bridge/h5md_frames.hpp): every snapshot_interval of MD time
  // (0 = none), to h5md_path (under MPI each rank its block of IDs beside it, rank 0 the joined
  // file); the whole-box observables at every sample. The same path on every rank.
  double snapshot_interval = 0.0;
  std::string h5md_path;
  std::string creator_version = "granvv";
};

// Whole-box time series (MD units). T = thermal / N: granular temperature with the local
// mean flow (both components) removed in md.bins bins, unbiased.
struct MdSeries {
  std::vector<double> t, T, energy_thermal, energy_kinetic_x, energy_kinetic_y, energy_total,
      momentum_x, momentum_y;
  // Expected flow energy that the sampling noise of the bin means puts into energy_kinetic_x/y
  // (BoxEnergies::macro_noise_x/y): subtract it to see the macroscopic flow itself.
  std::vector<double> kinetic_noise_x, kinetic_noise_y;
  // The box's pressure tensor diagonal (kinetic plus contact, BoxPressure), the single-sample
  // standard error of (P_xx + P_yy)/2 and P/(n T); NaN where the engine gave no contact virial
  // (t = 0 for LAMMPS).
  std::vector<double> pressure_xx, pressure_yy, pressure_stderr, compressibility;
  // The box's lowest Fourier modes (box_modes.hpp): their noise-corrected share of the kinetic
  // energy and the density modes' structure factor.
  std::vector<double> mode_energy_fraction, structure_factor;
  // The engine's own numbers at every sample (ParticleEngine::series_values), in its order.
  std::vector<std::pair<std::string, std::vector<double>>> engine;
};

// The per-sample columns of MdSeries by name, t first: what every writer and reader of a
// series loops over.
struct MdSeriesColumn {
  const char* name;
  std::vector<double> MdSeries::*values;
};
const std::vector<MdSeriesColumn>& md_series_columns();

struct MdProgress {
  double t, t_end, T, wall_seconds;
  long long steps;
  EngineCost cost;  // the engine's, over every run it made so far
};

struct MdRunResult {
  std::string status = "failed";  // "ok" or "failed"
  std::string stop_reason;
  double wall_seconds = 0.0;
  long long steps = 0;  // the engine's steps
  MdSeries series;
  // The coarse-grained snapshots at the output times (bins, MD units, this run's own
  // single-snapshot standard errors: md_bridge/coarse_grainer.hpp).
  fields::FieldSeries fields;
};

// Everything a run needs to continue from a safe point (just after a sample, or inside the
// segment after it for an engine that saves_within_segment): the engine's state, where the
// loop stood at the last sample, and what the run has recorded so far (status "running").
struct MdRunState {
  double t = 0.0;               // the last sample's time
  std::size_t next_output = 0;  // index into MdRunSpec::output_times
  double next_frame = 0.0;      // time of the next H5MD particle frame
  EngineState engine;
  MdRunResult so_far;
};

// The time a saved state continues from: inside a segment, the time the engine had reached
// there; else the last sample's.
double resumed_time(const MdRunState& state);

// Checkpoints of a run (docs/outputs.md, "Checkpoints and resume"). After every sample, and
// inside a segment at the engine's within-segment checks if it saves_within_segment, rank 0
// asks due(); if it says yes, every rank saves the state and hands it to save() (collective:
// under MPI each rank's state may hold only its block of the particles, EngineState).
struct MdCheckpoints {
  std::function<bool()> due;
  std::function<void(const MdRunState&)> save;
  // Continue from this state instead of starting anew (the H5MD file, if any, is cut back to
  // the state's step).
  const MdRunState* resume_from = nullptr;
};

// One run of `engine` (which starts it anew, or continues checkpoints.resume_from). Validates
// the spec (scene_problem, times) and throws std::invalid_argument before the engine sees it.
// Deterministic for a seed (and a number of ranks) if the engine is; a resumed run has the
// same statistics as an uninterrupted one, not the same digits (the engine's summation order
// differs after a restart, and the dynamics is chaotic).
MdRunResult run_md(const MdRunSpec& spec, ParticleEngine& engine,
                   const std::function<void(const MdProgress&)>& progress,
                   const MdCheckpoints& checkpoints = {});

}  // namespace granvv::md
