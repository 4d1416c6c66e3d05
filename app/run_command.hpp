#pragma once
#include <string>
#include <vector>

namespace granvv::app {

struct RunOptions {
  std::string case_name;  // path or scene name; empty: the embedded default
  std::string out_dir;    // default out/<case name>
  std::vector<std::string> sets;
  bool dry_run = false;
  bool quiet = false;
  bool report = true;
  // Continue the checkpoints in the output folder (scene/md_checkpoint.hpp) if they are of this
  // resolved case (exit 2 if they are of another); without any, start from t = 0.
  bool resume = false;
  // Ensemble members at a time in threads on each rank, for an engine whose members are
  // independent (0: the cores of the machine shared among its ranks).
  int jobs = 0;
};

// `granvv run`: exit 0 for a finished run (status ok or singularity), 1 if the run failed,
// 2 for bad input (nothing is written then).
int run_command(const RunOptions& options);

}  // namespace granvv::app
