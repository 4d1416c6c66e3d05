#pragma once
// What kind a disagreement between the hydro and the particles is (docs/physics.md §8).
//
// The particles' fluctuations, amplified by the unstable modes of the cooling gas, shape the
// coarse-grained profiles of a weakly driven run; a deterministic hydro cannot follow them, and
// the fields part without any failure of the hydro. The difference is the model's ("model")
// when either
//  - the imposed flow is clear of the thermal noise on the bin scale: signal-to-noise
//    (max |v0| over the velocity noise of a bin mean) >= signal_to_noise_min = 3, or
//  - the first field to part is off as a whole: its box mean of hydro - MD is beyond
//    offset_sigmas standard errors of that mean (a different cooling rate, say), which
//    fluctuations of zero mean cannot make;
// otherwise it is the particles' noise ("noise"), and "none" when every field agreed at every
// compared time.
#include <string>
#include <vector>

#include "compare/field_metrics.hpp"

namespace granvv::compare {

// The signal-to-noise from which the imposed flow counts as clear of the particles' noise: its
// amplitude three times the velocity noise of one bin mean.
inline constexpr double kClearSignalToNoise = 3.0;

struct VerdictRule {
  double signal_to_noise_min = kClearSignalToNoise;
  double offset_sigmas = 0.0;  // the case's compare.sigmas
};

enum class Disagreement {
  none,                // every field agreed at every compared time
  model_clear_signal,  // the signal is clear of the noise and the fields still part
  model_box_offset,    // the box mean of the first field to part is off beyond offset_sigmas
  noise,               // neither: the particles' own fluctuations
};

// "none", "model" (both model kinds) or "noise": the names summary.json and results.h5 carry.
const char* disagreement_name(Disagreement kind);

// The rule above; offset_in_sigmas is box_mean_offset of the first field to part. The
// signal-to-noise is tested first: at or above its minimum the kind is model_clear_signal
// whatever the offset. A NaN signal-to-noise or offset does not count as beyond its threshold.
Disagreement classify_disagreement(bool agreed_throughout, double signal_to_noise,
                                   double offset_in_sigmas, const VerdictRule& rule);

// The box mean of hydro - md over the bins, in standard errors of that mean, with the bins'
// errors independent: sum d_b / sqrt(sum e_b^2) (the mean sum d / B has the error
// sqrt(sum e^2) / B). Bins with a non-finite difference or without a positive error are left
// out; 0 when none is left.
double box_mean_offset(const std::vector<double>& hydro, const std::vector<double>& md,
                       const std::vector<double>& md_error);

// The one-line verdict of a comparison: the agreement window at `agreement_sigmas` (the
// field_difference tolerance), the signal-to-noise, and what the kind of disagreement means.
// last_time: the last compared time (NaN if there is none).
std::string verdict_sentence(const AgreementWindow& window, double last_time,
                             double agreement_sigmas, double signal_to_noise,
                             double offset_in_sigmas, Disagreement kind);

}  // namespace granvv::compare
