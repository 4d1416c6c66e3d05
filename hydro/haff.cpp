#include "hydro/haff.hpp"

#include <cmath>

#include "hydro/dilute_closure.hpp"

namespace granvv::hydro {

double haff_time_scale(const Closure& closure) {
  return closure.hcs_linearisation().haff_time;
}

double haff_time_scale(const Physics& physics) {
  return haff_time_scale(DiluteClosure(physics));
}

double haff_temperature(double t, double t0) {
  const double g = 1.0 + t / t0;
  return 1.0 / (g * g);
}

double collision_clock(double t, double t0) {
  if (std::isinf(t0)) return t;
  // log1p keeps s = t (1 - t/(2 t0) + ...) accurate for t << t0.
  return t0 * std::log1p(t / t0);
}

}  // namespace granvv::hydro
