#pragma once
// The box's lowest 2D Fourier modes of the momentum and density fields (docs/physics.md §12),
// summed in place over every rank's particles: the measure of how far a homogeneously cooling
// gas has left homogeneity through its shear and clustering instabilities.
//
// For a wave vector k = 2 pi (n_x / Lx, n_y / Ly) the momentum mode is j_k = sum_p m c e^{-i k.r}
// and the density mode rho_k = sum_p e^{-i k.r}. The flow energy a pair of wave vectors +-k
// carries is |j_k|^2 / M (M the total mass; (1/2) rho A |u_k|^2 for each of k and -k). Independent
// particles (no flow) give it the expectation sum_p m^2 |c|^2 / M, about 2 K / N for a kinetic
// energy K of N equal disks; that thermal noise is subtracted, so the fraction
//   f = sum_k (|j_k|^2 - sum m^2 |c|^2) / M / K_total
// has expectation 0 in a homogeneous gas and its noise is about sqrt(2 modes) / N. The density
// modes are recorded as the structure factor sum_k |rho_k|^2 / N / modes (1 for an ideal gas,
// growing when the gas clusters).
#include <mpi.h>

#include <array>
#include <utility>
#include <vector>

#include "md_bridge/particle_scene.hpp"

namespace granvv::md {

// The measured wave vectors (n_x, n_y), one of each pair +-k: every one with n_x^2 + n_y^2 <= 4
// in the half plane, the box's lowest shear and clustering modes along x, y and the diagonals.
const std::vector<std::pair<int, int>>& box_mode_wave_vectors();

// Raw sums over particles, additive over ranks.
struct BoxModeSums {
  // Per wave vector: Re and Im of j_k (x, y components) and of rho_k.
  std::vector<std::array<double, 6>> mode;
  double mass = 0.0, kinetic2 = 0.0, noise = 0.0, particles = 0.0;  // sum m, m|c|^2, m^2|c|^2, N
};

// Sums of n particles (xyz triplets, masses or nullptr for unit mass) in the box of lengths
// lx, ly (any origin: only phases enter).
BoxModeSums box_mode_sums(const double* x, const double* v, const double* mass, int n, double lx,
                          double ly);
void allreduce(BoxModeSums& sums, MPI_Comm comm);

struct BoxModes {
  double energy_fraction = 0.0;   // f above: noise-corrected flow energy of the modes / kinetic
  double structure_factor = 0.0;  // mean over the wave vectors of |rho_k|^2 / N
};
BoxModes box_modes(const BoxModeSums& sums);

// Linear theory of the onset (docs/physics.md §12): the first unstable mode of the box grows
// from its thermal noise to `threshold` of the kinetic energy. In the collision clock s of the
// dilute hydro with the scene's K, q (hydro/linear_stability.hpp) the energy fraction of a
// velocity mode of rate lambda grows as f0 exp(2 lambda s) from f0 = (degenerate wave-vector
// pairs x polarisations) / N, so s* = ln(threshold / f0) / (2 lambda) and t* = t0 (e^{s*/t0} - 1)
// with the hydro's t0 = 1/eps. Taken over the lowest mode k = 1 along x: the shear mode (one
// polarisation) and the fastest longitudinal HCS mode (hcs_modes), degenerate twice in a box
// square to 1 %; the earlier of the two. Returns the MD time, or +infinity when neither grows (r =
// 1) or the threshold is below the noise.
double linear_mode_onset_md(const ParticleScene& scene, double threshold);

}  // namespace granvv::md
