#pragma once
// The ensemble of an engine's seeds as one FieldSeries: snapshot by snapshot (snapshot s of
// every member that reached it) and bin by bin, the mean over the members as the values and
// its standard error (compare/ensemble_statistics.hpp: NaN with one member) as the *_stderr,
// for every field and the counts. Times, labels and positions are the first member's.
#include <cstddef>
#include <vector>

#include "compare/ensemble_statistics.hpp"
#include "fields/field_series.hpp"

namespace granvv::compare {

// The statistics of one column at snapshot s over the members that have it.
EnsembleStatistics column_statistics(const std::vector<fields::FieldSeries>& members,
                                     std::size_t snapshot,
                                     std::vector<double> fields::FieldSnapshot::*column);

// Throws std::invalid_argument without members.
fields::FieldSeries ensemble_field_series(const std::vector<fields::FieldSeries>& members);

// Units of a particle run in the hydro's scaled variables (docs/physics.md §4): x / length,
// n / density, t / time; v and T are already scaled in MD units (sqrt(T0/m), T0).
struct ScaledUnits {
  double length = 1.0, density = 1.0, time = 1.0;
};

// The particles as a model's fields: the ensemble mean in scaled units, each field's *_stderr the
// error of that mean from one member's snapshot error model (member 0's: the coarse-grainer's
// sqrt(T/N) and T/sqrt(N - 1), Poisson n/sqrt(N) for n), calibrated by the ensemble's scatter
// (compare/ensemble_error_model.hpp). error_source[s][f] labels how the error of field f
// (fields_with_errors order) was made at snapshot s.
struct EnsembleMeanFields {
  fields::FieldSeries fields;
  std::vector<std::vector<std::string>> error_source;
};
// The fields whose errors are calibrated: fields::hydrodynamic_fields() (n, v_x, v_y, T).
const std::vector<std::string>& fields_with_errors();
EnsembleMeanFields ensemble_mean_fields(const std::vector<fields::FieldSeries>& members,
                                        const ScaledUnits& units);

}  // namespace granvv::compare
