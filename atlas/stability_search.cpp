#include "atlas/stability_search.hpp"

#include <cmath>
#include <stdexcept>

namespace granvv::atlas {

StabilityBoundary find_stability_boundary(double start, double factor, int max_steps,
                                          int refinements,
                                          const std::function<std::string(double)>& probe) {
  if (!(factor > 0.0) || factor == 1.0) {
    throw std::invalid_argument("find_stability_boundary: the factor must be > 0 and not 1");
  }
  StabilityBoundary b;
  b.stable = start;
  std::string failure = probe(start);
  ++b.probes;
  if (!failure.empty()) {
    throw std::invalid_argument("find_stability_boundary: the start fails (" + failure + ")");
  }
  for (int step = 0; step < max_steps; ++step) {
    const double next = b.stable * factor;
    failure = probe(next);
    ++b.probes;
    if (!failure.empty()) {
      b.failed = next;
      b.failure = failure;
      break;
    }
    b.stable = next;
  }
  if (b.failure.empty()) return b;
  for (int r = 0; r < refinements; ++r) {
    const double middle = std::sqrt(b.stable * b.failed);  // bisection in log(knob)
    failure = probe(middle);
    ++b.probes;
    if (failure.empty()) {
      b.stable = middle;
    } else {
      b.failed = middle;
      b.failure = failure;
    }
  }
  return b;
}

}  // namespace granvv::atlas
