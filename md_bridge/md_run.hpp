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
      momentum_x, momentum_y;
  // Expected flow energy that the sampling noise of the bin means puts into energy_kinetic_x/y
  // (BoxEnergies::macro_noise_x/y): subtract it to see the macroscopic flow itself.
  std::vector<double> kinetic_noise_x, kinetic_noise_y;
  // The engine's own numbers at every sample (ParticleEngine::series_values), in its order.
  std::vector<std::pair<std::string, std::vector<double>>> engine;
};

struct MdProgress {
  double t, t_end, T, wall_seconds;
  long long steps;
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

// One run of `engine` (which starts it anew). Validates the spec (scene_problem, times) and
// throws std::invalid_argument before the engine sees it. Deterministic for a seed (and a
// number of ranks) if the engine is.
MdRunResult run_md(const MdRunSpec& spec, ParticleEngine& engine,
                   const std::function<void(const MdProgress&)>& progress);

}  // namespace granvv::md
