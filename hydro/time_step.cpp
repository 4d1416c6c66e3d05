#include "hydro/time_step.hpp"

#include <cmath>
#include <limits>

namespace granvv::hydro {

TimeStepLimiter::TimeStepLimiter(const Closure& closure, const TimeStepControl& control)
    : closure_(closure), control_(control) {}

TimeStepLimit TimeStepLimiter::limit(const LagrangianState& s, const CellGeometry& cells) {
  const int n = s.cells();
  closure_.sound_speed(cells.density, s.cell_T, sound_speed_);
  double sound = std::numeric_limits<double>::infinity();
  double compression = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    const double w = cells.width[i];
    sound = std::min(sound, w / sound_speed_[i]);
    const double dv = std::abs(s.node_v[i + 1 < n ? i + 1 : 0] - s.node_v[i]);
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
