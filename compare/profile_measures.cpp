#include "compare/profile_measures.hpp"

#include <cmath>

namespace granvv::compare {

double mass_weighted_mean(const std::vector<double>& n, const std::vector<double>& g) {
  double mass = 0.0, sum = 0.0;
  for (std::size_t b = 0; b < n.size(); ++b) {
    if (std::isfinite(n[b]) && std::isfinite(g[b])) mass += n[b], sum += n[b] * g[b];
  }
  return sum / mass;
}

std::size_t peak_bin(const std::vector<double>& values) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < values.size(); ++i) {
    if (values[i] > values[best]) best = i;
  }
  return best;
}

double periodic_centred_slope(const std::vector<double>& values, std::size_t b) {
  const std::size_t bins = values.size();
  return (values[(b + 1) % bins] - values[(b + bins - 1) % bins]) * bins / 2.0;
}

}  // namespace granvv::compare
