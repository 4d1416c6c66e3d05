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

}  // namespace granvv::compare
