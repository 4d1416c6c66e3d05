#include "hydro/driver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "hydro/haff.hpp"
#include "hydro/integrator.hpp"

namespace granvv::hydro {

std::string to_string(RunStatus s) {
  switch (s) {
    case RunStatus::completed:
      return "ok";
    case RunStatus::singularity:
      return "singularity";
    case RunStatus::closure_limit:
      return "closure_limit";
    case RunStatus::failed:
      return "failed";
  }
  return "failed";
}

namespace {

// 1/n is linear in t near a flow-by-inertia singularity (paper Eq. 5b), so a crossing time
// is interpolated linearly in 1/n between the two steps that bracket it.
double crossing_time(double t0, double n0, double t1, double n1, double level) {
  const double u0 = 1.0 / n0, u1 = 1.0 / n1, u = 1.0 / level;
  return u0 == u1 ? t1 : t0 + (t1 - t0) * (u0 - u) / (u0 - u1);
}

// The first node or cell whose value is not finite, as the reason a run cannot start (a field
// given as NaN there); empty if every value is finite.
std::string non_finite_initial_state(const LagrangianState& s) {
  const auto describe = [](const char* what, double value, double x) {
    return std::string("the initial ") + what + " is " + std::to_string(value) +
           " at x = " + std::to_string(x) + " (a non-finite initial field)";
  };
  for (int j = 0; j < s.cells(); ++j) {
    if (!std::isfinite(s.node_v[j])) return describe("velocity v_x", s.node_v[j], s.node_x[j]);
    if (s.has_transverse() && !std::isfinite(s.node_vy[j])) {
      return describe("transverse velocity v_y", s.node_vy[j], s.node_x[j]);
    }
    const double centre = s.node_x[j] + 0.5 * cell_width(s, j);
    if (!std::isfinite(s.cell_mass[j])) return describe("cell mass", s.cell_mass[j], centre);
    if (!std::isfinite(s.cell_T[j])) return describe("temperature", s.cell_T[j], centre);
  }
  return "";
}

// A step of dt, halved until the integrator accepts it (at most 30 tries): dt becomes the step
// taken, and each rejection is counted.
StepOutcome step_halving(HydroIntegrator& integrator, LagrangianState& s, double& dt,
                         CellGeometry& cells, long long& rejected) {
  StepOutcome step;
  for (int attempt = 0; attempt < 30; ++attempt) {
    step = integrator.step(s, dt, cells);
    if (step.accepted) break;
    ++rejected;
    dt *= 0.5;
  }
  return step;
}

// The times the peak density first crossed each level within the step from (t0, n0) to (t1, n1).
void note_crossings(const std::vector<double>& levels, double t0, double n0, double t1, double n1,
                    std::map<double, double>& crossing_times) {
  for (double level : levels) {
    if (n0 < level && n1 >= level && !crossing_times.count(level)) {
      crossing_times[level] = crossing_time(t0, n0, t1, n1, level);
    }
  }
}

}  // namespace

RunResult run_hydro(const Closure& closure, LagrangianState s, const RunControl& control,
                    const ProgressCallback& progress) {
  const TimeStepControl& ts = control.time_step;
  if (!(ts.cfl > 0 && ts.max_compression > 0 && ts.max_temperature_change > 0 && ts.dt_max > 0) ||
      control.series_every < 1) {
    throw std::invalid_argument(
        "run_hydro: cfl, max_compression, max_temperature_change and dt_max must be > 0, "
        "series_every >= 1");
  }
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto wall = [&] { return std::chrono::duration<double>(clock::now() - start).count(); };

  RunResult result;
  HydroIntegrator integrator(closure, s.cells());
  TimeStepLimiter limiter(closure, control.time_step);
  const double t0 = haff_time_scale(closure);
  CellGeometry cells;  // widths and densities of s, updated by every accepted step
  measure_cells(s, cells);
  const Diagnostics d0 = diagnose(s, cells);
  // The validity monitors, measured on every accepted state (hydro/validity_monitors.hpp).
  const ValidityScales scales = closure.validity_scales();
  result.validity = ValidityRecord(scales);
  ValidityWorkspace validity_work;
  ValidityMeasures validity = measure_validity(s, cells, scales, validity_work);
  result.validity.note(validity, s.t);
  double cooled = 0.0;
  auto record = [&](double step, const Diagnostics& now) {
    result.series.record(
        {s.t, step, now, cooled, haff_temperature(s.t, t0), validity, scales.area_fraction > 0.0});
  };
  record(0.0, d0);
  result.snapshots.push_back({"initial", s});

  std::vector<double> outputs;
  for (double t : control.output_times) {
    if (t > s.t) outputs.push_back(t);
    if (t == s.t) result.snapshots.back().label = "output";
  }
  size_t next_output = 0;
  Diagnostics d = d0;
  double heating_limit = control.time_step.dt_max;
  TimeStepLimit limit{0.0, ""};

  auto drift = [&](const Diagnostics& now) {
    result.energy_drift =
        std::max(result.energy_drift, std::abs(now.energy() + cooled - d0.energy()) / d0.energy());
    result.momentum_drift = std::max(result.momentum_drift, std::abs(now.momentum - d0.momentum));
    result.mass_drift = std::max(result.mass_drift, std::abs(now.mass - d0.mass));
  };

  // The closure's own limit, checked on the initial state and after every accepted step.
  auto outside_closure = [&] {
    const std::string problem = closure.validity_problem(cells.density);
    if (problem.empty()) return false;
    result.status = RunStatus::closure_limit;
    result.stop_reason = problem + " at t = " + std::to_string(s.t);
    return true;
  };

  const std::string not_finite = non_finite_initial_state(s);
  if (!not_finite.empty()) {
    result.status = RunStatus::failed;
    result.stop_reason = not_finite;
  }
  while (not_finite.empty() && !outside_closure()) {
    if (s.t >= control.t_end) {
      result.status = RunStatus::completed;
      result.stop_reason = "end time reached";
      break;
    }
    limit = limiter.limit(s, cells);
    if (heating_limit < limit.dt) limit = {heating_limit, "heating"};
    double dt = limit.dt;
    bool clamped = false;
    const double target = next_output < outputs.size() ? outputs[next_output] : control.t_end;
    if (s.t + dt >= target * (1.0 - 1e-14)) {
      dt = target - s.t;
      clamped = true;
      limit.limited_by = "output time";
    }

    if (!(s.t + dt > s.t)) {  // a step below the clock's round-off would never end the run
      result.status = RunStatus::failed;
      result.stop_reason = "the time step dt = " + std::to_string(dt) + " (limited by " +
                           limit.limited_by + ") no longer advances t = " + std::to_string(s.t) +
                           " in double precision";
      break;
    }
    const auto rejected_before = result.rejected_steps;
    const StepOutcome step = step_halving(integrator, s, dt, cells, result.rejected_steps);
    if (result.rejected_steps != rejected_before) clamped = false;  // dt is no longer the target's
    if (!step.accepted) {
      result.status = RunStatus::failed;
      result.stop_reason = "no admissible time step at t = " + std::to_string(s.t) +
                           " (temperature would turn negative or cells would cross)";
      break;
    }
    if (clamped) s.t = target;  // exact output and end times, free of round-off
    const bool lands_on_output = clamped && next_output < outputs.size();
    ++result.steps;
    cooled += step.energy_cooled;
    heating_limit = step.relative_heating > 0.0
                        ? dt * control.time_step.max_temperature_change / step.relative_heating
                        : control.time_step.dt_max;
    heating_limit = std::max(heating_limit, 0.5 * dt);

    const Diagnostics prev = d;
    d = diagnose(s, cells);
    validity = measure_validity(s, cells, scales, validity_work);
    result.validity.note(validity, s.t);
    drift(d);
    note_crossings(control.crossing_densities, s.t - dt, prev.n_max, s.t, d.n_max,
                   result.crossing_times);
    const bool singular = d.n_max >= control.stop_density || d.min_width <= control.min_cell_width;
    if (result.steps % control.series_every == 0 || singular || lands_on_output) {
      record(dt, d);
    }
    if (lands_on_output) {
      result.snapshots.push_back({"output", s});
      ++next_output;
    }
    if (progress) {
      progress({result.steps, s.t, dt, control.t_end, d.n_max, control.stop_density, d.energy(),
                wall(), limit.limited_by});
    }
    if (!std::isfinite(d.energy())) {
      result.status = RunStatus::failed;
      result.stop_reason = "non-finite energy at t = " + std::to_string(s.t);
      break;
    }
    if (singular) {
      result.status = RunStatus::singularity;
      result.stop_reason = d.n_max >= control.stop_density
                               ? "peak density reached hydro.stop_density"
                               : "a cell width reached hydro.min_cell_width";
      break;
    }
  }
  if (result.series.t.back() != s.t) record(0.0, d);
  if (result.snapshots.back().state.t != s.t || result.snapshots.size() == 1) {
    result.snapshots.push_back({"final", s});
  }
  result.wall_seconds = wall();
  return result;
}

}  // namespace granvv::hydro
