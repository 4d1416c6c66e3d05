#pragma once
// A step that may fail on some ranks of a collective run (a file written by each rank, or by
// rank 0 alone) ends the same way on every rank, so that no rank goes on alone into the next
// collective call.
#include <mpi.h>

#include <exception>
#include <stdexcept>
#include <string>

namespace granvv::md {

// Runs `action` on every rank of comm (collective). If it threw on any rank, every rank throws:
// the first failing rank its own exception, the others a std::runtime_error with its message.
template <class Action>
void on_every_rank(MPI_Comm comm, const Action& action) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  std::exception_ptr error;
  std::string message;
  try {
    action();
  } catch (const std::exception& e) {
    error = std::current_exception();
    message = e.what();
  }
  int first = error ? rank : ranks;
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == ranks) return;
  int length = int(message.size());
  MPI_Bcast(&length, 1, MPI_INT, first, comm);
  message.resize(std::size_t(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, first, comm);
  if (rank == first) std::rethrow_exception(error);
  throw std::runtime_error(message + " (on rank " + std::to_string(first) + ")");
}

}  // namespace granvv::md
