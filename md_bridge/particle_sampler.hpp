#pragma once
// Particles from fields: positions without overlap following a density profile n(x)
// (uniform in y), velocities Maxwellian about the local mean v(x), v_y(x) with the local
// temperature T(x), and the total momentum exactly what the fields carry. Any hydro initial
// condition (hydro/initial_conditions.hpp, scaled units) can so start an MD run.
#include <cstdint>
#include <vector>

#include "hydro/initial_conditions.hpp"
#include "md_bridge/particle_scene.hpp"

namespace granvv::md {

// LAMMPS layout: x[3 i + 0..2], v[3 i + 0..2]; z = 0. The box is [-Lx/2, Lx/2) x [-Ly/2, Ly/2).
struct ParticleSample {
  std::vector<double> x, v;
  long long count() const { return static_cast<long long>(x.size() / 3); }
};

// Throws std::invalid_argument (one line) if the profile cannot be packed: a local area
// fraction above 0.5 anywhere, or no free spot found for a particle after many tries.
// The same seed gives the same sample on every rank and platform.
ParticleSample sample_particles(const ParticleScene& scene, const hydro::InitialFields& scaled,
                                std::uint64_t seed);

}  // namespace granvv::md
