#pragma once
// Thermal and flow energy per particle from fields on the bins (scaled units: the box has unit
// length, n is relative to the mean density, T is the thermal energy per particle of a 2D gas,
// docs/physics.md §1 and §4).
//
// The flow energy of coarse-grained particles carries the sampling noise of the bin means
// (docs/physics.md §7 and §8): a bin mean over N_b particles of velocity variance T_b per
// component has E|v_b|^2 = |u_b|^2 + 2 T_b / N_b in two components, and the mean over k
// independent members divides that noise by k. Subtracting 2 T_b / (N_b k) bin by bin leaves an
// unbiased estimate of the flow energy (1/2) n |u|^2, so that a gas at rest reads zero, not
// T / N_b, and a weak imposed flow is not hidden under its own noise.
#include <vector>

#include "compare/binned_fields.hpp"

namespace granvv::compare {

struct EnergiesPerParticle {
  double thermal = 0.0;  // sum n T dx over the mass
  double flow = 0.0;     // sum (1/2) n |v|^2 dx over the mass
};

// The hydro on the bins (bin_lagrangian_state): box integrals with dx = 1 / bins. The hydro's
// mass is 1 in scaled units, so they are already per particle; no bin is skipped.
EnergiesPerParticle box_energies(const fields::FieldSnapshot& hydro);

// The particles' ensemble means on the bins, with the sampling noise 2 T_b / (N_b k) removed
// from the flow energy (none where count_per_member_b = 0). Bins where v_x or T is not finite
// (empty) are left out, and both energies are divided by the mass sum n dx of the bins kept.
EnergiesPerParticle noise_corrected_energies(const fields::FieldSnapshot& md_mean,
                                             const std::vector<double>& count_per_member,
                                             int members);

}  // namespace granvv::compare
