#pragma once
// Whole-mesh diagnostics of a Lagrangian state: peak density, energies of paper Eq. (3),
// momentum. The thermal energy is sum m_i T_i (n T is the thermal energy density in 2D).
#include "hydro/lagrangian_state.hpp"

namespace granvv::hydro {

struct Diagnostics {
  int peak_cell = 0;
  double n_max = 0.0;      // largest cell density
  double x_peak = 0.0;     // centre of the densest cell, wrapped into [-1/2, 1/2)
  double dvdx_peak = 0.0;  // velocity gradient across the densest cell
  double T_min = 0.0;
  double T_mean = 0.0;     // mass-weighted mean temperature
  double min_width = 0.0;  // smallest cell width
  double energy_thermal = 0.0;
  double energy_kinetic = 0.0;    // sum mu v_x^2 / 2
  double energy_kinetic_y = 0.0;  // sum mu v_y^2 / 2
  double momentum = 0.0;
  double mass = 0.0;
  double energy() const { return energy_thermal + energy_kinetic + energy_kinetic_y; }
};

// cells: the state's widths and densities (measure_cells).
Diagnostics diagnose(const LagrangianState& s, const CellGeometry& cells);
Diagnostics diagnose(const LagrangianState& s);

}  // namespace granvv::hydro
