#include "app/summary.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "hydro/initial_conditions.hpp"
#include "hydro/linear_mode_measurement.hpp"
#include "hydro/linear_stability.hpp"
#include "hydro/singularity_analysis.hpp"
#include "scene/json_numbers.hpp"

namespace granvv::app {
namespace {

using nlohmann::json;

// |deviation| <= tolerance, or null when there is no deviation to judge.
json within(std::optional<double> deviation, double tolerance) {
  return deviation ? json(std::abs(*deviation) <= tolerance) : json();
}

// "10", "100", "1000", "1e6": the crossing densities as the contract spells them.
std::string density_key(double level) {
  std::ostringstream s;
  if (level >= 1e4) {
    s << "1e" << std::lround(std::log10(level));
  } else {
    s << std::lround(level);
  }
  return s.str();
}

json convergence_json(const hydro::ConvergenceStudy& c) {
  return {{"t", c.t},
          {"cfl", c.cfl},
          {"cells", c.cells},
          {"error_x", c.error_x},
          {"error_v", c.error_v},
          {"error_n", c.error_n},
          {"error_T", c.error_T},
          {"order_x", c.order_x.back()},
          {"order_v", c.order_v.back()},
          {"order_n", c.order_n.back()},
          {"order_T", c.order_T.back()},
          {"wall_seconds", c.wall_seconds}};
}

}  // namespace

json validity_json(const hydro::ValidityRecord& v) {
  json out = json::object();
  for (const auto& d : hydro::monitor_definitions()) {
    const int k = static_cast<int>(d.monitor);
    const auto& crossing = v.first_crossing[k];
    out[d.name] = {
        {"applies", bool(v.applies[k])},
        {"threshold", v.threshold[k]},
        {"crossed", crossing.has_value()},
        {"value", crossing ? json(crossing->value) : json()},
        {"time", crossing ? json(crossing->time) : json()},
        {"place", crossing ? json(crossing->x) : json()},
        {"largest", v.applies[k] ? number_or_null(v.largest[k]) : json()},
    };
  }
  return out;
}

std::string summary_text(const json& summary) {
  // Strings that are not UTF-8 (a folder name, say) are written with U+FFFD, not thrown on.
  return summary.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

json hydro_summary(const HydroScene& scene, const HydroOutcome& out) {
  const auto& run = out.run;
  json h;
  h["status"] = hydro::to_string(run.status);
  h["stop_reason"] = run.stop_reason;
  h["wall_seconds"] = run.wall_seconds;
  h["cells"] = scene.cells;
  h["steps"] = run.steps;
  h["rejected_steps"] = run.rejected_steps;
  const double cell_steps = double(run.steps) * scene.cells;
  h["cell_steps"] = cell_steps;
  h["cell_steps_per_second"] = run.wall_seconds > 0 ? json(cell_steps / run.wall_seconds) : json();
  h["t_final"] = run.snapshots.back().state.t;
  h["unstable_modes"] = out.unstable_modes;
  h["shear_unstable_modes"] = out.shear_unstable_modes;
  h["clustering_cutoff_mode"] = hydro::clustering_cutoff_mode(*make_hydro_closure(scene));
  h["closure"] = scene.closure;
  h["cooling"] = hydro::to_string(scene.cooling);
  h["area_fraction"] = scene.area_fraction;
  h["transport_factors"] = {{"viscosity", scene.factors.viscosity},
                            {"conductivity", scene.factors.conductivity},
                            {"cooling", scene.factors.cooling},
                            {"mu", scene.factors.mu}};

  std::optional<double> tau;
  if (run.status == hydro::RunStatus::singularity && out.singularity) tau = out.singularity->tau;
  h["singularity_time"] = number_or_null(tau);
  if (out.singularity) {
    const auto& f = *out.singularity;
    h["tau_fit_window"] = {{"n_min", f.n_min}, {"n_max", f.n_max},   {"t_min", f.t_min},
                           {"t_max", f.t_max}, {"points", f.points}, {"tau", f.tau}};
  } else {
    h["tau_fit_window"] = nullptr;
  }
  h["blowup_time"] = number_or_null(out.blowup_time);
  h["blowup_time_deviation"] =
      out.blowup_time && out.inertia_tau ? json(*out.blowup_time / *out.inertia_tau - 1.0) : json();
  h["inertia_singularity_time"] = number_or_null(out.inertia_tau);
  const auto tau_deviation =
      tau && out.inertia_tau ? std::optional<double>(*tau / *out.inertia_tau - 1.0) : std::nullopt;
  h["singularity_time_deviation"] = number_or_null(tau_deviation);
  h["singularity_time_tolerance"] = hydro::kSingularityTimeTolerance;
  h["singularity_time_within_tolerance"] = within(tau_deviation, hydro::kSingularityTimeTolerance);

  json crossings = json::object();
  for (double level : scene.control.crossing_densities) {
    const auto it = run.crossing_times.find(level);
    crossings[density_key(level)] = it == run.crossing_times.end() ? json() : json(it->second);
  }
  h["peak_density_times"] = crossings;

  json snaps = json::array();
  std::optional<double> collapse_max;
  for (const auto& s : out.snapshots) {
    if (s.label != "output") continue;
    if (s.collapse_error) collapse_max = std::max(collapse_max.value_or(0.0), *s.collapse_error);
    const auto& d = s.diagnostics;
    const json collapse_ok = within(s.collapse_error, scene.collapse_tolerance);
    snaps.push_back({{"t", s.t},
                     {"n_max", d.n_max},
                     {"T_min", d.T_min},
                     {"energy", d.energy()},
                     {"energy_thermal", d.energy_thermal},
                     {"energy_kinetic", d.energy_kinetic},
                     {"energy_kinetic_y", d.energy_kinetic_y},
                     {"collapse_error", number_or_null(s.collapse_error)},
                     {"collapse_within_tolerance", collapse_ok}});
  }
  h["snapshots"] = snaps;
  h["collapse_tolerance"] = scene.collapse_tolerance;
  h["collapse_error_max"] = number_or_null(collapse_max);
  h["collapse_within_tolerance"] = within(collapse_max, scene.collapse_tolerance);
  json missing = json::array();
  for (double t : scene.control.output_times) {
    bool found = false;
    for (const auto& s : out.snapshots) found |= (s.label == "output" && s.t == t);
    if (!found) missing.push_back(t);
  }
  h["output_times_not_reached"] = missing;

  if (out.profile_slope) {
    const auto& p = *out.profile_slope;
    h["profile_slope"] = {{"t", out.profile_slope_time},
                          {"slope", p.slope},
                          {"x_min", p.x_min},
                          {"x_max", p.x_max},
                          {"points", p.points}};
  } else {
    h["profile_slope"] = nullptr;
  }
  h["energy_drift"] = run.energy_drift;
  h["momentum_drift"] = run.momentum_drift;
  h["mass_drift"] = run.mass_drift;
  const auto totals = [](const hydro::FieldTotals& t) {
    return nlohmann::json{{"mass", t.mass},
                          {"momentum_x", t.momentum_x},
                          {"momentum_y", t.momentum_y},
                          {"energy", t.energy}};
  };
  h["initial_totals"] = totals(out.initial_cells);
  h["initial_totals"]["given"] = totals(out.initial_given);
  h["initial_totals"]["relative_difference"] =
      hydro::largest_relative_difference(out.initial_cells, out.initial_given);
  h["validity"] = validity_json(run.validity);
  h["haff_max_relative_error"] = out.haff_max_relative_error;
  if (out.linear_rate) {
    const auto& r = *out.linear_rate;
    const auto seeded = hydro::seeded_eigenmode(scene.initial);
    h["linear_mode"] = {{"k", seeded ? json(seeded->mode) : json()},
                        {"branch", seeded ? json(seeded->branch) : json()},
                        {"rate_theory", {r.theory.real(), r.theory.imag()}},
                        {"rate_measured", {r.measured.real(), r.measured.imag()}},
                        {"relative_error", number_or_null(r.relative_error)},
                        {"relative_error_tolerance", hydro::kLinearRateTolerance},
                        {"within_tolerance", within(r.relative_error, hydro::kLinearRateTolerance)},
                        {"samples", r.samples}};
  } else {
    h["linear_mode"] = nullptr;
  }
  h["convergence"] = out.convergence ? convergence_json(*out.convergence) : json();
  return h;
}

}  // namespace granvv::app
