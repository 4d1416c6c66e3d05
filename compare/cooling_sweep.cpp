#include "compare/cooling_sweep.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace granvv::compare {

CoolingSweep analyse_cooling_sweep(const std::vector<CoolingPoint>& points, double power_r_min,
                                   double sigmas) {
  CoolingSweep s;
  s.power_r_min = power_r_min;
  std::vector<double> x, y, dy;
  for (const auto& p : points) {
    if (!(p.t0 > 0) || !(p.t0_error > 0) || !std::isfinite(p.t0) || !std::isfinite(p.t0_error) ||
        !(p.restitution > 0 && p.restitution < 1)) {
      throw std::invalid_argument(
          "analyse_cooling_sweep: the point at r = " + std::to_string(p.restitution) +
          " needs r in (0, 1) and a positive, finite t0 and error");
    }
    const double zeta = 2.0 / p.t0, err = 2.0 * p.t0_error / (p.t0 * p.t0);
    const double chi = p.t0_dilute / p.t0_enskog;
    s.zeta.push_back(zeta);
    s.zeta_error.push_back(err);
    s.zeta_enskog.push_back(2.0 / p.t0_enskog);
    s.zeta_dilute.push_back(2.0 / p.t0_dilute);
    s.zeta_paper.push_back(2.0 / p.t0_paper);
    s.zeta_paper_enskog.push_back(2.0 * chi / p.t0_paper);
    s.paper_deviation.push_back(s.zeta_paper_enskog.back() / zeta - 1.0);
    s.paper_deviation_sigmas.push_back((s.zeta_paper_enskog.back() - zeta) / err);
    if (std::abs(s.paper_deviation_sigmas.back()) > sigmas &&
        (!s.paper_departs_at || p.restitution > *s.paper_departs_at)) {
      s.paper_departs_at = p.restitution;
    }
    if (p.restitution >= power_r_min) {
      x.push_back(1.0 - p.restitution * p.restitution);
      y.push_back(zeta);
      dy.push_back(err);
    }
  }
  try {
    s.power = fit_power_law(x, y, dy);
  } catch (const std::invalid_argument&) {
    s.power.reset();  // fewer than two distinct restitutions above power_r_min
  }
  return s;
}

}  // namespace granvv::compare
