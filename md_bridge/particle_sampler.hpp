#pragma once
// Particles from fields: positions without overlap following a density profile n(x)
// (uniform in y), velocities Maxwellian about the local mean v(x), v_y(x) with the local
// temperature T(x), and the total momentum exactly what the fields carry. Any hydro initial
// condition (hydro/initial_conditions.hpp, scaled units) can so start an MD run.
#include <cstdint>
#include <functional>
#include <vector>

#include "hydro/initial_conditions.hpp"
#include "md_bridge/particle_scene.hpp"

namespace granvv::md {

// LAMMPS layout: x[3 i + 0..2], v[3 i + 0..2]; z = 0. The box is [-Lx/2, Lx/2) x [-Ly/2, Ly/2).
struct ParticleSample {
  std::vector<double> x, v;
  // 1-based particle IDs, the same on every rank; empty: 1 .. count() in order (a whole box).
  std::vector<long long> id;
  long long count() const { return static_cast<long long>(x.size() / 3); }
};

// Parallel sampling. The box is cut along x into strip_count(scene) strips of equal
// width, about kStripParticles disks each. How many disks each strip gets is drawn first, as N
// positions from the profile from a stream seeded by (seed, "counts"), which every rank draws
// alike (a multinomial draw, as N independent positions give); strip k then draws its disks'
// positions and velocities from its own stream, seeded by (seed, k), with the profile restricted
// to the strip. Strips are sampled in colours (even, odd, and a last odd strip of an odd count)
// and a strip keeps clear of its neighbours of lower colour, so no two disks overlap across a
// strip boundary. A rank samples the strips that overlap its x-range (and the neighbours they
// keep clear of), so the sample does not depend on the ranks: the same seed gives the same
// particles, bit for bit, on 1 or P ranks. A box of one strip (N <= kStripParticles, every
// shipped case) is sampled by the whole-box sampler from the stream seeded by `seed` itself,
// as before strips existed.
inline constexpr long long kStripParticles = 100000;
int strip_count(const ParticleScene& scene);

// Evaluates the fields where the sampler tabulates its profile; throws what sampling would
// (hydro::InitialFieldError for a field that is not finite there, std::invalid_argument for a
// profile that cannot be packed). A disk's own position is drawn at random, so a field that is
// not finite only between these points is found when that disk is sampled.
void check_sampled_profile(const ParticleScene& scene, const hydro::InitialFields& scaled);

// Throws std::invalid_argument (one line) if the profile cannot be packed: a local area
// fraction above 0.5 anywhere, or no free spot found for a particle after many tries.
// The same seed gives the same sample on every rank and platform. The whole box: every strip.
ParticleSample sample_particles(const ParticleScene& scene, const hydro::InitialFields& scaled,
                                std::uint64_t seed);

// The particles of the strips that overlap [x_lo, x_hi) (MD units; a whole box of one strip
// whatever the range), with their IDs. The total momentum is set to the fields' by one shift of
// every velocity, from the momentum of every strip: `combine` (collective under MPI: an
// MPI_MAX all-reduce over the ranks) receives this rank's per-strip sums (px, py of strip k at
// 2k, 2k + 1; -inf for a strip it did not sample) and must leave every strip's. It is called
// when the box has more than one strip, and then on every rank; the ranks' ranges together must
// cover the box.
using StripMomentumCombine = std::function<void(std::vector<double>& strip_momenta)>;
ParticleSample sample_particles_in(const ParticleScene& scene, const hydro::InitialFields& scaled,
                                   std::uint64_t seed, double x_lo, double x_hi,
                                   const StripMomentumCombine& combine);

}  // namespace granvv::md
