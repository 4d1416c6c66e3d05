#include "hydro/blowup_extrapolation.hpp"

namespace granvv::hydro {

std::optional<double> extrapolate_blowup_time(const std::vector<double>& t,
                                              const std::vector<double>& n_max) {
  if (t.size() < 2 || n_max.size() != t.size()) return std::nullopt;
  const std::size_t last = t.size() - 1;
  if (!(n_max[last] > n_max[last - 1])) return std::nullopt;
  const double u0 = 1.0 / n_max[last - 1], u1 = 1.0 / n_max[last];
  return t[last] + u1 * (t[last] - t[last - 1]) / (u0 - u1);
}

}  // namespace granvv::hydro
