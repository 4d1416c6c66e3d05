#pragma once
// The run loop of the continuum engine: time-step control, retries, snapshots at the
// requested output times, time series of the whole-mesh diagnostics, peak-density
// crossing times and the stop conditions (end time, singularity, the closure's own validity
// limit, failure).
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "hydro/closure.hpp"
#include "hydro/diagnostics.hpp"
#include "hydro/lagrangian_state.hpp"
#include "hydro/time_series.hpp"
#include "hydro/time_step.hpp"
#include "hydro/validity_monitors.hpp"

namespace granvv::hydro {

// The case's hydro.* keys (defaults in the case schema, scene/case_schema.cpp).
struct RunControl {
  double t_end = 0.0;
  std::vector<double> output_times;  // snapshots are taken exactly at these times
  TimeStepControl time_step;
  double stop_density = 0.0;    // singularity: peak density reaches this
  double min_cell_width = 0.0;  // singularity: a cell gets this thin
  std::vector<double> crossing_densities = {10.0, 100.0, 1000.0, 1e6};
  int series_every = 0;  // >= 1
};

struct Snapshot {
  std::string label;  // "initial", "output", "final"
  LagrangianState state;
};

// closure_limit: the state left the range in which the closure applies
// (Closure::validity_problem, e.g. the Enskog closure at the freezing area fraction).
enum class RunStatus { completed, singularity, closure_limit, failed };
std::string to_string(RunStatus s);

struct RunResult {
  RunStatus status = RunStatus::failed;
  std::string stop_reason;
  long long steps = 0;
  long long rejected_steps = 0;
  double wall_seconds = 0.0;
  TimeSeries series;
  std::vector<Snapshot> snapshots;
  // time at which the peak density first reached each crossing density (absent: never)
  std::map<double, double> crossing_times;
  double energy_drift = 0.0;    // max |E + E_cooled - E(0)| / E(0)
  double momentum_drift = 0.0;  // max |P - P(0)| (P(0) is zero in the paper's scenes)
  double mass_drift = 0.0;
  // The validity monitors' first crossings and largest values (hydro/validity_monitors.hpp).
  ValidityRecord validity;
};

struct Progress {
  long long step;
  double t, dt, t_end, n_max, stop_density, energy, wall_seconds;
  std::string limited_by;
};
using ProgressCallback = std::function<void(const Progress&)>;

// Throws std::invalid_argument if a time-step bound is not > 0 or series_every < 1.
RunResult run_hydro(const Closure& closure, LagrangianState initial, const RunControl& control,
                    const ProgressCallback& progress = {});

}  // namespace granvv::hydro
