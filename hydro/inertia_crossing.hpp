#pragma once
// When the peak density of flow by inertia (paper Eq. 5) first reaches a level: every fluid
// element keeps n = n0(xi) / (1 + t v0'(xi)), which grows with t where v0' < 0, so the peak
// max_xi n(xi, t) is non-decreasing and crosses each level once before the singularity time.
#include "hydro/flow_by_inertia.hpp"

namespace granvv::hydro {

// The largest density over the labels at time t in [0, tau): the maximum over `samples`
// equispaced labels and the singular label xi*, where the peak forms as t -> tau.
double inertia_peak_density(const FlowByInertia& flow, double t, int samples = 4096);

// The first t with inertia_peak_density(t) >= level, by bisection to round-off on [0, tau); 0 if
// the initial peak already reaches it. For n0 = 1 it is tau (1 - 1/level) exactly at xi*.
// NaN if tau is infinite (no flow that converges).
double inertia_crossing_time(const FlowByInertia& flow, double level, int samples = 4096);

}  // namespace granvv::hydro
