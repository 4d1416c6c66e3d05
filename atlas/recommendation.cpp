#include "atlas/recommendation.hpp"

#include <cmath>

namespace granvv::atlas {

bool adequate(const Candidate& candidate, const std::vector<std::string>& observables,
              double tolerance) {
  for (const auto& name : observables) {
    const auto it = candidate.error.find(name);
    if (it == candidate.error.end() || !(it->second <= tolerance)) return false;
  }
  return true;
}

std::optional<std::size_t> cheapest_adequate(const std::vector<Candidate>& candidates,
                                             const std::vector<std::string>& observables,
                                             double tolerance) {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (!adequate(candidates[i], observables, tolerance)) continue;
    if (!best || candidates[i].wall_seconds < candidates[*best].wall_seconds) best = i;
  }
  return best;
}

}  // namespace granvv::atlas
