#include "hydro/time_step.hpp"

#include <cmath>
#include <limits>

#include "hydro/wide_loops.hpp"

namespace granvv::hydro {

TimeStepLimiter::TimeStepLimiter(const Closure& closure, const TimeStepControl& control)
    : closure_(closure), control_(control) {}

GRANVV_WIDE_LOOPS
TimeStepLimit TimeStepLimiter::limit(const LagrangianState& s, const CellGeometry& cells) {
  const int n = s.cells();
  closure_.sound_speed(cells.density, s.cell_T, sound_speed_);
  double sound = std::numeric_limits<double>::infinity();
  double compression = std::numeric_limits<double>::infinity();
  // The smallest w/c and w/|dv|, compared as products (c, |dv| >= 0) and divided only where a
  // cell beats the smallest so far; |dv| = 0 sets no limit (0 * inf is NaN, never smaller).
  const auto scan = [&](int i, int next) {
    const double w = cells.width[i], c = sound_speed_[i];
    const double dv = std::abs(s.node_v[next] - s.node_v[i]);
    if (w < sound * c) sound = std::min(sound, w / c);
    if (w < compression * dv) compression = std::min(compression, w / dv);
  };
  for (int i = 0; i + 1 < n; ++i) scan(i, i + 1);
  scan(n - 1, 0);
  TimeStepLimit limit{control_.dt_max, "dt_max"};
  if (control_.cfl * sound < limit.dt) limit = {control_.cfl * sound, "sound"};
  if (control_.max_compression * compression < limit.dt) {
    limit = {control_.max_compression * compression, "compression"};
  }
  return limit;
}

}  // namespace granvv::hydro
