#pragma once
// Initial conditions as continuous fields n(x), v(x), v_y(x), T(x) on [-1/2, 1/2), and their
// discretisation onto the Lagrangian mesh. Scenes register their generator by name
// (cases name it as initial.type), so no switch over problems is spread across files.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "hydro/lagrangian_state.hpp"
#include "hydro/physics.hpp"

namespace granvv::hydro {

struct InitialFields {
  std::function<double(double)> n, v, vy, T;
  // Initial velocity profile and its slope when the scene has a smooth one (flow by
  // inertia, paper Eq. 5, uses them); empty otherwise.
  std::function<double(double)> dv;
};

struct InitialParameters {
  std::string type = "single_mode";
  double velocity_amplitude = -0.05;  // a in v = a sin(2 pi k x), paper Eq. (8)
  int mode = 1;                       // k
  int random_modes = 300;
  double random_amplitude = 1e-3;
  unsigned long long seed = 1;
  double linear_amplitude = 1e-6;
  int linear_branch = 0;  // 0: fastest-growing eigenmode of mode k, 1, 2: the others
  // Any scene may add a transverse velocity v_y = b cos(2 pi k_y x): the shear mode whose
  // growth in a long box the 1D model leaves out unless v_y is carried (DESIGN.md §6).
  double transverse_amplitude = 0.0;
  int transverse_mode = 1;
};

using InitialConditionGenerator =
    std::function<InitialFields(const InitialParameters&, const Physics&)>;

// The registered generators: uniform, single_mode, random_modes, linear_mode.
const std::map<std::string, InitialConditionGenerator>& initial_condition_registry();
InitialFields make_initial_fields(const InitialParameters& p, const Physics& physics);

// Nodes at x_j = -1/2 + (j + offset)/N (offset 1/2 puts a cell centre at x = 0, where the
// single-mode singularity forms); cell masses and temperatures are exact cell averages
// of n and nT by 3-point Gauss-Legendre quadrature.
LagrangianState discretize(const InitialFields& fields, int cells, double node_offset,
                           bool transverse);

}  // namespace granvv::hydro
