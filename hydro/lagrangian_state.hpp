#pragma once
// The Lagrangian state of the 1D periodic staggered mesh (paper: "a Lagrangian scheme
// with periodic boundary conditions"). N nodes carry position and velocity; N cells
// carry mass and granular temperature. Cell i lies between node i and node i+1; node N
// is node 0 shifted by the period 1, so node positions are kept unwrapped and increasing.
#include <vector>

namespace granvv::hydro {

struct LagrangianState {
  double t = 0.0;
  std::vector<double> node_x;     // node positions, increasing, node_x.back() < node_x[0] + 1
  std::vector<double> node_v;     // longitudinal velocity v_x at nodes
  std::vector<double> node_vy;    // transverse velocity v_y at nodes (empty: not carried)
  std::vector<double> node_xi;    // Lagrangian label: the node's initial position
  std::vector<double> cell_mass;  // Delta m_i = integral of n over the cell (conserved)
  std::vector<double> cell_T;     // granular temperature per cell

  int cells() const { return static_cast<int>(cell_mass.size()); }
  bool has_transverse() const { return !node_vy.empty(); }
};

// Width of cell i of a periodic mesh with node positions node_x.
inline double cell_width(const std::vector<double>& node_x, int i) {
  const int n = static_cast<int>(node_x.size());
  return i + 1 < n ? node_x[i + 1] - node_x[i] : node_x[0] + 1.0 - node_x[i];
}
inline double cell_width(const LagrangianState& s, int i) {
  return cell_width(s.node_x, i);
}
// Cell-centre position of cell i (unwrapped, may exceed 1/2 for the last cell).
double cell_centre(const LagrangianState& s, int i);
// Node mass: half the mass of each neighbouring cell.
inline double node_mass(const LagrangianState& s, int j) {
  return 0.5 * (s.cell_mass[j == 0 ? s.cells() - 1 : j - 1] + s.cell_mass[j]);
}
// Position wrapped into [-1/2, 1/2).
double wrap_position(double x);

// Widths and densities n_i = m_i / dx_i of all cells of one state: measured once per state
// and read by every pass over it (cooling, time-step control, diagnostics).
struct CellGeometry {
  std::vector<double> width;
  std::vector<double> density;
};
void cell_widths(const std::vector<double>& node_x, std::vector<double>& widths);
void measure_cells(const LagrangianState& s, CellGeometry& out);

}  // namespace granvv::hydro
