#include "app/mpi_ranks.hpp"

#include <mpi.h>

#include <cstdlib>

#include "md_bridge/mpi_environment.hpp"

namespace granvv::app {
namespace {

// The variables that Open MPI, MPICH and PMIx launchers set in every process they start.
bool started_by_mpi_launcher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"}) {
    if (std::getenv(name)) return true;
  }
  return false;
}

}  // namespace

Ranks join_ranks(bool engine_needs_mpi) {
  Ranks r;
  if (!engine_needs_mpi && !started_by_mpi_launcher()) return r;
  md::MpiEnvironment::ensure();
  MPI_Comm_rank(MPI_COMM_WORLD, &r.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &r.size);
  return r;
}

bool all_ranks_ok(const Ranks& ranks, bool ok) {
  if (ranks.size == 1) return ok;
  int local = ok ? 1 : 0, all = 0;
  MPI_Allreduce(&local, &all, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
  return all == 1;
}

std::string writers_value(const Ranks& ranks, std::string value) {
  if (ranks.size == 1) return value;
  int length = int(value.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
  value.resize(std::size_t(length));
  MPI_Bcast(value.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  return value;
}

}  // namespace granvv::app
