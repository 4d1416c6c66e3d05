#include "hydro/cell_fields.hpp"

namespace granvv::hydro {

fields::FieldSeries cell_field_series(const std::vector<Snapshot>& snapshots) {
  fields::FieldSeries series;
  series.geometry = fields::Geometry::cells;
  for (const auto& snap : snapshots) {
    const LagrangianState& s = snap.state;
    const int cells = s.cells();
    const bool transverse = s.has_transverse();
    fields::FieldSnapshot f;
    f.t = s.t;
    f.label = snap.label;
    for (int i = 0; i < cells; ++i) {
      const int r = (i + 1) % cells;
      f.x.push_back(cell_centre(s, i));
      f.n.push_back(s.cell_mass[i] / cell_width(s, i));
      f.T.push_back(s.cell_T[i]);
      f.v_x.push_back(0.5 * (s.node_v[i] + s.node_v[r]));
      if (transverse) f.v_y.push_back(0.5 * (s.node_vy[i] + s.node_vy[r]));
    }
    series.snapshots.push_back(std::move(f));
  }
  return series;
}

}  // namespace granvv::hydro
