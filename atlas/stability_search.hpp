#pragma once
// A stability map's boundary along one cost knob (docs/atlas.md): the knob is pushed from a
// setting that works toward failure by a constant factor per probe, and the first failure is
// then bracketed by bisection on a log scale, so the boundary is known to within
// factor^(1/2^refinements).
#include <functional>
#include <string>

namespace granvv::atlas {

struct StabilityBoundary {
  double stable = 0.0;  // the last knob value that worked
  double failed = 0.0;  // the first that failed (0 if none failed within the probes)
  std::string failure;  // how it failed at `failed` (empty if none did)
  int probes = 0;       // runs made
};

// probe(knob) returns "" when the method works at that knob value and the name of its failure
// otherwise. start must work (the caller's default); factor > 1 pushes the knob up, < 1 down.
// At most max_steps pushes, then `refinements` bisections. Throws std::invalid_argument for a
// factor of 1 or <= 0, or if probe(start) fails.
StabilityBoundary find_stability_boundary(double start, double factor, int max_steps,
                                          int refinements,
                                          const std::function<std::string(double)>& probe);

}  // namespace granvv::atlas
