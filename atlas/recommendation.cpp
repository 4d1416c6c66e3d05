#include "atlas/recommendation.hpp"

#include <cmath>

namespace granvv::atlas {

bool within_tolerance(double error, double reference_error, double tolerance, double sigmas) {
  const double s = std::isfinite(reference_error) && reference_error > 0.0 ? reference_error : 0.0;
  return error <= tolerance + sigmas * s;  // false for a NaN error
}

bool adequate(const Candidate& candidate, const std::vector<std::string>& observables,
              double tolerance, double sigmas) {
  for (const auto& name : observables) {
    const auto it = candidate.error.find(name);
    if (it == candidate.error.end()) return false;
    const auto s = candidate.reference_error.find(name);
    const double reference_error = s == candidate.reference_error.end() ? 0.0 : s->second;
    if (!within_tolerance(it->second, reference_error, tolerance, sigmas)) return false;
  }
  return true;
}

std::optional<std::size_t> cheapest_adequate(const std::vector<Candidate>& candidates,
                                             const std::vector<std::string>& observables,
                                             double tolerance, double sigmas) {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (!adequate(candidates[i], observables, tolerance, sigmas)) continue;
    if (!best || candidates[i].wall_seconds < candidates[*best].wall_seconds) best = i;
  }
  return best;
}

}  // namespace granvv::atlas
