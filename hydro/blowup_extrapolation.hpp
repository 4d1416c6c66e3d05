#pragma once
// When the peak density of flow by inertia diverges (paper Eqs. 5-7, Fig. 4; docs/physics.md
// §3). Near the singularity 1/n_max(t) falls to zero linearly in t, n_max ~ 1/(tau - t).
// fit_singularity_time (hydro/singularity_analysis.hpp) fits that line over a density window;
// pressure in the peak bends 1/n_max(t) there, so the line through the last two samples of a
// run stopped at the singularity is a tighter estimate of tau:
//   u = 1/n_max,  tau = t_1 + u_1 (t_1 - t_0) / (u_0 - u_1).
#include <optional>
#include <vector>

namespace granvv::hydro {

// The root of the straight line through the last two samples of 1/n_max(t); nullopt with
// fewer than two samples or when n_max did not grow over the last step.
std::optional<double> extrapolate_blowup_time(const std::vector<double>& t,
                                              const std::vector<double>& n_max);

}  // namespace granvv::hydro
