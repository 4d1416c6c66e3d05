#pragma once
// The time average of a sampled quantity over a run, and over an ensemble of runs, with its
// standard error: with two or more members the scatter of the members' averages / sqrt(M)
// (independent seeds); with one, the single-sample errors propagated as for independent
// samples, sqrt(sum sigma_s^2) / S.
#include <vector>

namespace granvv::compare {

struct SampleAverage {
  double mean = 0.0, error = 0.0;  // NaN when no member has a finite sample
  int members = 0;
};

// values[m][s], errors[m][s] (same shapes); non-finite samples are skipped.
SampleAverage sample_average(const std::vector<std::vector<double>>& values,
                             const std::vector<std::vector<double>>& errors);

}  // namespace granvv::compare
