#include "compare/field_metrics.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace granvv::compare {

FieldDifference field_difference(const std::vector<double>& hydro, const std::vector<double>& md,
                                 const std::vector<double>& md_error, double scale, double sigmas) {
  if (hydro.size() != md.size() || md.size() != md_error.size()) {
    throw std::invalid_argument("field_difference: hydro, md and error differ in length");
  }
  if (!(scale > 0.0) || !std::isfinite(scale) || !(sigmas > 0.0)) {
    throw std::invalid_argument("field_difference: scale and sigmas must be positive");
  }
  FieldDifference f;
  f.scale = scale;
  double sum = 0.0, sum2 = 0.0;
  int within = 0;
  for (std::size_t i = 0; i < hydro.size(); ++i) {
    const double d = hydro[i] - md[i], e = md_error[i];
    if (!std::isfinite(d) || !std::isfinite(e) || !(e > 0.0)) continue;
    ++f.points;
    sum += std::abs(d), sum2 += d * d;
    f.linf = std::max(f.linf, std::abs(d));
    f.worst_z = std::max(f.worst_z, std::abs(d) / e);
    if (std::abs(d) < sigmas * e) ++within;
  }
  if (f.points == 0) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    f.l1 = f.l2 = f.linf = f.fraction_within = f.worst_z = nan;
    return f;
  }
  f.l1 = sum / f.points / scale;
  f.l2 = std::sqrt(sum2 / f.points) / scale;
  f.linf /= scale;
  f.fraction_within = double(within) / f.points;
  return f;
}

FieldDifference deterministic_field_difference(const std::vector<double>& candidate,
                                               const std::vector<double>& reference, double scale) {
  // Unit errors and infinitely many sigmas: every finite bin counts, none is judged.
  FieldDifference f =
      field_difference(candidate, reference, std::vector<double>(reference.size(), 1.0), scale,
                       std::numeric_limits<double>::infinity());
  f.fraction_within = f.worst_z = std::numeric_limits<double>::quiet_NaN();
  return f;
}

bool field_agrees(const FieldDifference& d, double required_fraction) {
  return !std::isnan(d.fraction_within) && d.fraction_within >= required_fraction;
}

AgreementWindow agreement_window(const std::vector<double>& times,
                                 const std::vector<FieldTrack>& tracks, double required_fraction) {
  for (const auto& track : tracks) {
    if (track.at.size() != times.size()) {
      throw std::invalid_argument("agreement_window: field " + track.field + " has " +
                                  std::to_string(track.at.size()) + " entries for " +
                                  std::to_string(times.size()) + " times");
    }
  }
  AgreementWindow w;
  for (std::size_t k = 0; k < times.size(); ++k) {
    // A field without usable bins (NaN) cannot be said to agree; it ranks below every number.
    auto rank = [k](const FieldTrack& t) {
      const double f = t.at[k].fraction_within;
      return std::isnan(f) ? -1.0 : f;
    };
    const FieldTrack* worst = nullptr;
    for (const auto& track : tracks) {
      if (field_agrees(track.at[k], required_fraction)) continue;
      if (!worst || rank(track) < rank(*worst)) worst = &track;
    }
    if (worst) {
      w.first_out = worst->field;
      w.left_at = times[k];
      return w;
    }
    w.until = times[k];
  }
  w.throughout = true;
  return w;
}

}  // namespace granvv::compare
