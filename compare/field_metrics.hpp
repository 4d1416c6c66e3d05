#pragma once
// How far the hydro is from the coarse-grained particles, field by field and time by time,
// measured in the two currencies a physicist asks for: the size of the difference relative to
// the field's natural scale (L1, L2, L-infinity norms over the bins), and whether the particles'
// own statistical error explains it (the fraction of bins where |hydro - MD| < k standard
// errors of the MD mean; for Gaussian noise alone about 99.7 % at k = 3).
#include <optional>
#include <string>
#include <vector>

namespace granvv::compare {

struct FieldDifference {
  double l1 = 0.0, l2 = 0.0, linf = 0.0;  // mean |d|, rms d, max |d|; each divided by scale
  double fraction_within = 0.0;           // of the bins with a finite error
  double worst_z = 0.0;                   // max |d| / error over the bins
  double scale = 1.0;
  int points = 0;  // bins with finite hydro, MD and error
};

// d = hydro - md over the bins where all three are finite and the error is positive. Throws
// std::invalid_argument if the sizes differ or scale or sigmas is not positive. No usable bin gives
// points = 0 and NaN norms.
FieldDifference field_difference(const std::vector<double>& hydro, const std::vector<double>& md,
                                 const std::vector<double>& md_error, double scale, double sigmas);

// The same norms between two models without standard errors (both deterministic: a hydro, an
// exact solution), over the bins where both are finite; fraction_within and worst_z are NaN,
// because there is no error to judge a difference by. Throws like field_difference.
FieldDifference deterministic_field_difference(const std::vector<double>& candidate,
                                               const std::vector<double>& reference, double scale);

// One field's differences at a sequence of output times.
struct FieldTrack {
  std::string field;
  std::vector<FieldDifference> at;  // one per output time
};

// The agreement window: a field agrees at an output time when at least `required_fraction` of
// its bins are within the sigmas of field_difference. `until` is the last output time up to
// which every field agreed at every output time (nullopt: not even at the first); `first_out`
// is the field with the smallest fraction at the first time where any field disagreed, and
// `left_at` that time (both empty if every field agreed throughout).
struct AgreementWindow {
  std::optional<double> until;
  std::string first_out;
  std::optional<double> left_at;
  bool throughout = false;
};

// Whether a field agrees at one time: at least `required_fraction` of its bins lie within the
// sigmas; a difference without usable bins (NaN fraction) does not agree.
bool field_agrees(const FieldDifference& d, double required_fraction);

// Throws std::invalid_argument if a track's length differs from times.size().
AgreementWindow agreement_window(const std::vector<double>& times,
                                 const std::vector<FieldTrack>& tracks, double required_fraction);

}  // namespace granvv::compare
