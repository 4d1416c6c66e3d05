#include "compare/ensemble_error_model.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace granvv::compare {

EnsembleMeanError ensemble_mean_error(const std::vector<double>& model_one_member,
                                      const EnsembleStatistics& statistics) {
  const std::size_t bins = model_one_member.size();
  EnsembleMeanError out;
  double ratio_sum = 0.0;
  int ratio_count = 0;
  for (std::size_t b = 0; b < bins; ++b) {
    out.members = std::max(out.members, statistics.members[b]);
    const double k = statistics.members[b], se = statistics.standard_error[b],
                 m = model_one_member[b];
    if (k >= 2 && std::isfinite(se) && m > 0.0 && std::isfinite(m)) {
      ratio_sum += k * se * se / (m * m);
      ++ratio_count;
    }
  }
  out.calibrated = ratio_count > 0;
  out.variance_ratio = out.calibrated ? ratio_sum / ratio_count : 1.0;
  out.error.resize(bins);
  for (std::size_t b = 0; b < bins; ++b) {
    out.error[b] =
        model_one_member[b] * std::sqrt(out.variance_ratio / std::max(1, statistics.members[b]));
  }
  return out;
}

std::string error_source_label(const EnsembleMeanError& error) {
  std::ostringstream s;
  if (error.calibrated) {
    s << "ensemble of " << error.members << " (model error x " << std::sqrt(error.variance_ratio)
      << ")";
  } else {
    s << "single-snapshot model";
  }
  return s.str();
}

}  // namespace granvv::compare
