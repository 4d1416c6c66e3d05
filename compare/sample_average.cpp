#include "compare/sample_average.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace granvv::compare {

SampleAverage sample_average(const std::vector<std::vector<double>>& values,
                             const std::vector<std::vector<double>>& errors) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> means, propagated;
  for (std::size_t m = 0; m < values.size(); ++m) {
    double sum = 0.0, variance = 0.0;
    int samples = 0;
    for (std::size_t s = 0; s < values[m].size(); ++s) {
      if (!std::isfinite(values[m][s])) continue;
      sum += values[m][s];
      const double e = m < errors.size() && s < errors[m].size() ? errors[m][s] : nan;
      variance += e * e;
      ++samples;
    }
    if (samples == 0) continue;
    means.push_back(sum / samples);
    propagated.push_back(std::sqrt(variance) / samples);
  }
  SampleAverage a;
  a.members = int(means.size());
  if (means.empty()) {
    a.mean = a.error = nan;
    return a;
  }
  double sum = 0.0;
  for (double m : means) sum += m;
  a.mean = sum / double(means.size());
  if (means.size() == 1) {
    a.error = propagated.front();
    return a;
  }
  double squares = 0.0, propagated_squares = 0.0;
  for (double m : means) squares += (m - a.mean) * (m - a.mean);
  for (double e : propagated) propagated_squares += e * e;
  const double scatter = std::sqrt(squares / double(means.size() - 1) / double(means.size()));
  const double model = std::sqrt(propagated_squares) / double(means.size());
  a.error = std::isfinite(model) ? std::max(scatter, model) : scatter;
  return a;
}

}  // namespace granvv::compare
