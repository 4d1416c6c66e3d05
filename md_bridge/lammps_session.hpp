#pragma once
// One LAMMPS instance, opened through the C library interface (lammps_open with an MPI
// communicator, docs/physics.md §10) and closed by the destructor.
//
// The Debian LAMMPS is built without C++ exceptions: an error inside lammps_command ends the
// whole process (docs/physics.md §10). So this class does not try to catch LAMMPS errors; it checks
// what it can before a call (box defined, atoms inside it, types in range, finite numbers,
// writable log file) and callers build commands only from validated numbers (see
// contact_model.hpp: lammps_number). Every command sent is recorded in history() and passed
// to an optional callback, so a run's exact LAMMPS input can be logged or replayed.
#include <mpi.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "md_bridge/mpi_environment.hpp"

namespace granvv::md {

#if defined(LAMMPS_BIGBIG)
using LammpsTag = std::int64_t;
#else
using LammpsTag = int;  // tagint of the default LAMMPS_SMALLBIG build (Debian's)
#endif

struct LammpsSessionOptions {
  std::string log_file = "none";  // -log FILE; "none" writes no log
  MPI_Comm comm = MPI_COMM_WORLD;
  std::function<void(const std::string&)> on_command;  // called before each command is sent
};

// Atoms to add: the same full list on every rank (each rank keeps the atoms in its
// subdomain). Positions and velocities are xyz triplets; velocities may be empty (at rest).
struct AtomBatch {
  std::vector<int> type;         // 1 .. ntypes
  std::vector<double> x;         // 3 per atom, inside the box
  std::vector<double> v;         // 3 per atom, or empty
  std::vector<double> diameter;  // per atom; required when atoms carry a radius
  std::vector<double> mass;      // per atom; required when atoms carry a per-atom mass
  // IDs (>= 1), or empty: consecutive after the largest existing one. With IDs, the batch may
  // differ from rank to rank (each rank keeps the atoms of its subdomain), and `total` is the
  // number of atoms all ranks create together (0: the batch's size, the same on every rank).
  std::vector<LammpsTag> id;
  long long total = 0;
};

class LammpsSession {
 public:
  // Opens LAMMPS with "-log FILE -screen none -nocite". Throws std::invalid_argument if the
  // log file cannot be written (LAMMPS would end the process).
  explicit LammpsSession(LammpsSessionOptions options = {});
  ~LammpsSession();  // lammps_close
  LammpsSession(const LammpsSession&) = delete;
  LammpsSession& operator=(const LammpsSession&) = delete;

  // Sends one command line (no newlines); records it first.
  void command(const std::string& line);
  void commands(const std::vector<std::string>& lines);
  const std::vector<std::string>& history() const { return history_; }
  void set_command_callback(std::function<void(const std::string&)> callback);

  // "run N pre yes|no post no". Use pre = true for the first run and after any change of
  // atoms, pair coefficients, fixes or the time step. Throws std::logic_error without a box,
  // std::invalid_argument for N outside [0, 1e9].
  void run(long long steps, bool pre);

  std::int64_t natoms() const;
  int nlocal() const;
  int ntypes() const;
  int dimension() const;
  bool box_exists() const;
  int rank() const { return rank_; }
  int size() const { return size_; }
  MPI_Comm comm() const { return comm_; }
  void* handle() const { return handle_; }

  // Zero-copy per-atom arrays of the local atoms (index 0 .. nlocal-1); null if the atom
  // style lacks them. Valid until LAMMPS next reallocates (any run or atom creation).
  double** x();
  double** v();
  double* radius();
  double* rmass();
  LammpsTag* id();

  // lammps_create_atoms with consecutive new IDs after the largest existing one; returns the
  // first new ID. Sets radius and per-atom mass explicitly afterwards: lammps_create_atoms
  // leaves atom_style sphere's 3D default (diameter 1, mass pi/6), even in 2D. Throws
  // std::invalid_argument (nothing created) for inconsistent sizes, non-finite values,
  // atoms outside the box, types outside [1, ntypes], non-positive diameter or mass, or a
  // 2D atom with z or v_z != 0; std::logic_error without a box.
  LammpsTag create_atoms(const AtomBatch& atoms);

  // A per-atom property of all atoms ordered by ID, `count` values per atom, on every rank
  // (lammps_gather_atoms; IDs must be 1..N). Throws std::runtime_error if LAMMPS declined.
  std::vector<double> gather_atoms(const std::string& name, int count);

 private:
  LammpsTag create_atoms_with_ids(const AtomBatch& atoms, bool has_radius, bool has_rmass);
  void* handle_ = nullptr;
  MPI_Comm comm_ = MPI_COMM_WORLD;
  int rank_ = 0;
  int size_ = 1;
  std::vector<std::string> history_;
  std::function<void(const std::string&)> on_command_;
};

}  // namespace granvv::md
