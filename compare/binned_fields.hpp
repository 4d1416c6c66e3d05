#pragma once
// The hydro's Lagrangian state seen through the particles' coarse-graining: top-hat averages
// over the same periodic bins the MD fields are binned on (md_bridge/coarse_grainer.hpp,
// kernel "bin"), so that both sides of a comparison carry the same spatial filter.
//
// Within cell i (nodes i, i+1) the density n_i = m_i / w_i and temperature T_i are constant
// and the velocity is linear between the node values. A bin's density is its mass over its
// width, its velocity the mass-weighted mean (momentum / mass), and its temperature the thermal
// energy per particle with the bin's mean flow removed, exactly as the coarse-grainer defines
// it for particles: T_b = [sum n T + (1/2) sum n |v - v_b|^2] / M_b. The second term is the
// flow that varies inside the bin, which particles in one bin see as heat; for a 2D gas
// (thermal energy T per particle, docs/physics.md §1) it enters with the factor 1/2.
#include <functional>
#include <vector>

#include "fields/field_series.hpp"
#include "hydro/initial_conditions.hpp"
#include "hydro/lagrangian_state.hpp"

namespace granvv::compare {

// Fields on `bins` equal bins of [-1/2, 1/2): x, n, v_x, v_y and T at the bin centres (t and
// label are left to the caller, no standard errors). v_y is zero when the state carries no
// transverse velocity.
// Throws std::invalid_argument if bins < 1 or the state has no cells.
fields::FieldSnapshot bin_lagrangian_state(const hydro::LagrangianState& state, int bins);

// The other way: a continuous, 1-periodic function through values at the bin centres,
// piecewise linear between them (a bin's mean is kept to second order in the bin width).
std::function<double(double)> bin_interpolant(std::vector<double> values);

// Flow by inertia (paper Eq. 5): every fluid element keeps its initial velocity,
// x(xi, t) = xi + t v0(xi), n = n0(xi) / (dx/dxi). Returned as a Lagrangian state of `labels`
// elements (temperature carried unchanged, it has no meaning here), valid while x(xi) stays
// monotonic, i.e. before the first crossing of trajectories. Element masses take n0 at the
// element's midpoint (exact for uniform n0, second order otherwise).
hydro::LagrangianState flow_by_inertia_state(const hydro::InitialFields& initial, double t,
                                             int labels);

}  // namespace granvv::compare
