#include "hydro/time_step.hpp"

#include <cmath>
#include <limits>

#include "hydro/transport.hpp"

namespace granvv::hydro {

TimeStepLimit time_step_limit(const LagrangianState& s, const TimeStepControl& control) {
  const int n = s.cells();
  double sound = std::numeric_limits<double>::infinity();
  double compression = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    const double w = cell_width(s, i);
    sound = std::min(sound, w / sound_speed(s.cell_T[i]));
    const double dv = std::abs(s.node_v[(i + 1) % n] - s.node_v[i]);
    if (dv > 0.0) compression = std::min(compression, w / dv);
  }
  TimeStepLimit limit{control.dt_max, "dt_max"};
  if (control.cfl * sound < limit.dt) limit = {control.cfl * sound, "sound"};
  if (control.max_compression * compression < limit.dt) {
    limit = {control.max_compression * compression, "compression"};
  }
  return limit;
}

}  // namespace granvv::hydro
