#include "atlas/relative_bias.hpp"

#include <cmath>

#include "atlas/work_precision.hpp"

namespace granvv::atlas {

RelativeBias relative_bias(double a, double a_error, double b, double b_error) {
  if (!std::isfinite(a) || !std::isfinite(b) || b == 0.0) return {kNoValue, kNoValue};
  const double sa = std::isfinite(a_error) ? a_error : 0.0;
  const double sb = std::isfinite(b_error) ? b_error : 0.0;
  return {a / b - 1.0, std::hypot(sa / b, a * sb / (b * b))};
}

}  // namespace granvv::atlas
