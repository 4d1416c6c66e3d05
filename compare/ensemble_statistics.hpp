#pragma once
// Mean and standard error over an ensemble of independent runs (seeds), element by element.
// The standard error of the mean over k members is s / sqrt(k), s the sample standard deviation
// (Bessel-corrected); it needs k >= 2 and is NaN otherwise. Members may be ragged (a run that
// stopped early) and non-finite entries (an empty bin) are skipped.
#include <vector>

namespace granvv::compare {

struct EnsembleStatistics {
  std::vector<double> mean, standard_error;
  std::vector<int> members;  // how many finite values entered each element
};

// Element i over all members that have an element i; the result is as long as the longest
// member.
EnsembleStatistics ensemble_statistics(const std::vector<std::vector<double>>& members);

}  // namespace granvv::compare
