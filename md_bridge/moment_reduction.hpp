#pragma once
// In-place reduction of coarse-graining moments across MPI ranks (docs/physics.md §7): each rank
// sums the kernel moments of its own particles, and one MPI_Allreduce adds them, so that a run
// of millions of disks never gathers particles. Only sums cross ranks, so the fields of the
// reduced moments are those of the whole box.
#include <mpi.h>

#include "md_bridge/coarse_grainer.hpp"

namespace granvv::md {

// Replaces m on every rank of comm by the sum over the ranks (MPI_SUM), in one MPI_Allreduce
// over a packed buffer. Collective: every rank must call it with moments of the same grid
// (same number of bins); MPI cannot check that without a second collective. Throws
// std::runtime_error if MPI reports an error (under the default MPI_ERRORS_ARE_FATAL handler
// MPI aborts first).
void allreduce(Moments& m, MPI_Comm comm);

}  // namespace granvv::md
