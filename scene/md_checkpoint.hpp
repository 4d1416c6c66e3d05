#pragma once
// Checkpoints of a case's particle part (docs/outputs.md, "Checkpoints and resume"). They live in
// DIR/.granvv-checkpoint/ beside the outputs, outside the staging folder, so that they outlast a
// killed or interrupted run:
//   case.toml          the resolved case they belong to (what `granvv resume` runs)
//   inputs.json        the fingerprint of the inputs they were made from (the resolved case and
//                      the SHA-256 of every file it reads): a resume must have the same
//   member_<m>.h5      ensemble member m: its finished result, or the state its run last saved
//                      (md_bridge/md_run.hpp MdRunState), each file replaced whole by a rename;
//                      it carries the SHA-256 of inputs.json, and is not read under another
//   member_<m>.step<S>.rank<k>.h5  under MPI, rank k's block of the particles of member m's
//                      state at step S (EngineState::particle_blocks > 1), written by rank k of
//                      the ranks that run the member (scene/md_members.hpp: all, or its group)
//   particles*.h5      the members' H5MD particle files while the particle part runs
// Rank 0 alone writes the member files; every rank reads them, and its own block file.
#include <mpi.h>

#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "md_bridge/md_run.hpp"
#include "scene/case_config.hpp"

namespace granvv::app {

// The checkpoint folder of an output folder.
std::filesystem::path checkpoint_folder(const std::filesystem::path& out_dir);

// The resolved case of the checkpoints in out_dir, if there are any.
std::optional<std::string> checkpointed_case(const std::filesystem::path& out_dir);

// "" if the checkpoints in out_dir were made from the inputs whose fingerprint is `now`
// (scene/input_fingerprint.hpp: the resolved case, keys outside the results aside, and every
// file it reads); else one phrase naming what changed (a key with both values, a file whose
// SHA-256 differs, a checkpoint without a record of its inputs).
std::string checkpoint_inputs_difference(const std::filesystem::path& out_dir,
                                         const nlohmann::json& now);

// Removes any earlier checkpoints and starts a folder for resolved_case, with the fingerprint of
// its inputs (inputs.json). Throws std::runtime_error if it cannot be written.
void start_checkpoints(const std::filesystem::path& out_dir, const std::string& resolved_case,
                       const nlohmann::json& inputs);

// One member's checkpoint: finished (state.so_far is its result, state.engine the engine's
// totals after it, without particles) or in progress (the run's state at a sample).
struct MemberCheckpoint {
  bool finished = false;
  md::MdRunState state;
  double particle_part_wall_seconds = 0.0;  // wall time of the particle part when it was saved
  bool missing = false;  // no checkpoint of this member (members that run apart leave gaps)
  // Saved in blocks (state.engine.particle_blocks > 1): every rank's block in ID order, for the
  // checks of the whole state (state.engine holds this rank's block alone).
  md::ParticleFrame all_blocks;
};

// Writes member m's checkpoint, replacing the previous one only once it is complete on the disk.
// Called on every rank of comm: with the particles in blocks (particle_blocks > 1) it is
// collective, each rank writing its block file before rank 0 writes the member file that names
// them; otherwise rank 0 alone writes. Throws std::runtime_error (on every rank that took part;
// the previous checkpoint then stays).
void save_member_checkpoint(const std::filesystem::path& out_dir, int member,
                            const MemberCheckpoint& checkpoint, MPI_Comm comm = MPI_COMM_SELF);

// The members' checkpoints in order, up to the last member with one (a member without one
// between them is `missing`), as rank `rank` of `ranks` restores them (its own block of particles
// saved in blocks). Throws std::runtime_error naming the file if one cannot be read, or if it was
// saved in blocks over another number of ranks.
std::vector<MemberCheckpoint> load_member_checkpoints(const std::filesystem::path& out_dir,
                                                      int members, int rank = 0, int ranks = 1);

// Throws std::runtime_error naming the member and what is wrong if a loaded checkpoint cannot
// belong to a run of spec: its place in the run, the lengths and finiteness of its series, its
// snapshots' bins, its particles' count and finiteness, its engine's numbers, and the engine's
// own state of a member in progress as `engine` (an engine of the run) finds it.
void check_member_checkpoints(const std::vector<MemberCheckpoint>& checkpoints,
                              const md::MdRunSpec& spec, const md::ParticleEngine& engine);

// Removes the checkpoint folder (after a run whose results are complete); never throws.
void remove_checkpoints(const std::filesystem::path& out_dir);

}  // namespace granvv::app
