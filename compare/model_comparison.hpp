#pragma once
// Any two models of a scene weighed against each other (fields/model_result.hpp): their fields
// at the times both have, bin by bin, and their common observables.
//
// Fields: the candidate's values against the reference's, with the reference's standard errors
// (the candidate's where the reference has none), on the same bins; two models without errors
// get the norms alone (deterministic_field_difference). The difference of a field is
// measured on a physical scale (compare/field_metrics.hpp): n in n0, v in the reference's thermal
// speed sqrt(T_bar), T in T_bar, with T_bar the reference's mass-weighted mean temperature at
// that time (docs/physics.md §7); the candidate's T_bar where the reference has no temperature
// (flow by inertia), and absolute differences where neither has one.
#include <string>
#include <vector>

#include "compare/field_metrics.hpp"
#include "fields/model_result.hpp"

namespace granvv::compare {

// The scale on which differences of the named field are measured (above).
double field_scale(const std::string& field, const fields::FieldSnapshot& reference,
                   const fields::FieldSnapshot& candidate);

// Snapshot pairs of two series at equal times (fields::same_time), in the reference's order.
std::vector<std::pair<std::size_t, std::size_t>> common_snapshots(
    const fields::FieldSeries& reference, const fields::FieldSeries& candidate);

// One track per named field over the given snapshot pairs. Throws std::invalid_argument if the
// two series are not on the same bins, or a field is missing on either side.
std::vector<FieldTrack> compare_field_series(
    const fields::FieldSeries& reference, const fields::FieldSeries& candidate,
    const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
    const std::vector<std::string>& field_names, double sigmas);

struct ObservableDifference {
  std::string name;
  double reference = 0.0, candidate = 0.0;
  double relative = 0.0;  // candidate / reference - 1
  double sigmas = 0.0;    // |difference| over the combined standard error (NaN without errors)
};

struct ModelComparison {
  std::string reference, candidate;
  std::vector<double> t;  // the times both have fields at
  std::vector<FieldTrack> fields;
  std::vector<ObservableDifference> observables;  // every name both models report
};

// Fields are compared when both models have them (each named field both carry) and the series
// share their bins; observables whenever both report the same name.
ModelComparison compare_models(const fields::ModelResult& reference,
                               const fields::ModelResult& candidate, double sigmas);

}  // namespace granvv::compare
