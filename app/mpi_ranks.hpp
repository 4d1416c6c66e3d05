#pragma once
// The ranks of a command under mpirun: for `granvv run` (and each point of `granvv sweep`) every
// rank runs the scene, rank 0 alone writes, and a failure of the writer (an unusable folder, a
// write error) is shared so that no rank goes on alone into a collective step; `granvv atlas`
// runs on rank 0 alone.
#include <functional>
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

// The problem of the lowest rank that has one ("" if none has), on every rank (collective when
// size > 1), naming that rank if it is not rank 0: what a check that each rank makes on its own
// part (its block of a checkpoint) reports through the writer.
std::string first_ranks_problem(const Ranks& ranks, const std::string& problem);

// The writer's value on every rank (collective when size > 1): a path only rank 0 knows.
std::string writers_value(const Ranks& ranks, std::string value);

// A command that rank 0 runs alone under mpirun (the atlas, whose choice of runs depends on the
// wall time each takes, which ranks would not agree on): rank 0 runs `work` with its particle
// engines on itself only (md::set_particle_ranks), the other ranks wait without spinning, and
// every rank returns work's exit code (1 if it threw). Without mpirun, work() itself.
int on_rank_zero_alone(const Ranks& ranks, const std::function<int()>& work);

// The writer's exit code on every rank (collective when size > 1), the others waiting without
// spinning: the end of a command whose outputs rank 0 alone writes.
int writers_exit_code(const Ranks& ranks, int code);

}  // namespace granvv::app
