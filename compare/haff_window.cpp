#include "compare/haff_window.hpp"

#include <cmath>
#include <limits>

namespace granvv::compare {

HomogeneousWindow homogeneous_window(const std::vector<double>& t,
                                     const std::vector<double>& fraction, double threshold,
                                     double t_end) {
  HomogeneousWindow w;
  w.t_max = t_end;
  w.onset = std::numeric_limits<double>::quiet_NaN();
  bool first = true;
  double last_below = t_end;
  for (std::size_t i = 0; i < t.size() && i < fraction.size(); ++i) {
    if (!std::isfinite(fraction[i])) continue;
    if (fraction[i] > threshold) {
      w.onset = t[i];
      if (first) {
        w.starts_homogeneous = false;
      } else {
        w.t_max = last_below;
      }
      return w;
    }
    first = false;
    last_below = t[i];
  }
  return w;
}

}  // namespace granvv::compare
