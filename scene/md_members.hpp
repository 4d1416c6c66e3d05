#pragma once
// The members of an ensemble run apart: each member on an engine of its own, made afresh with its
// seed (md.seed + m). For an engine whose members are independent
// (md::ParticleEngine::independent_members) member m runs on MPI rank m mod P, and on each rank
// in threads on `jobs` cores (with more members than jobs, jobs + 1 threads pass the cores
// round, scene/core_turns.hpp); for an engine that runs a member over several ranks
// (md::ParticleEngine::ranks_per_member) the ranks form groups of that many, member m runs on
// group m mod G, one member at a time. Every member's result is the one it has when the members
// run in turn on one rank, or on one group (docs/performance.md, "Ensemble members in parallel").
#include <mpi.h>

#include <functional>
#include <string>
#include <vector>

#include "md_bridge/particle_engine.hpp"
#include "scene/md_checkpoint.hpp"
#include "scene/member_exchange.hpp"

namespace granvv::app {

struct MdScene;
struct MdCheckpointing;

// How an ensemble's members are spread over the P ranks of a run: in `groups` groups of `size`
// consecutive ranks, member m on group m mod groups (apart); or one after another over every
// rank on the one engine (not apart: one group of all of them).
struct MemberGroups {
  bool apart = false;
  int size = 1;    // ranks per group
  int groups = 1;  // P / size
  int group_of(int rank) const { return rank / size; }
  int rank_in_group(int rank) const { return rank % size; }
  // The rank that runs member m (the first of its group): its result is sent from there.
  int leader(int member) const { return (member % groups) * size; }
};

// The engine's groups over `ranks` ranks: one rank each for independent members, its
// ranks_per_member where that is > 0 (one group of every rank where it does not divide them, as
// on the atlas's rank 0 alone), else the members in turn.
MemberGroups member_groups(const md::ParticleEngine& engine, int ranks);

struct MembersApart {
  std::vector<MemberRecord> records;  // every member in order, the same on every rank
  int threads = 1;                    // members at a time on this rank
  int cores = 1;                      // the cores they share (threads > cores: passed round)
  int checkpoints_written = 0;        // over every rank
  int resumed_member = -1;            // the first member continued from its checkpoint
  double resumed_t = 0.0;
  int members_restored = 0;  // finished members taken from the checkpoints
};

// Runs the scene's members over the groups of comm's ranks (member_groups over comm's size) and,
// on a group of one rank, `jobs` threads (collective). The members' engines log into log_dir
// ("" = none; the engine logs on the first rank of a group only). The progress callback is called
// from one thread at a time; an exception it throws (an interruption) stops that member, and the
// others at their next sample. Checkpoints (checkpointing may be null) are saved per member by the
// group that runs it; particle_part_wall gives the particle part's wall seconds so far (for the
// checkpoints). If a member fails on any rank, every rank throws: the first failing member's own
// exception where it ran.
MembersApart run_members_apart(const MdScene& scene, MPI_Comm comm, const MemberGroups& groups,
                               int jobs, const std::string& log_dir,
                               const std::function<void(int, const md::MdProgress&)>& progress,
                               const MdCheckpointing* checkpointing,
                               const std::function<double()>& particle_part_wall);

}  // namespace granvv::app
