#include "compare/cooling_sweep.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace granvv::compare {

CoolingSweep analyse_cooling_sweep(const std::vector<CoolingPoint>& points, double power_r_min,
                                   double sigmas) {
  CoolingSweep s;
  s.sigmas = sigmas;
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
    s.enskog_deviation.push_back(p.t0 / p.t0_enskog - 1.0);
    s.enskog_deviation_sigmas.push_back((p.t0 - p.t0_enskog) / p.t0_error);
    s.enskog_beyond_sigmas.push_back(std::abs(s.enskog_deviation_sigmas.back()) > sigmas);
    s.zeta.push_back(zeta);
    s.zeta_error.push_back(err);
    s.zeta_enskog.push_back(2.0 / p.t0_enskog);
    s.zeta_dilute.push_back(2.0 / p.t0_dilute);
    s.zeta_paper.push_back(2.0 / p.t0_paper);
    s.zeta_paper_enskog.push_back(2.0 * chi / p.t0_paper);
    s.paper_deviation.push_back(s.zeta_paper_enskog.back() / zeta - 1.0);
    s.paper_deviation_sigmas.push_back((s.zeta_paper_enskog.back() - zeta) / err);
    s.paper_beyond_sigmas.push_back(std::abs(s.paper_deviation_sigmas.back()) > sigmas);
    if (s.paper_beyond_sigmas.back() &&
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
  if (s.power) {
    const double z = (s.power->power - 1.0) / s.power->power_error;
    s.power_deviation_from_one_sigmas = z;
    if (std::isfinite(z)) s.power_consistent_with_one = std::abs(z) <= sigmas;
  }
  return s;
}

}  // namespace granvv::compare
