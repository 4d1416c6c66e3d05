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

// Width of cell i, periodic.
double cell_width(const LagrangianState& s, int i);
// Cell-centre position of cell i (unwrapped, may exceed 1/2 for the last cell).
double cell_centre(const LagrangianState& s, int i);
// Node mass: half the mass of each neighbouring cell.
double node_mass(const LagrangianState& s, int j);
// Position wrapped into [-1/2, 1/2).
double wrap_position(double x);

}  // namespace granvv::hydro
