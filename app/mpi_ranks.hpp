#pragma once
// The ranks of a `granvv run` under mpirun: every rank runs the scene, rank 0 alone writes, and
// a failure of the writer (an unusable folder, a write error) is shared so that no rank goes on
// alone into a collective step.
#include <string>

namespace granvv::app {

struct Ranks {
  int rank = 0;
  int size = 1;
  bool writer() const { return rank == 0; }
};

// Joins MPI_COMM_WORLD when the particle engine needs MPI or when the process was started by
// an MPI launcher (so that a hydro-only scene under mpirun -np 2 also has one writer).
Ranks join_ranks(bool engine_needs_mpi);

// True on every rank if ok is true on every rank (collective when size > 1).
bool all_ranks_ok(const Ranks& ranks, bool ok);

// The writer's value on every rank (collective when size > 1): a path only rank 0 knows.
std::string writers_value(const Ranks& ranks, std::string value);

}  // namespace granvv::app
