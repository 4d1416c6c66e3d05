#include "hydro/diagnostics.hpp"

#include <limits>

#include "hydro/wide_loops.hpp"

namespace granvv::hydro {

GRANVV_WIDE_LOOPS
Diagnostics diagnose(const LagrangianState& s, const CellGeometry& cells) {
  Diagnostics d;
  const int n = s.cells();
  d.T_min = std::numeric_limits<double>::infinity();
  d.min_width = std::numeric_limits<double>::infinity();
  const bool transverse = s.has_transverse();
  for (int i = 0; i < n; ++i) {
    const double w = cells.width[i];
    const double density = cells.density[i];
    if (density > d.n_max) {
      d.n_max = density;
      d.peak_cell = i;
    }
    d.min_width = std::min(d.min_width, w);
    d.T_min = std::min(d.T_min, s.cell_T[i]);
    d.mass += s.cell_mass[i];
    d.energy_thermal += s.cell_mass[i] * s.cell_T[i];
    const double mu = node_mass(s, i);
    d.energy_kinetic += 0.5 * mu * s.node_v[i] * s.node_v[i];
    d.momentum += mu * s.node_v[i];
    if (transverse) d.energy_kinetic_y += 0.5 * mu * s.node_vy[i] * s.node_vy[i];
  }
  d.T_mean = d.energy_thermal / d.mass;
  const int p = d.peak_cell;
  d.x_peak = wrap_position(cell_centre(s, p));
  d.dvdx_peak = (s.node_v[p + 1 < n ? p + 1 : 0] - s.node_v[p]) / cells.width[p];
  return d;
}

Diagnostics diagnose(const LagrangianState& s) {
  CellGeometry cells;
  measure_cells(s, cells);
  return diagnose(s, cells);
}

}  // namespace granvv::hydro
