#include "scene/md_members.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "fields/hdf5_datasets.hpp"
#include "md_bridge/every_rank.hpp"
#include "md_bridge/mpi_environment.hpp"
#include "scene/core_turns.hpp"
#include "scene/md_scene.hpp"

namespace granvv::app {

namespace {

// How long a member holds a core before it passes it on to a waiting one (scene/core_turns.hpp):
// long against the cache refill a switch costs (milliseconds), short against a member's run.
constexpr double kCoreSliceSeconds = 0.5;

// Another member failed: this one stops at its next sample.
struct Abandoned : std::runtime_error {
  Abandoned() : std::runtime_error("abandoned after another member failed") {}
};

}  // namespace

MemberGroups member_groups(const md::ParticleEngine& engine, int ranks) {
  MemberGroups g;
  const int per_member = engine.ranks_per_member();
  g.apart = engine.independent_members() || per_member > 0;
  g.size = engine.independent_members()                ? 1
           : per_member > 0 && ranks % per_member == 0 ? per_member
                                                       : ranks;
  g.groups = ranks / g.size;
  return g;
}

MembersApart run_members_apart(const MdScene& scene, MPI_Comm comm, const MemberGroups& groups,
                               int jobs, const std::string& log_dir,
                               const std::function<void(int, const md::MdProgress&)>& progress,
                               const MdCheckpointing* checkpointing,
                               const std::function<double()>& particle_part_wall) {
  using clock = std::chrono::steady_clock;
  md::MpiEnvironment::ensure();
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const int members = scene.ensemble;
  const int group = groups.group_of(rank);
  const bool group_leader = groups.rank_in_group(rank) == 0;
  auto owner = [&groups](int m) { return groups.leader(m); };
  MembersApart out;
  out.records.resize(std::size_t(members));
  const bool saving = checkpointing && !checkpointing->out_dir.empty();
  const std::vector<MemberCheckpoint> none;
  const auto& resume = checkpointing ? checkpointing->resume : none;
  auto earlier_of = [&](int m) -> const MemberCheckpoint* {
    return m < int(resume.size()) && !resume[std::size_t(m)].missing ? &resume[std::size_t(m)]
                                                                     : nullptr;
  };
  std::vector<int> to_run;  // this rank's members still to run, in order
  for (int m = 0; m < members; ++m) {
    const MemberCheckpoint* earlier = earlier_of(m);
    if (earlier && earlier->finished) {  // its result as it was, and its engine's totals
      out.records[std::size_t(m)] = {earlier->state.so_far, earlier->state.engine};
      ++out.members_restored;
      continue;
    }
    if (earlier && out.resumed_member < 0) {
      out.resumed_member = m;
      out.resumed_t = md::resumed_time(earlier->state);
    }
    if (m % groups.groups == group) to_run.push_back(m);
  }

  // MPI calls from several threads at once need MPI_THREAD_MULTIPLE and a communicator each; a
  // member over several ranks runs one at a time. With jobs > 1 one member more than jobs runs,
  // the jobs cores passed round among them (scene/core_turns.hpp), so that a heavy member that
  // comes late does not run alone at the end.
  const int cores = std::max(1, std::min<int>(jobs, int(to_run.size())));
  out.threads = cores > 1 ? std::min<int>(cores + 1, int(to_run.size())) : 1;
  if (md::MpiEnvironment::thread_level() < MPI_THREAD_MULTIPLE || groups.size > 1) out.threads = 1;
  out.cores = out.threads > 1 ? cores : 1;
  CoreTurns turns(out.cores, kCoreSliceSeconds);
  CoreTurns* const turns_for_members = out.threads > out.cores ? &turns : nullptr;
  MPI_Comm group_comm;
  MPI_Comm_split(comm, group, rank, &group_comm);
  std::vector<MPI_Comm> comms(std::size_t(out.threads));
  for (MPI_Comm& c : comms) MPI_Comm_dup(group_comm, &c);
  MPI_Comm_free(&group_comm);

  std::mutex mutex;  // the progress callback, the checkpoint count
  std::atomic<std::size_t> next{0};
  std::atomic<bool> abandon{false};
  std::vector<std::exception_ptr> errors(to_run.size());
  auto save = [&](int member, MemberCheckpoint c, MPI_Comm member_comm) {
    c.particle_part_wall_seconds = particle_part_wall();
    try {
      const std::lock_guard<std::recursive_mutex> lock(h5::library_mutex());
      save_member_checkpoint(checkpointing->out_dir, member, c, member_comm);
      const std::lock_guard<std::mutex> count(mutex);
      if (group_leader) ++out.checkpoints_written;
    } catch (const std::exception& e) {
      const std::lock_guard<std::mutex> lock(mutex);
      if (checkpointing->warn) checkpointing->warn(e.what());
    }
  };
  auto run_member = [&](int m, MPI_Comm member_comm) {
    const auto engine = make_engine(scene, log_dir, member_comm);
    md::MdRunSpec spec = scene.spec;
    spec.seed += static_cast<std::uint64_t>(m);
    spec.h5md_path = member_h5md_path(scene, m);
    auto last_save = clock::now();
    md::MdCheckpoints checkpoints;
    if (saving) {
      checkpoints.due = [&] {
        const double since = std::chrono::duration<double>(clock::now() - last_save).count();
        return (checkpointing->interval_seconds > 0.0 &&
                since >= checkpointing->interval_seconds) ||
               (checkpointing->stop_requested && checkpointing->stop_requested());
      };
      checkpoints.save = [&](const md::MdRunState& state) {
        save(m, {false, state, 0.0}, member_comm);
        last_save = clock::now();
      };
    }
    checkpoints.resume_from = earlier_of(m) ? &earlier_of(m)->state : nullptr;
    MemberRecord record;
    CoreTurn core(turns_for_members);
    record.run = md::run_md(
        spec, *engine,
        [&](const md::MdProgress& p) {
          if (abandon) throw Abandoned();
          {
            const std::lock_guard<std::mutex> lock(mutex);
            if (progress) progress(m, p);
          }
          core.offer();
        },
        checkpoints);
    record.totals = engine->save_state(false);
    if (saving) {  // the finished member, and its engine's totals
      md::MdRunState done;
      done.engine = record.totals;
      done.so_far = record.run;
      save(m, {true, done, 0.0}, member_comm);
    }
    out.records[std::size_t(m)] = std::move(record);
  };
  auto work = [&](std::size_t thread) {
    for (std::size_t i = next++; i < to_run.size(); i = next++) {
      if (abandon) return;
      try {
        run_member(to_run[i], comms[thread]);
      } catch (...) {
        errors[i] = std::current_exception();
        abandon = true;
      }
    }
  };
  if (out.threads == 1) {
    work(0);
  } else {
    std::vector<std::thread> pool;
    for (std::size_t j = 0; j < comms.size(); ++j) pool.emplace_back(work, j);
    for (auto& thread : pool) thread.join();
  }
  for (MPI_Comm& c : comms) MPI_Comm_free(&c);

  // The first member's failure in member order (not one that stopped because of it).
  std::exception_ptr first;
  for (const auto& error : errors) {
    if (!error) continue;
    try {
      std::rethrow_exception(error);
    } catch (const Abandoned&) {
      continue;
    } catch (...) {
      first = error;
      break;
    }
  }
  md::on_every_rank(comm, [&] {
    if (first) std::rethrow_exception(first);
  });
  share_member_records(out.records, owner, comm);
  MPI_Allreduce(MPI_IN_PLACE, &out.checkpoints_written, 1, MPI_INT, MPI_SUM, comm);
  return out;
}

}  // namespace granvv::app
