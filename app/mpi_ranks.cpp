#include "app/mpi_ranks.hpp"

#include <mpi.h>

#include <chrono>
#include <cstdlib>
#include <thread>

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

// How often a waiting rank looks whether the writer has finished: a blocking MPI call would
// spin a core (Open MPI busy-polls) that the writer's own runs need.
constexpr auto kWaitingPoll = std::chrono::milliseconds(50);

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

std::string first_ranks_problem(const Ranks& ranks, const std::string& problem) {
  if (ranks.size == 1) return problem;
  int first = problem.empty() ? ranks.size : ranks.rank;
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == ranks.size) return "";
  std::string shared = problem;
  int length = int(shared.size());
  MPI_Bcast(&length, 1, MPI_INT, first, MPI_COMM_WORLD);
  shared.resize(std::size_t(length));
  MPI_Bcast(shared.data(), length, MPI_CHAR, first, MPI_COMM_WORLD);
  return first == 0 ? shared : shared + " (on rank " + std::to_string(first) + ")";
}

std::string writers_value(const Ranks& ranks, std::string value) {
  if (ranks.size == 1) return value;
  int length = int(value.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
  value.resize(std::size_t(length));
  MPI_Bcast(value.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  return value;
}

int writers_exit_code(const Ranks& ranks, int code) {
  if (ranks.size == 1) return code;
  MPI_Request request;
  MPI_Ibcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return code;
    std::this_thread::sleep_for(kWaitingPoll);
  }
}

int on_rank_zero_alone(const Ranks& ranks, const std::function<int()>& work) {
  if (ranks.size == 1) return work();
  if (!ranks.writer()) return writers_exit_code(ranks, 1);
  md::set_particle_ranks(MPI_COMM_SELF);
  int code = 1;
  try {
    code = work();
  } catch (...) {
    writers_exit_code(ranks, 1);
    throw;
  }
  return writers_exit_code(ranks, code);
}

}  // namespace granvv::app
