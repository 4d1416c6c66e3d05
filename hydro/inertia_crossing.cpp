#include "hydro/inertia_crossing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace granvv::hydro {
namespace {

double density_of_label(const FlowByInertia& flow, double xi, double t) {
  const double stretch = 1.0 + t * flow.initial_velocity_derivative()(xi);
  return stretch > 0.0 ? flow.initial_density()(xi) / stretch
                       : std::numeric_limits<double>::infinity();
}

}  // namespace

double inertia_peak_density(const FlowByInertia& flow, double t, int samples) {
  double peak = 0.0;
  for (int i = 0; i < samples; ++i) {
    peak = std::max(peak, density_of_label(flow, -0.5 + double(i) / samples, t));
  }
  if (std::isfinite(flow.singularity_time())) {
    peak = std::max(peak, density_of_label(flow, flow.singular_label(), t));
  }
  return peak;
}

double inertia_crossing_time(const FlowByInertia& flow, double level, int samples) {
  const double tau = flow.singularity_time();
  if (!std::isfinite(tau)) return std::numeric_limits<double>::quiet_NaN();
  if (inertia_peak_density(flow, 0.0, samples) >= level) return 0.0;
  double lo = 0.0, hi = tau;
  while (true) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    (inertia_peak_density(flow, mid, samples) >= level ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace granvv::hydro
