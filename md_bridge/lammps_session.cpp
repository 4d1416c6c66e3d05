#include "md_bridge/lammps_session.hpp"

#include <lammps/library.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <unordered_map>
#include <utility>

// Debian's LAMMPS (20220106, built without C++ exceptions) ends a run it cannot continue (its
// Error::one: a coordinate that is not finite or left the box, a lost atom) through MPI_Abort,
// after writing its reason to its log, which only world rank 0 keeps. The rank that met the
// error may be another, so the reason would be lost and the job end without a line. This
// definition comes before the MPI library's (the MPI standard's profiling interface): it
// writes one line naming the rank, then aborts through PMPI_Abort. granvv itself never calls
// MPI_Abort.
extern "C" int MPI_Abort(MPI_Comm comm, int errorcode) {
  int rank = -1;
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::fprintf(stderr,
               "granvv: error: LAMMPS ended the run on rank %d (its own check failed, for example "
               "a particle coordinate not finite or outside the box; rank 0's LAMMPS log has the "
               "message when rank 0 met it)\n",
               rank);
  std::fflush(stderr);
  return PMPI_Abort(comm, errorcode);
}

namespace granvv::md {

// ---------------------------------------------------------------------------------------------
// LammpsSession

namespace {

// Same verdict on every rank: rank 0 (the one LAMMPS lets open the log) tries to open it.
bool log_file_writable(const std::string& path, MPI_Comm comm, int rank) {
  int ok = 1;
  if (rank == 0) {
    std::ofstream probe(path, std::ios::app);
    ok = probe.good() ? 1 : 0;
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, comm);
  return ok == 1;
}

std::string show(double value) {
  // Short form for messages only; commands use lammps_number (contact_model.hpp).
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

}  // namespace

LammpsSession::LammpsSession(LammpsSessionOptions options)
    : comm_(options.comm), on_command_(std::move(options.on_command)) {
  MpiEnvironment::ensure();
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  if (options.log_file.empty())
    throw std::invalid_argument("LAMMPS log file: empty path (use \"none\" for no log)");
  // Only rank 0 writes the log, so its choice decides, and the probe is made on every rank
  // (other ranks may be given "none": a collective made on some ranks only would be matched
  // by the next one the others make).
  int wants_log = options.log_file != "none" ? 1 : 0;
  MPI_Bcast(&wants_log, 1, MPI_INT, 0, comm_);
  if (wants_log && !log_file_writable(options.log_file, comm_, rank_))
    throw std::invalid_argument("LAMMPS log file '" + options.log_file +
                                "' cannot be opened for writing");
  std::vector<std::string> args = {"granvv",  "-log", options.log_file,
                                   "-screen", "none", "-nocite"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // The handle is the return value (passing &handle as the last argument still works in this
  // version but prints a deprecation notice to stdout).
  handle_ = lammps_open(static_cast<int>(args.size()), argv.data(), comm_, nullptr);
  if (handle_ == nullptr) throw std::runtime_error("lammps_open returned no instance");
}

LammpsSession::~LammpsSession() {
  // After MPI_Finalize (a session outliving the MpiEnvironment that owned MPI) closing would
  // call MPI and abort; the process is ending then, so the instance is left to it.
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (handle_ != nullptr && !finalised) lammps_close(handle_);
}

void LammpsSession::set_command_callback(std::function<void(const std::string&)> callback) {
  on_command_ = std::move(callback);
}

void LammpsSession::command(const std::string& line) {
  if (line.find_first_of("\n\r") != std::string::npos)
    throw std::invalid_argument("LAMMPS command with a line break: '" + line + "'");
  if (line.find_first_not_of(" \t") == std::string::npos)
    throw std::invalid_argument("empty LAMMPS command");
  history_.push_back(line);
  if (on_command_) on_command_(line);
  lammps_command(handle_, line.c_str());
}

void LammpsSession::commands(const std::vector<std::string>& lines) {
  for (const auto& line : lines) command(line);
}

void LammpsSession::run(long long steps, bool pre) {
  if (!box_exists()) throw std::logic_error("LAMMPS run before the simulation box is defined");
  if (steps < 0 || steps > 1000000000LL)
    throw std::invalid_argument("LAMMPS run of " + std::to_string(steps) +
                                " steps: must be in [0, 1e9]");
  command("run " + std::to_string(steps) + (pre ? " pre yes" : " pre no") + " post no");
}

std::int64_t LammpsSession::natoms() const {
  return static_cast<std::int64_t>(std::llround(lammps_get_natoms(handle_)));
}

int LammpsSession::nlocal() const {
  return lammps_extract_setting(handle_, "nlocal");
}
int LammpsSession::ntypes() const {
  return lammps_extract_setting(handle_, "ntypes");
}
int LammpsSession::dimension() const {
  return lammps_extract_setting(handle_, "dimension");
}
bool LammpsSession::box_exists() const {
  return lammps_extract_setting(handle_, "box_exist") == 1;
}

double** LammpsSession::x() {
  return static_cast<double**>(lammps_extract_atom(handle_, "x"));
}
double** LammpsSession::v() {
  return static_cast<double**>(lammps_extract_atom(handle_, "v"));
}
double* LammpsSession::radius() {
  return static_cast<double*>(lammps_extract_atom(handle_, "radius"));
}
double* LammpsSession::rmass() {
  return static_cast<double*>(lammps_extract_atom(handle_, "rmass"));
}
LammpsTag* LammpsSession::id() {
  return static_cast<LammpsTag*>(lammps_extract_atom(handle_, "id"));
}

LammpsTag LammpsSession::create_atoms(const AtomBatch& atoms) {
  if (!box_exists())
    throw std::logic_error("LAMMPS create_atoms before the simulation box is defined");
  const std::size_t n = atoms.type.size();
  const auto bad = [](const std::string& what) {
    throw std::invalid_argument("create_atoms: " + what);
  };
  if (n == 0 && atoms.id.empty()) bad("no atoms");
  if (!atoms.id.empty() && atoms.id.size() != n) bad("id must be empty or hold 1 per atom");
  if (atoms.x.size() != 3 * n) bad("x must hold 3 values per atom");
  if (!atoms.v.empty() && atoms.v.size() != 3 * n) bad("v must be empty or hold 3 per atom");
  const bool has_radius = lammps_extract_setting(handle_, "radius_flag") == 1;
  const bool has_rmass = lammps_extract_setting(handle_, "rmass_flag") == 1;
  if (has_radius && atoms.diameter.size() != n)
    bad("this atom style stores a radius: give one diameter per atom");
  if (has_rmass && atoms.mass.size() != n)
    bad("this atom style stores per-atom masses: give one mass per atom (the library "
        "default is the 3D sphere's, also in 2D)");
  if (!has_radius && !atoms.diameter.empty()) bad("this atom style has no radius");
  if (!has_rmass && !atoms.mass.empty()) bad("this atom style has no per-atom mass");

  double lo[3], hi[3], xy = 0, yz = 0, xz = 0;
  int periodic[3], box_change = 0;
  lammps_extract_box(handle_, lo, hi, &xy, &yz, &xz, periodic, &box_change);
  if (lammps_extract_setting(handle_, "triclinic") != 0) bad("triclinic boxes not supported");
  const int types = ntypes();
  const bool two_d = dimension() == 2;
  for (std::size_t i = 0; i < n; ++i) {
    const std::string atom = "atom " + std::to_string(i);
    if (atoms.type[i] < 1 || atoms.type[i] > types)
      bad(atom + ": type " + std::to_string(atoms.type[i]) + " outside [1, " +
          std::to_string(types) + "]");
    for (int d = 0; d < 3; ++d) {
      const double xd = atoms.x[3 * i + d];
      if (!std::isfinite(xd) || xd < lo[d] || xd >= hi[d])
        bad(atom + ": coordinate " + std::to_string(d) + " = " + show(xd) + " outside [" +
            show(lo[d]) + ", " + show(hi[d]) + ")");
      if (!atoms.v.empty() && !std::isfinite(atoms.v[3 * i + d]))
        bad(atom + ": non-finite velocity");
    }
    if (two_d && (atoms.x[3 * i + 2] != 0.0 || (!atoms.v.empty() && atoms.v[3 * i + 2] != 0.0)))
      bad(atom + ": z and v_z must be 0 in 2D");
    if (has_radius && !(std::isfinite(atoms.diameter[i]) && atoms.diameter[i] > 0.0))
      bad(atom + ": diameter " + show(atoms.diameter[i]) + " must be finite and > 0");
    if (has_rmass && !(std::isfinite(atoms.mass[i]) && atoms.mass[i] > 0.0))
      bad(atom + ": mass " + show(atoms.mass[i]) + " must be finite and > 0");
  }

  if (!atoms.id.empty()) return create_atoms_with_ids(atoms, has_radius, has_rmass);

  // New IDs continue after the largest existing one.
  long long local_max = 0;
  {
    const int nl = nlocal();
    const LammpsTag* tags = id();
    for (int i = 0; i < nl; ++i) local_max = std::max<long long>(local_max, tags[i]);
  }
  long long max_id = 0;
  MPI_Allreduce(&local_max, &max_id, 1, MPI_LONG_LONG, MPI_MAX, comm_);
  if (max_id + static_cast<long long>(n) > std::numeric_limits<LammpsTag>::max())
    bad("atom IDs would overflow");
  const LammpsTag first = static_cast<LammpsTag>(max_id + 1);
  std::vector<LammpsTag> ids(n);
  for (std::size_t i = 0; i < n; ++i) ids[i] = first + static_cast<LammpsTag>(i);

  const std::int64_t before = natoms();
  lammps_create_atoms(handle_, static_cast<int>(n), ids.data(), atoms.type.data(), atoms.x.data(),
                      atoms.v.empty() ? nullptr : atoms.v.data(), nullptr, 0);
  const std::int64_t after = natoms();
  if (after != before + static_cast<std::int64_t>(n))
    throw std::runtime_error("lammps_create_atoms created " + std::to_string(after - before) +
                             " of " + std::to_string(n) + " atoms");

  // The explicit radius and mass (the 2D mass trap, docs/physics.md §10).
  const int nl = nlocal();
  const LammpsTag* tags = id();
  double* rad = has_radius ? radius() : nullptr;
  double* mass = has_rmass ? rmass() : nullptr;
  for (int i = 0; i < nl; ++i) {
    const long long k = static_cast<long long>(tags[i]) - first;
    if (k < 0 || k >= static_cast<long long>(n)) continue;
    if (rad) rad[i] = 0.5 * atoms.diameter[k];
    if (mass) mass[i] = atoms.mass[k];
  }
  return first;
}

LammpsTag LammpsSession::create_atoms_with_ids(const AtomBatch& atoms, bool has_radius,
                                               bool has_rmass) {
  const std::size_t n = atoms.type.size();
  const std::int64_t before = natoms();
  // lammps_create_atoms keeps, on each rank, the atoms of the list inside its subdomain.
  lammps_create_atoms(handle_, static_cast<int>(n), atoms.id.data(), atoms.type.data(),
                      atoms.x.data(), atoms.v.empty() ? nullptr : atoms.v.data(), nullptr, 0);
  const std::int64_t after = natoms();
  if (after != before + atoms.total)
    throw std::runtime_error("lammps_create_atoms created " + std::to_string(after - before) +
                             " of " + std::to_string(atoms.total) +
                             " atoms (the ranks' lists do not cover the box once)");
  std::unordered_map<LammpsTag, std::size_t> index;
  index.reserve(n);
  for (std::size_t i = 0; i < n; ++i) index.emplace(atoms.id[i], i);
  const int nl = nlocal();
  const LammpsTag* tags = id();
  double* rad = has_radius ? radius() : nullptr;
  double* mass = has_rmass ? rmass() : nullptr;
  LammpsTag first = std::numeric_limits<LammpsTag>::max();
  for (int i = 0; i < nl; ++i) {
    const auto found = index.find(tags[i]);
    if (found == index.end()) continue;
    if (rad) rad[i] = 0.5 * atoms.diameter[found->second];
    if (mass) mass[i] = atoms.mass[found->second];
  }
  for (LammpsTag t : atoms.id) first = std::min(first, t);
  return first;
}

std::vector<double> LammpsSession::gather_atoms(const std::string& name, int count) {
  if (count < 1) throw std::invalid_argument("gather_atoms: count must be >= 1");
  const std::int64_t n = natoms();
  std::vector<double> data(static_cast<std::size_t>(n) * count,
                           std::numeric_limits<double>::quiet_NaN());
  if (n == 0) return data;
  std::string key = name;  // the 2021 API takes a non-const char*
  lammps_gather_atoms(handle_, key.data(), 1, count, data.data());
  // On refusal (IDs not 1..N, unknown name) LAMMPS warns and leaves data untouched.
  if (std::isnan(data.front()) || std::isnan(data.back()))
    throw std::runtime_error("lammps_gather_atoms declined '" + name + "' (atom IDs must be 1..N)");
  return data;
}

}  // namespace granvv::md
