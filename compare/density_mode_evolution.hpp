#pragma once
// The density modes |n_k| of a particle ensemble and of the hydro at the compared times, against
// the linear theory of the homogeneous cooling state (hydro/linear_stability.hpp). For the
// particles the rms over members (the phases of noise-born modes differ between seeds, so the
// mean field would average them away), with its error from the scatter of |n_k|^2; the linear
// theory evolves each member's own t = 0 perturbation (nu, w, theta)_k with exp(A s) over the
// collision clock s, rms over members.
#include <cstddef>
#include <utility>
#include <vector>

#include "fields/field_series.hpp"
#include "hydro/closure.hpp"

namespace granvv::compare {

struct DensityModes {
  std::vector<double> theory_rate;  // [k - 1]: the most unstable branch's rate Re lambda_k
  // [compared time][k - 1]: |n_k| of the hydro (relative to n0 = 1), rms |n_k| of the particles
  // (relative to n0) with its standard error (NaN where the rms is 0), and the linear theory's
  // rms |nu_k|.
  std::vector<std::vector<double>> hydro, md, md_error, theory;
};

// Modes k = 1..modes. members: each particle run's fields on the bins in MD units (its first
// snapshot the t = 0 state); hydro_on_bins: the hydro's fields on the same bins in scaled units;
// pairs[i] = (particle snapshot, hydro snapshot) of compared time i, at collision clock
// collision_clock[i]; n0 the particles' mean number density. A member without snapshot
// pairs[i].first is left out at that time (the theory's rms still divides by every member).
DensityModes density_modes(int modes, const hydro::Closure& closure,
                           const std::vector<fields::FieldSeries>& members,
                           const fields::FieldSeries& hydro_on_bins,
                           const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
                           const std::vector<double>& collision_clock, double n0);

}  // namespace granvv::compare
