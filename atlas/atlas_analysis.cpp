#include "atlas/atlas_analysis.hpp"

#include <cmath>

#include "atlas/work_precision.hpp"
#include "compare/field_metrics.hpp"
#include "compare/model_comparison.hpp"
#include "fields/field_series.hpp"

namespace granvv::app {
namespace {

using atlas::kNoValue;

// The run's snapshot index for each of the reference's compared times (-1 where it has none).
std::vector<int> matching_times(const AtlasRun& run, const AtlasRun& reference) {
  std::vector<int> index(reference.times.size(), -1);
  if (!run.fields || !reference.fields) return index;
  for (const auto& [i, j] : compare::common_snapshots(*reference.fields, *run.fields)) {
    index[i] = int(j);
  }
  return index;
}

bool is_field(const std::string& name) {
  return name.rfind("field_", 0) == 0;
}

bool time_resolved(const std::string& name) {
  return name == "thermal_energy" || name == "kinetic_energy" || is_field(name);
}

double relative_to(double error, double value) {
  return std::isfinite(error) && std::isfinite(value) && value != 0.0 ? error / std::abs(value)
                                                                      : kNoValue;
}

// The rms over the bins of a column's standard errors, over scale; NaN without errors.
double rms_error(const std::vector<double>& stderrs, double scale) {
  if (stderrs.empty()) return kNoValue;
  double sum = 0.0;
  for (double e : stderrs) {
    if (!std::isfinite(e)) return kNoValue;
    sum += e * e;
  }
  return std::sqrt(sum / double(stderrs.size())) / scale;
}

// The error of one time-resolved observable at the reference's i-th compared time, with the
// reference's statistical error there.
ObservableError error_at(const std::string& name, const AtlasRun& run, int at,
                         const AtlasRun& reference, std::size_t i) {
  if (at < 0) return {kNoValue, kNoValue};
  if (name == "thermal_energy") {
    return {atlas::relative_error(run.thermal[at], reference.thermal[i]),
            relative_to(reference.thermal_error[i], reference.thermal[i])};
  }
  if (name == "kinetic_energy") {
    return {atlas::relative_error(run.flow[at], reference.flow[i]),
            relative_to(reference.flow_error[i], reference.flow[i])};
  }
  if (!is_field(name)) return {kNoValue, kNoValue};
  const std::string field = name.substr(6);
  const auto& cand = run.fields->snapshots[at];
  const auto& ref = reference.fields->snapshots[i];
  const auto& column = fields::field_column(field);
  if ((cand.*column.values).empty() || (ref.*column.values).empty() ||
      (cand.*column.values).size() != (ref.*column.values).size()) {
    return {kNoValue, kNoValue};
  }
  const double scale = compare::field_scale(field, ref, cand);
  return {
      compare::deterministic_field_difference(cand.*column.values, ref.*column.values, scale).l2,
      rms_error(ref.*column.standard_error, scale)};
}

}  // namespace

const std::vector<std::string>& atlas_observable_names() {
  static const std::vector<std::string> names = {"crossing_times", "haff_t0", "thermal_energy",
                                                 "kinetic_energy", "field_n", "field_v_x",
                                                 "field_T"};
  return names;
}

ObservableErrors observable_errors(const AtlasRun& run, const AtlasRun& reference,
                                   const std::vector<std::string>& observables) {
  ObservableErrors errors;
  const std::vector<int> at = matching_times(run, reference);
  for (const auto& name : observables) {
    ObservableError worst{kNoValue, kNoValue};
    if (time_resolved(name)) {
      if (!reference.times.empty()) worst.error = 0.0;
      for (std::size_t i = 0; i < reference.times.size() && !std::isnan(worst.error); ++i) {
        const ObservableError e = error_at(name, run, at[i], reference, i);
        if (std::isnan(e.error)) {
          worst.error = kNoValue;
        } else if (e.error >= worst.error) {
          worst = e;  // the reference's error at the time of the largest error
        }
      }
    } else {
      const auto r = reference.scalars.find(name);
      const auto c = run.scalars.find(name);
      if (r != reference.scalars.end() && c != run.scalars.end()) {
        const auto s = reference.scalar_errors.find(name);
        worst = {atlas::relative_error(c->second, r->second),
                 relative_to(s == reference.scalar_errors.end() ? kNoValue : s->second, r->second)};
      }
    }
    if (std::isfinite(worst.error)) errors[name] = worst;
  }
  return errors;
}

std::map<std::string, double> errors_of(const ObservableErrors& errors) {
  std::map<std::string, double> e;
  for (const auto& [k, v] : errors) e[k] = v.error;
  return e;
}

std::map<std::string, double> reference_errors_of(const ObservableErrors& errors) {
  std::map<std::string, double> e;
  for (const auto& [k, v] : errors) {
    if (std::isfinite(v.reference_error)) e[k] = v.reference_error;
  }
  return e;
}

std::map<std::string, double> statistical_errors(const AtlasRun& reference,
                                                 const std::vector<std::string>& observables) {
  // Against itself every error is 0; what is left is the reference's own statistical error,
  // taken at its largest over the compared times.
  std::map<std::string, double> s;
  const std::vector<int> at = matching_times(reference, reference);
  for (const auto& name : observables) {
    double largest = kNoValue;
    if (time_resolved(name)) {
      for (std::size_t i = 0; i < reference.times.size(); ++i) {
        const double e = error_at(name, reference, at[i], reference, i).reference_error;
        if (std::isfinite(e)) largest = std::isfinite(largest) ? std::max(largest, e) : e;
      }
    } else {
      const auto e = observable_errors(reference, reference, {name});
      if (e.count(name)) largest = e.at(name).reference_error;
    }
    if (std::isfinite(largest)) s[name] = largest;
  }
  return s;
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
      const auto it = run.scalars.find(name);
      has = it != run.scalars.end() && std::isfinite(it->second);
    }
    if (has) given.push_back(name);
  }
  return given;
}

std::vector<ObservableError> error_over_time(const AtlasRun& run, const AtlasRun& reference,
                                             const std::vector<std::string>& observables,
                                             double sigmas) {
  const std::vector<int> at = matching_times(run, reference);
  std::vector<ObservableError> worst(reference.times.size(), ObservableError{0.0, kNoValue});
  for (std::size_t i = 0; i < reference.times.size(); ++i) {
    double excess = -1.0;  // the largest error less its allowance, sigmas reference errors
    for (const auto& name : observables) {
      if (!time_resolved(name) || std::isnan(worst[i].error)) continue;
      const ObservableError e = error_at(name, run, at[i], reference, i);
      if (std::isnan(e.error)) {
        worst[i] = {kNoValue, kNoValue};
        continue;
      }
      const double allowance = std::isfinite(e.reference_error) ? sigmas * e.reference_error : 0;
      if (e.error - allowance > excess) excess = e.error - allowance, worst[i] = e;
    }
  }
  return worst;
}

}  // namespace granvv::app
