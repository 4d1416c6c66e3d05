#pragma once
// The time average of a sampled quantity over a run, and over an ensemble of runs, with its
// standard error. Each member's average has the propagated single-sample error
// sqrt(sum sigma_s^2) / S (independent samples); the ensemble's error is the larger of the
// scatter of the members' averages / sqrt(M) and those errors propagated to the mean: with
// the two to four seeds of the shipped scenes the scatter alone has one to three degrees of
// freedom, and the contact virial, a few contacts per sample, is far from Gaussian.
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
