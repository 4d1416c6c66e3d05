#include "md_bridge/mpi_environment.hpp"

namespace granvv::md {

MpiEnvironment::MpiEnvironment() {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) {
    MPI_Init(nullptr, nullptr);
    initialised_here_ = true;
  }
}

MpiEnvironment::~MpiEnvironment() {
  if (!initialised_here_) return;
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (!finalised) MPI_Finalize();
}

void MpiEnvironment::ensure() {
  // Constructed on first use, destroyed at exit after every object constructed before it
  // returned, so an engine's session (which calls this in its constructor) closes first.
  static MpiEnvironment guard;
}

namespace {
MPI_Comm particle_comm = MPI_COMM_WORLD;
}  // namespace

MPI_Comm particle_ranks() {
  return particle_comm;
}

void set_particle_ranks(MPI_Comm comm) {
  particle_comm = comm;
}

}  // namespace granvv::md
