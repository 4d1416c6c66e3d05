#pragma once
// The work a case asks for, estimated before anything runs (steps, cell-steps, atom-steps,
// output size), and the limits beyond which a run cannot finish here and is refused with one
// line naming the key, its value and the estimate.
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "scene/case_config.hpp"

namespace granvv::app {

// Hydro: 1e12 cell-steps is about two days at the measured 6e6 cell-steps/s (README).
constexpr double kMaxCellSteps = 1e12;
// Particles: each engine's own limit (md_bridge/particle_work.hpp).
// Particle runs in segments (one per sample or snapshot), each a LAMMPS `run` with its log
// header of about 1 kB: 1e7 segments is a 10 GB log.
constexpr double kMaxSegments = 1e7;
// Particle frames (H5MD) and time series: at most 20 GB on disk.
constexpr double kMaxOutputBytes = 2e10;

// The machine's physical memory in bytes (sysconf), against which a rank's memory is judged.
double machine_memory_bytes();

// The MPI ranks the process was started among, from the launcher's environment (1 outside
// mpirun): the estimate is made before MPI is joined.
int launched_ranks();

// A particle run's work on one rank (md_bridge/particle_work.hpp): printed by --dry-run and at
// the start of a run.
struct ParticleRunEstimate {
  int ranks = 1;
  double work_per_rank = 0.0;  // in unit
  std::string unit;            // "atom-steps", "collisions"
  double rate = 0.0;           // unit per second on one core (measured)
  double bytes_per_rank = 0.0, machine_bytes = 0.0;
  double seconds() const { return work_per_rank / rate; }
  // One member's work to MD time t (md_bridge/particle_work.hpp), and its share of the member's
  // work to MD time t_end (t / t_end without a model).
  std::function<double(double)> member_work_until;
  double member_share_done(double t, double t_end) const;
  // The groups of ranks the members are spread over (scene/md_members.hpp: member m runs on
  // group m mod member_groups; 1: every member on every rank).
  int member_groups = 1;
  // The wall seconds left of this rank's members while `member` runs with `share_done` of its
  // work done after `wall_seconds`: its rest at its pace so far, then the later members of its
  // group at the same pace, `jobs` at a time.
  double seconds_left(int member, int ensemble, int jobs, double share_done,
                      double wall_seconds) const;
  // "per rank (R ranks): W atom-steps, M GB of memory (this machine has X GB), about T wall at
  // the measured rate of ... per core"
  std::string describe() const;
};

// A duration as "12 s", "3.4 h", "2.1 days".
std::string human_duration(double seconds);

// Of `keys`, the one the user set last: a --set before the case file before a default (the
// first of equals). The key a refusal names.
std::string key_to_blame(const CaseConfig& config, std::initializer_list<std::string> keys);
std::string key_to_blame(const CaseConfig& config, const std::vector<std::string>& keys);

// Throws ConfigError "ORIGIN: KEY = VALUE: <what> (estimate E); the limit is L <unit>" if
// estimate > limit or is not finite; KEY is key_to_blame(keys). `remedy`, if given, ends the
// message in place of "(a run that cannot finish here)".
void refuse_beyond(const CaseConfig& config, std::initializer_list<std::string> keys,
                   double estimate, double limit, const std::string& unit, const std::string& what);
void refuse_beyond(const CaseConfig& config, const std::vector<std::string>& keys, double estimate,
                   double limit, const std::string& unit, const std::string& what,
                   const std::string& remedy = "");

}  // namespace granvv::app
