#include "hydro/time_step.hpp"

#include <cmath>
#include <limits>

namespace granvv::hydro {

TimeStepLimiter::TimeStepLimiter(const Closure& closure, const TimeStepControl& control)
    : closure_(closure), control_(control) {}

TimeStepLimit TimeStepLimiter::limit(const LagrangianState& s) {
  const int n = s.cells();
  widths_.resize(n);
  density_.resize(n);
  for (int i = 0; i < n; ++i) {
    widths_[i] = cell_width(s, i);
    density_[i] = s.cell_mass[i] / widths_[i];
  }
  closure_.sound_speed(density_, s.cell_T, sound_speed_);
  double sound = std::numeric_limits<double>::infinity();
  double compression = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    const double w = widths_[i];
    sound = std::min(sound, w / sound_speed_[i]);
    const double dv = std::abs(s.node_v[(i + 1) % n] - s.node_v[i]);
    if (dv > 0.0) compression = std::min(compression, w / dv);
  }
  TimeStepLimit limit{control_.dt_max, "dt_max"};
  if (control_.cfl * sound < limit.dt) limit = {control_.cfl * sound, "sound"};
  if (control_.max_compression * compression < limit.dt) {
    limit = {control_.max_compression * compression, "compression"};
  }
  return limit;
}

}  // namespace granvv::hydro
