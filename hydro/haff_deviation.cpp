#include "hydro/haff_deviation.hpp"

#include <algorithm>
#include <cmath>

#include "hydro/haff.hpp"

namespace granvv::hydro {

double haff_max_relative_error(const std::vector<double>& t, const std::vector<double>& T_mean,
                               double t0) {
  double worst = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    worst = std::max(worst, std::abs(T_mean[i] / haff_temperature(t[i], t0) - 1.0));
  }
  return worst;
}

}  // namespace granvv::hydro
