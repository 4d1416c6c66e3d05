#include "hydro/linear_mode_measurement.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "fields/constants.hpp"
#include "hydro/haff.hpp"
#include "hydro/linear_stability.hpp"
#include "hydro/singularity_analysis.hpp"

namespace granvv::hydro {

namespace {

// Complex Fourier amplitudes (nu, w, theta) of mode k, X(x) = Re(X_k e^{i 2 pi k x}), with
// n = 1 + nu, v = T_H^{1/2} w, T = T_H (1 + theta) and T_H Haff's law at the state's time.
// Cell fields are integrated exactly over each cell; node velocities by the midpoint rule.
Eigen::Vector3cd hcs_mode_amplitudes(const LagrangianState& s, const Closure& closure, int k) {
  using cd = std::complex<double>;
  const double kx = 2.0 * kPi * k;
  const double TH = haff_temperature(s.t, haff_time_scale(closure));
  const int n = s.cells();
  auto e = [kx](double x) { return std::exp(cd(0.0, -kx * x)); };
  cd nu = 0.0, u = 0.0, theta = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x0 = s.node_x[i], w = cell_width(s, i), x1 = x0 + w;
    const cd cell_integral = (e(x1) - e(x0)) / cd(0.0, -kx);  // integral of e^{-ikx x}
    nu += (s.cell_mass[i] / w - 1.0) * cell_integral;
    theta += (s.cell_T[i] / TH - 1.0) * cell_integral;
    const double node_span = 0.5 * (cell_width(s, (i + n - 1) % n) + w);
    u += s.node_v[i] * node_span * e(x0);
  }
  return Eigen::Vector3cd(2.0 * nu, 2.0 * u / std::sqrt(TH), 2.0 * theta);
}

}  // namespace

MeasuredRate measure_linear_rate(const std::vector<LagrangianState>& snapshots,
                                 const Closure& closure, int k, int branch) {
  const auto modes = hcs_modes(closure, k);
  Eigen::Matrix3cd V;
  for (int b = 0; b < 3; ++b) V.col(b) = modes[b].eigenvector;
  const auto lu = V.partialPivLu();
  const double t0 = haff_time_scale(closure);
  std::vector<double> s, log_modulus, phase;
  for (const auto& snap : snapshots) {
    const Eigen::Vector3cd c = lu.solve(hcs_mode_amplitudes(snap, closure, k));
    const std::complex<double> cb = c[branch];
    s.push_back(collision_clock(snap.t, t0));
    log_modulus.push_back(std::log(std::abs(cb)));
    double p = std::arg(cb);
    if (!phase.empty()) p += 2.0 * kPi * std::round((phase.back() - p) / (2.0 * kPi));
    phase.push_back(p);
  }
  MeasuredRate r;
  r.samples = static_cast<int>(s.size());
  r.measured = {fit_line(s, log_modulus).slope, fit_line(s, phase).slope};
  r.theory = modes[branch].rate;
  r.relative_error = std::abs(r.measured - r.theory) / std::abs(r.theory);
  return r;
}

}  // namespace granvv::hydro
