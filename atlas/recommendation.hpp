#pragma once
// "Model no more than the scene needs" (docs/atlas.md): of the runs of a scene's ladder, the
// cheapest one whose error against the richest model meets the tolerance on every observable
// the atlas judges, the reference's statistical error allowed for (σ-aware adequacy).
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace granvv::atlas {

// docs/atlas.md, "σ-aware adequacy": an error e (relative, against the reference) is within
// the tolerance when e <= tolerance + sigmas * s, with s the reference's own statistical error
// on the same relative scale (the ensemble standard error of a particle reference). A
// deterministic reference has s = 0 (or NaN: none), and the test is then e <= tolerance. The
// candidate's own scatter is not allowed for: it is part of what the candidate gets wrong.
bool within_tolerance(double error, double reference_error, double tolerance, double sigmas);

struct Candidate {
  double wall_seconds = 0.0;
  // Model error per observable (relative, against the richest model). An observable the run
  // does not give (flow by inertia has no temperature) is missing here, and the run is then
  // not adequate for it.
  std::map<std::string, double> error;
  // The reference's statistical error per observable on the same scale (missing: none).
  std::map<std::string, double> reference_error;
};

// Whether one candidate is within the tolerance (within_tolerance) on every observable.
bool adequate(const Candidate& candidate, const std::vector<std::string>& observables,
              double tolerance, double sigmas);

// The index of the cheapest adequate candidate (by wall seconds); nullopt if none is.
std::optional<std::size_t> cheapest_adequate(const std::vector<Candidate>& candidates,
                                             const std::vector<std::string>& observables,
                                             double tolerance, double sigmas);

}  // namespace granvv::atlas
