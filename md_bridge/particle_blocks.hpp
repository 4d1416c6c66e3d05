#pragma once
// Particle frames without a gather: under MPI each rank owns a contiguous block of
// particle IDs, and at a frame every rank sends its local particles to the owners of their
// IDs, so that no rank holds more than its block and its own particles. The blocks are written
// one file per rank and joined by a virtual dataset (h5md_frames.hpp).
#include <mpi.h>

#include <vector>

#include "md_bridge/particle_engine.hpp"
#include "md_bridge/particle_sampler.hpp"

namespace granvv::md {

// Rows [first, first + count) of an N-particle frame: the particles with IDs first + 1 ..
// first + count.
struct IdBlock {
  long long first = 0;
  long long count = 0;
};

// Rank k of P owns rows [floor(k N / P), floor((k + 1) N / P)): blocks of N / P rows, the first
// ones one row shorter where P does not divide N; empty where N < P.
IdBlock id_block(long long n, int ranks, int rank);
// The rank whose block holds row `row` (0 <= row < n).
int id_block_owner(long long row, long long n, int ranks);

// This rank's block of a frame (collective over comm): x and v of the particles with IDs
// block.first + 1 .. block.first + block.count as xyz triplets (z = 0), from every rank's
// local particles and their IDs (1 .. n, in the order of `local`). Throws std::runtime_error on
// every rank if some rank's block did not receive each of its IDs exactly once.
ParticleFrame block_frame(const LocalParticles& local, const std::vector<long long>& ids,
                          long long n, MPI_Comm comm);

// Particles held by ID block, each sent to every rank whose subdomain [lo_x, hi_x) x [lo_y, hi_y)
// (every rank's own lo, hi), grown by `margin` on each side, holds it (collective): what a rank
// needs to create the particles of its subdomain (LAMMPS keeps those inside it, and only those).
ParticleSample to_subdomains(const ParticleSample& mine, const double lo[2], const double hi[2],
                             double margin, MPI_Comm comm);

}  // namespace granvv::md
