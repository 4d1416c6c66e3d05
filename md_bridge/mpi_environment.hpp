#pragma once
// MPI for programs that do not own it: the particle engines are collective over
// MPI_COMM_WORLD, while `granvv run` of a hydro-only scene needs no MPI at all.
#include <mpi.h>

namespace granvv::md {

// Initialises MPI if nobody has, and finalises it at destruction only if it was this guard
// that initialised it (and MPI is not finalised yet).
class MpiEnvironment {
 public:
  MpiEnvironment();
  ~MpiEnvironment();
  MpiEnvironment(const MpiEnvironment&) = delete;
  MpiEnvironment& operator=(const MpiEnvironment&) = delete;

  bool initialised_here() const { return initialised_here_; }

  // A process-wide guard (function-local static): MPI is initialised on first use and,
  // if it was initialised here, finalised at program exit. Engines call this before they
  // open anything collective.
  static void ensure();
  // The thread support MPI gives (MPI_THREAD_SINGLE .. MPI_THREAD_MULTIPLE; it is asked for
  // MPI_THREAD_MULTIPLE, so that ensemble members may run in threads); SINGLE before MPI starts.
  static int thread_level();
  // The ranks of comm on this machine (collective; 1 before MPI starts).
  static int ranks_on_this_machine(MPI_Comm comm);

 private:
  bool initialised_here_ = false;
};

// The ranks a particle engine spans unless its setup says otherwise (ParticleEngineSetup::comm):
// MPI_COMM_WORLD, or MPI_COMM_SELF in a process whose command rank 0 runs alone under mpirun
// (`granvv atlas`, app/mpi_ranks.hpp).
MPI_Comm particle_ranks();
void set_particle_ranks(MPI_Comm comm);

}  // namespace granvv::md
