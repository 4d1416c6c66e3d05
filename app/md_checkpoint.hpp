#pragma once
// Checkpoints of a case's particle part (docs/outputs.md, "Checkpoints and resume"). They live in
// DIR/.granvv-checkpoint/ beside the outputs, outside the staging folder, so that they outlast a
// killed or interrupted run:
//   case.toml          the resolved case they belong to; a resume must resolve to the same text
//   member_<m>.h5      ensemble member m: its finished result, or the state its run last saved
//                      (md_bridge/md_run.hpp MdRunState), each file replaced whole by a rename
//   particles*.h5      the members' H5MD particle files while the particle part runs
// Rank 0 alone writes and reads them; the states go to the other ranks by the engine's restore.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/case_config.hpp"
#include "md_bridge/md_run.hpp"

namespace granvv::app {

// The checkpoint folder of an output folder.
std::filesystem::path checkpoint_folder(const std::filesystem::path& out_dir);

// The resolved case of the checkpoints in out_dir, if there are any.
std::optional<std::string> checkpointed_case(const std::filesystem::path& out_dir);

// "" if the checkpointed case (its case.toml text) and config resolve to the same run, keys
// that do not change results (md.checkpoint_interval, hydro.progress_seconds) aside; else the
// first key that differs, with both values.
std::string checkpointed_case_difference(const std::string& checkpointed_case,
                                         const CaseConfig& config);

// Removes any earlier checkpoints and starts a folder for resolved_case. Throws
// std::runtime_error if it cannot be written.
void start_checkpoints(const std::filesystem::path& out_dir, const std::string& resolved_case);

// One member's checkpoint: finished (state.so_far is its result, state.engine the engine's
// totals after it, without particles) or in progress (the run's state at a sample).
struct MemberCheckpoint {
  bool finished = false;
  md::MdRunState state;
  double particle_part_wall_seconds = 0.0;  // wall time of the particle part when it was saved
};

// Writes member m's checkpoint, replacing the previous one only once it is complete on the disk.
// Throws std::runtime_error (the previous checkpoint then stays).
void save_member_checkpoint(const std::filesystem::path& out_dir, int member,
                            const MemberCheckpoint& checkpoint);

// The members' checkpoints in order, up to the first member without one. Throws
// std::runtime_error naming the file if one cannot be read.
std::vector<MemberCheckpoint> load_member_checkpoints(const std::filesystem::path& out_dir,
                                                      int members);

// Removes the checkpoint folder (after a run whose results are complete); never throws.
void remove_checkpoints(const std::filesystem::path& out_dir);

}  // namespace granvv::app
