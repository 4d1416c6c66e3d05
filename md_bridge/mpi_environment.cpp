#include "md_bridge/mpi_environment.hpp"

namespace granvv::md {

MpiEnvironment::MpiEnvironment() {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) {
    int provided = MPI_THREAD_SINGLE;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_MULTIPLE, &provided);
    initialised_here_ = true;
  }
}

MpiEnvironment::~MpiEnvironment() {
  if (!initialised_here_) return;
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (!finalised) MPI_Finalize();
}

int MpiEnvironment::thread_level() {
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  if (!initialised || finalised) return MPI_THREAD_SINGLE;
  int provided = MPI_THREAD_SINGLE;
  MPI_Query_thread(&provided);
  return provided;
}

int MpiEnvironment::ranks_on_this_machine(MPI_Comm comm) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) return 1;
  MPI_Comm local;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &local);
  int size = 1;
  MPI_Comm_size(local, &size);
  MPI_Comm_free(&local);
  return size;
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
