#pragma once
// "Model no more than the scene needs" (docs/atlas.md): of the runs of a scene's ladder, the
// cheapest one whose error against the richest model meets the tolerance on every observable
// the atlas judges.
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace granvv::atlas {

struct Candidate {
  double wall_seconds = 0.0;
  // Model error per observable (relative, against the richest model). An observable the run
  // does not give (flow by inertia has no temperature) is missing here, and the run is then
  // not adequate for it.
  std::map<std::string, double> error;
};

// The index of the cheapest candidate (by wall seconds) with error <= tolerance on every one of
// `observables`; nullopt if none meets it.
std::optional<std::size_t> cheapest_adequate(const std::vector<Candidate>& candidates,
                                             const std::vector<std::string>& observables,
                                             double tolerance);

// Whether one candidate meets the tolerance on every observable.
bool adequate(const Candidate& candidate, const std::vector<std::string>& observables,
              double tolerance);

}  // namespace granvv::atlas
