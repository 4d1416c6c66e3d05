#include "atlas/work_precision.hpp"

#include <cmath>

namespace granvv::atlas {

double relative_error(double candidate, double reference) {
  if (!std::isfinite(candidate) || !std::isfinite(reference)) {
    return kNoValue;
  }
  if (reference == 0.0) return std::abs(candidate);
  return std::abs(candidate / reference - 1.0);
}

double largest_relative_error(const std::vector<double>& candidate,
                              const std::vector<double>& reference) {
  if (candidate.size() != reference.size() || candidate.empty()) return kNoValue;
  double worst = 0.0;
  for (std::size_t i = 0; i < candidate.size(); ++i) {
    const double e = relative_error(candidate[i], reference[i]);
    if (std::isnan(e)) return kNoValue;
    worst = std::max(worst, e);
  }
  return worst;
}

std::vector<bool> pareto_front(const std::vector<double>& cost, const std::vector<double>& error) {
  const std::size_t n = cost.size();
  std::vector<bool> front(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(cost[i]) || !std::isfinite(error[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < n && !dominated; ++j) {
      if (j == i || !std::isfinite(cost[j]) || !std::isfinite(error[j])) continue;
      dominated =
          cost[j] <= cost[i] && error[j] <= error[i] && (cost[j] < cost[i] || error[j] < error[i]);
    }
    front[i] = !dominated;
  }
  return front;
}

}  // namespace granvv::atlas
