#pragma once
// Observed order of accuracy on a smooth solution by self-convergence: the same scene on
// nested Lagrangian meshes N_0 < N_1 < ... (refinement ratios r with nested nodes), with
// the time step tied to the cell size, compared level to level at the shared nodes and
// over the shared cells (mass-weighted). With errors e_l = |u_l - u_{l+1}| the observed
// order is log(e_l / e_{l+1}) / log(r).
#include <string>
#include <vector>

#include "hydro/closure.hpp"
#include "hydro/driver.hpp"
#include "hydro/initial_conditions.hpp"
#include "hydro/time_step.hpp"

namespace granvv::hydro {

struct ConvergenceStudy {
  double t = 0.0;
  double cfl = 0.0;
  std::vector<int> cells;
  // L1 differences between successive levels (size levels - 1)
  std::vector<double> error_x, error_v, error_n, error_T;
  // observed orders between successive differences (size levels - 2)
  std::vector<double> order_x, order_v, order_n, order_T;
  double wall_seconds = 0.0;
};

// Returns an explanation if these meshes do not nest (an empty string if they do).
std::string convergence_mesh_problem(const std::vector<int>& cells, double node_offset);

// The stop conditions of the case (hydro.stop_density, hydro.min_cell_width): a level that
// meets one before t has left the smooth solution the study needs.
struct ConvergenceStops {
  double stop_density = 0.0;
  double min_cell_width = 0.0;
};

// Runs every level to t, reporting each level's steps through `progress`. Throws
// std::runtime_error naming the level, the time and the reason if a level stops before t
// (singularity or no admissible step): a study past a singularity has no answer.
ConvergenceStudy run_convergence_study(const Closure& closure, const InitialFields& fields,
                                       const std::vector<int>& cells, double node_offset, double t,
                                       const TimeStepControl& base, const ConvergenceStops& stops,
                                       const ProgressCallback& progress = {});

}  // namespace granvv::hydro
