#include "hydro/lagrangian_state.hpp"

#include <cmath>

namespace granvv::hydro {

double cell_width(const LagrangianState& s, int i) {
  const int n = s.cells();
  return i + 1 < n ? s.node_x[i + 1] - s.node_x[i] : s.node_x[0] + 1.0 - s.node_x[i];
}

double cell_centre(const LagrangianState& s, int i) {
  return s.node_x[i] + 0.5 * cell_width(s, i);
}

double node_mass(const LagrangianState& s, int j) {
  const int n = s.cells();
  return 0.5 * (s.cell_mass[(j + n - 1) % n] + s.cell_mass[j]);
}

double wrap_position(double x) {
  return x - std::floor(x + 0.5);
}

}  // namespace granvv::hydro
