#pragma once
// Measurements near the flow-by-inertia singularity (paper Eqs. 5-7 and Fig. 4):
// tau from the straight line of 1/n_max(t), the log-log slope of the density profile
// (paper: n ~ |x|^{-2/3}), and the collapse of v against xi = x - t v onto v0(xi) (Fig. 3).
#include <functional>
#include <optional>
#include <vector>

#include "hydro/lagrangian_state.hpp"

namespace granvv::hydro {

struct LineFit {
  double slope = 0.0, intercept = 0.0;
  int points = 0;
};
// Least-squares line y = slope x + intercept.
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

struct SingularityFit {
  double tau = 0.0;                 // where the fitted 1/n_max(t) reaches zero
  double t_min = 0.0, t_max = 0.0;  // the fitted window in t
  double n_min = 0.0, n_max = 0.0;  // ... and in density
  int points = 0;
};
// Paper Fig. 4a: the fitted singularity time "agrees with [tau = 1/(2 pi |a|)] within 2 %",
// the relative deviation from flow by inertia's tau that a run's singularity time is judged by.
inline constexpr double kSingularityTimeTolerance = 0.02;

// Fit 1/n_max(t) over the samples with n_min <= n_max(t) <= n_max (paper Fig. 4a inset).
std::optional<SingularityFit> fit_singularity_time(const std::vector<double>& t,
                                                   const std::vector<double>& n_max, double n_min,
                                                   double n_hi);

struct ProfileSlope {
  double slope = 0.0;
  double x_min = 0.0, x_max = 0.0;
  int points = 0;
};
// Log-log slope of the cell density against the distance |x - x_peak| from the densest
// cell, over cells with x_min <= |x - x_peak| <= x_max (both sides of the peak).
std::optional<ProfileSlope> fit_density_profile_slope(const LagrangianState& s, double x_min,
                                                      double x_max);

// Paper Fig. 3: the node velocities against xi = x - t v compared with the initial profile,
// max_j |v_j - v0(xi_j)| / scale.
double inertia_collapse_error(const LagrangianState& s, const std::function<double(double)>& v0,
                              double scale);

}  // namespace granvv::hydro
