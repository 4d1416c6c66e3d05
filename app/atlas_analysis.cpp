#include "app/atlas_analysis.hpp"

#include <cmath>
#include <limits>

#include "atlas/work_precision.hpp"
#include "compare/field_metrics.hpp"
#include "compare/model_comparison.hpp"
#include "fields/field_series.hpp"

namespace granvv::app {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The run's index for each of the reference's compared times (-1 where it has none).
std::vector<int> matching_times(const AtlasRun& run, const AtlasRun& reference) {
  std::vector<int> index;
  for (double t : reference.times) {
    int found = -1;
    for (std::size_t i = 0; i < run.times.size(); ++i) {
      if (std::abs(run.times[i] - t) <= 1e-9 * std::max(1.0, t)) found = int(i);
    }
    index.push_back(found);
  }
  return index;
}

bool is_field(const std::string& name) {
  return name.rfind("field_", 0) == 0;
}

// The error of one time-resolved observable at the reference's i-th compared time.
double error_at(const std::string& name, const AtlasRun& run, int at, const AtlasRun& reference,
                std::size_t i) {
  if (at < 0) return kNaN;
  if (name == "thermal_energy") return atlas::relative_error(run.thermal[at], reference.thermal[i]);
  if (name == "kinetic_energy") return atlas::relative_error(run.flow[at], reference.flow[i]);
  if (!is_field(name) || !run.fields || !reference.fields) return kNaN;
  const std::string field = name.substr(6);
  const auto& cand = run.fields->snapshots[at];
  const auto& ref = reference.fields->snapshots[i];
  const auto& column = fields::field_column(field);
  if ((cand.*column.values).empty() || (ref.*column.values).empty()) return kNaN;
  const double scale = compare::field_scale(field, ref, cand);
  return compare::deterministic_field_difference(cand.*column.values, ref.*column.values, scale).l2;
}

bool time_resolved(const std::string& name) {
  return name == "thermal_energy" || name == "kinetic_energy" || is_field(name);
}

}  // namespace

const std::vector<std::string>& atlas_observable_names() {
  static const std::vector<std::string> names = {
      "crossing_times", "thermal_energy", "kinetic_energy", "field_n", "field_v_x", "field_T"};
  return names;
}

std::map<std::string, double> observable_errors(const AtlasRun& run, const AtlasRun& reference,
                                                const std::vector<std::string>& observables) {
  std::map<std::string, double> errors;
  const std::vector<int> at = matching_times(run, reference);
  for (const auto& name : observables) {
    double error = kNaN;
    if (time_resolved(name)) {
      error = reference.times.empty() ? kNaN : 0.0;
      for (std::size_t i = 0; i < reference.times.size() && !std::isnan(error); ++i) {
        const double e = error_at(name, run, at[i], reference, i);
        error = std::isnan(e) ? kNaN : std::max(error, e);
      }
    } else {
      const auto r = reference.crossing_times.find(name);
      const auto c = run.crossing_times.find(name);
      if (r != reference.crossing_times.end() && c != run.crossing_times.end()) {
        error = atlas::relative_error(c->second, r->second);
      }
    }
    if (std::isfinite(error)) errors[name] = error;
  }
  return errors;
}

std::vector<std::string> provided_observables(const AtlasRun& run,
                                              const std::vector<std::string>& observables) {
  std::vector<std::string> given;
  for (const auto& name : observables) {
    bool has = false;
    if (name == "thermal_energy") {
      for (double e : run.thermal) has |= std::isfinite(e);
    } else if (name == "kinetic_energy") {
      has = !run.flow.empty();
    } else if (is_field(name)) {
      has = run.fields && !run.fields->snapshots.empty() &&
            !(run.fields->snapshots.front().*fields::field_column(name.substr(6)).values).empty();
    } else {
      has = run.crossing_times.count(name) > 0;
    }
    if (has) given.push_back(name);
  }
  return given;
}

std::vector<double> error_over_time(const AtlasRun& run, const AtlasRun& reference,
                                    const std::vector<std::string>& observables) {
  const std::vector<int> at = matching_times(run, reference);
  std::vector<double> worst(reference.times.size(), 0.0);
  for (std::size_t i = 0; i < reference.times.size(); ++i) {
    for (const auto& name : observables) {
      if (!time_resolved(name)) continue;
      const double e = error_at(name, run, at[i], reference, i);
      worst[i] = std::isnan(e) || std::isnan(worst[i]) ? kNaN : std::max(worst[i], e);
    }
  }
  return worst;
}

}  // namespace granvv::app
