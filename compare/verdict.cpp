#include "compare/verdict.hpp"

#include <cmath>
#include <sstream>

namespace granvv::compare {

const char* disagreement_name(Disagreement kind) {
  switch (kind) {
    case Disagreement::none:
      return "none";
    case Disagreement::model_clear_signal:
    case Disagreement::model_box_offset:
      return "model";
    case Disagreement::noise:
      break;
  }
  return "noise";
}

Disagreement classify_disagreement(bool agreed_throughout, double signal_to_noise,
                                   double offset_in_sigmas, const VerdictRule& rule) {
  if (agreed_throughout) return Disagreement::none;
  if (signal_to_noise >= rule.signal_to_noise_min) return Disagreement::model_clear_signal;
  if (std::abs(offset_in_sigmas) > rule.offset_sigmas) return Disagreement::model_box_offset;
  return Disagreement::noise;
}

double box_mean_offset(const std::vector<double>& hydro, const std::vector<double>& md,
                       const std::vector<double>& md_error) {
  double sum = 0.0, var = 0.0;
  for (std::size_t b = 0; b < hydro.size(); ++b) {
    const double d = hydro[b] - md[b], e = md_error[b];
    if (!std::isfinite(d) || !(e > 0)) continue;
    sum += d, var += e * e;
  }
  return var > 0 ? sum / std::sqrt(var) : 0.0;
}

std::string verdict_sentence(const AgreementWindow& window, double last_time,
                             double agreement_sigmas, double signal_to_noise,
                             double offset_in_sigmas, Disagreement kind) {
  std::ostringstream v;
  v.precision(4);
  if (window.throughout) {
    v << "fields agree within " << agreement_sigmas
      << " sigma at every compared time up to t = " << last_time;
  } else if (window.until) {
    v << "fields agree within " << agreement_sigmas << " sigma until t = " << *window.until
      << "; first to part: " << window.first_out << " (at t = " << *window.left_at << ")";
  } else if (window.left_at) {
    v << "fields differ beyond " << agreement_sigmas << " sigma from the first compared time; "
      << "worst: " << window.first_out;
  } else {
    v << "no common output time";
  }
  v << " [signal/noise " << signal_to_noise;
  switch (kind) {
    case Disagreement::noise:
      v << ": the imposed flow is not well above the particles' noise and the box means agree, "
           "so the difference is noise-driven, not a failure of the hydro";
      break;
    case Disagreement::model_clear_signal:
      v << ": the signal is clear of the noise, so the difference is the hydro's";
      break;
    case Disagreement::model_box_offset:
      v << "; the box mean of " << window.first_out << " is off by " << offset_in_sigmas
        << " standard errors, which zero-mean noise cannot make: the difference is the hydro's";
      break;
    case Disagreement::none:
      break;
  }
  v << "]";
  return v.str();
}

}  // namespace granvv::compare
