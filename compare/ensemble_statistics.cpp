#include "compare/ensemble_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace granvv::compare {

EnsembleStatistics ensemble_statistics(const std::vector<std::vector<double>>& members) {
  std::size_t length = 0;
  for (const auto& m : members) length = std::max(length, m.size());
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  EnsembleStatistics out;
  out.mean.assign(length, nan);
  out.standard_error.assign(length, nan);
  out.members.assign(length, 0);
  for (std::size_t i = 0; i < length; ++i) {
    // Two passes (mean, then squared deviations): no cancellation when the spread is small.
    double sum = 0.0;
    int k = 0;
    for (const auto& m : members) {
      if (i < m.size() && std::isfinite(m[i])) sum += m[i], ++k;
    }
    out.members[i] = k;
    if (k == 0) continue;
    const double mean = sum / k;
    out.mean[i] = mean;
    if (k < 2) continue;
    double squares = 0.0;
    for (const auto& m : members) {
      if (i < m.size() && std::isfinite(m[i])) squares += (m[i] - mean) * (m[i] - mean);
    }
    out.standard_error[i] = std::sqrt(squares / (k - 1) / k);
  }
  return out;
}

}  // namespace granvv::compare
