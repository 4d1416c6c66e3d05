#pragma once
// The measures of a work-precision diagram (docs/atlas.md): the error of a model's observable
// against a reference, and the Pareto front of error against cost.
#include <limits>
#include <vector>

namespace granvv::atlas {

// What a run does not give (an observable, an error, a time it did not reach): NaN in memory,
// null in JSON, NaN in HDF5 (docs/atlas.md).
inline constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

// |candidate / reference - 1|; |candidate| when the reference is 0; NaN when either is not finite.
double relative_error(double candidate, double reference);

// The largest relative_error over paired values (the same times); NaN if the sizes differ, the
// series are empty or any pair is not finite, because then the model did not reach a compared time.
double largest_relative_error(const std::vector<double>& candidate,
                              const std::vector<double>& reference);

// A point is on the Pareto front when no other point is at most as costly and at most as wrong,
// and better in one of the two. Points with a NaN cost or error are never on it.
std::vector<bool> pareto_front(const std::vector<double>& cost, const std::vector<double>& error);

}  // namespace granvv::atlas
