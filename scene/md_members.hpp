#pragma once
// The members of an ensemble run apart, for an engine whose members are independent
// (md::ParticleEngine::independent_members): each member on an engine of its own, made afresh
// with its seed (md.seed + m), members m = rank (mod P) on MPI rank `rank` of P, and on each rank
// up to `jobs` of them at a time in threads. Every member's result is the one it has when the
// members run in turn on one rank (docs/performance.md, "Ensemble members in parallel").
#include <mpi.h>

#include <functional>
#include <vector>

#include "scene/md_checkpoint.hpp"
#include "scene/member_exchange.hpp"

namespace granvv::app {

struct MdScene;
struct MdCheckpointing;

struct MembersApart {
  std::vector<MemberRecord> records;  // every member in order, the same on every rank
  int threads = 1;                    // members at a time on this rank
  int checkpoints_written = 0;        // over every rank
  int resumed_member = -1;            // the first member continued from its checkpoint
  double resumed_t = 0.0;
  int members_restored = 0;  // finished members taken from the checkpoints
};

// Runs the scene's members over the ranks of comm and `jobs` threads on each (collective). The
// progress callback is called from one thread at a time; an exception it throws (an interruption)
// stops that member, and the others at their next sample. Checkpoints (checkpointing may be null)
// are saved per member by the rank that runs it; particle_part_wall gives the particle part's wall
// seconds so far (for the checkpoints). If a member fails on any rank, every rank throws: the
// first failing member's own exception where it ran.
MembersApart run_members_apart(const MdScene& scene, MPI_Comm comm, int jobs,
                               const std::function<void(int, const md::MdProgress&)>& progress,
                               const MdCheckpointing* checkpointing,
                               const std::function<double()>& particle_part_wall);

}  // namespace granvv::app
