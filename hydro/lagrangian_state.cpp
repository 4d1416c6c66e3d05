#include "hydro/lagrangian_state.hpp"

#include <cmath>

#include "hydro/wide_loops.hpp"

namespace granvv::hydro {

double cell_centre(const LagrangianState& s, int i) {
  return s.node_x[i] + 0.5 * cell_width(s, i);
}

double wrap_position(double x) {
  return x - std::floor(x + 0.5);
}

GRANVV_WIDE_LOOPS
void cell_widths(const std::vector<double>& node_x, std::vector<double>& widths) {
  const int n = static_cast<int>(node_x.size());
  widths.resize(n);
  for (int i = 0; i + 1 < n; ++i) widths[i] = node_x[i + 1] - node_x[i];
  widths[n - 1] = cell_width(node_x, n - 1);
}

GRANVV_WIDE_LOOPS
void measure_cells(const LagrangianState& s, CellGeometry& out) {
  cell_widths(s.node_x, out.width);
  const int n = s.cells();
  out.density.resize(n);
  for (int i = 0; i < n; ++i) out.density[i] = s.cell_mass[i] / out.width[i];
}

}  // namespace granvv::hydro
