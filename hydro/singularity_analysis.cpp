#include "hydro/singularity_analysis.hpp"

#include <cmath>

#include "hydro/diagnostics.hpp"

namespace granvv::hydro {

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  LineFit f;
  f.points = static_cast<int>(x.size());
  if (f.points < 2) return f;
  double mx = 0, my = 0;
  for (int i = 0; i < f.points; ++i) mx += x[i], my += y[i];
  mx /= f.points, my /= f.points;
  double sxx = 0, sxy = 0;
  for (int i = 0; i < f.points; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  f.slope = sxx > 0 ? sxy / sxx : 0.0;
  f.intercept = my - f.slope * mx;
  return f;
}

std::optional<SingularityFit> fit_singularity_time(const std::vector<double>& t,
                                                   const std::vector<double>& n_max, double n_lo,
                                                   double n_hi) {
  std::vector<double> ts, inv;
  SingularityFit fit;
  for (size_t i = 0; i < t.size(); ++i) {
    if (n_max[i] < n_lo || n_max[i] > n_hi) continue;
    if (ts.empty()) fit.t_min = t[i], fit.n_min = n_max[i];
    fit.t_max = t[i], fit.n_max = n_max[i];
    ts.push_back(t[i]);
    inv.push_back(1.0 / n_max[i]);
  }
  const LineFit line = fit_line(ts, inv);
  if (line.points < 3 || !(line.slope < 0.0)) return std::nullopt;
  fit.tau = -line.intercept / line.slope;
  fit.points = line.points;
  return fit;
}

std::optional<ProfileSlope> fit_density_profile_slope(const LagrangianState& s, double x_min,
                                                      double x_max) {
  const Diagnostics d = diagnose(s);
  std::vector<double> lx, ln;
  for (int i = 0; i < s.cells(); ++i) {
    const double dist = std::abs(wrap_position(cell_centre(s, i) - d.x_peak));
    if (dist < x_min || dist > x_max) continue;
    lx.push_back(std::log(dist));
    ln.push_back(std::log(s.cell_mass[i] / cell_width(s, i)));
  }
  const LineFit line = fit_line(lx, ln);
  if (line.points < 4) return std::nullopt;
  return ProfileSlope{line.slope, x_min, x_max, line.points};
}

double inertia_collapse_error(const LagrangianState& s, const std::function<double(double)>& v0,
                              double scale) {
  double worst = 0.0;
  for (int j = 0; j < s.cells(); ++j) {
    const double xi = s.node_x[j] - s.t * s.node_v[j];
    worst = std::max(worst, std::abs(s.node_v[j] - v0(xi)) / scale);
  }
  return worst;
}

}  // namespace granvv::hydro
