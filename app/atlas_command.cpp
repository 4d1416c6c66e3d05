// `granvv atlas` (app/atlas_command.hpp): the command line around the atlas library
// (atlas/atlas_weigh.hpp): its input checks, its folder and lock, its files and its page.
#include "app/atlas_command.hpp"

#include <chrono>
#include <cmath>
#include <iostream>
#include <thread>

#include "app/mpi_ranks.hpp"
#include "app/output_folder.hpp"
#include "app/report_command.hpp"
#include "app/summary.hpp"
#include "atlas/atlas_files.hpp"
#include "atlas/atlas_weigh.hpp"
#include "models/model.hpp"
#include "scene/atomic_file.hpp"
#include "scene/case_config.hpp"
#include "scene/interruption.hpp"

namespace granvv::app {
namespace fs = std::filesystem;

namespace {

// The options' own values, checked before the case is read.
void check_options(const AtlasOptions& options) {
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance)) {
    throw ConfigError("--tolerance " + format_real(options.tolerance) +
                      ": must be a relative error > 0, e.g. 1e-2");
  }
  if (!(options.budget > 0.0) || !std::isfinite(options.budget)) {
    throw ConfigError("--budget " + format_real(options.budget) +
                      ": must be > 0 wall seconds, e.g. 300");
  }
  if (options.jobs < 0) {
    throw ConfigError("--jobs " + std::to_string(options.jobs) +
                      ": must be >= 1 (0 or absent = the core count)");
  }
}

int weigh_into_folder(const AtlasOptions& options, const AtlasSetup& setup,
                      std::chrono::steady_clock::time_point start);

}  // namespace

int atlas_command(const AtlasOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  // The scene, validated before anything runs.
  std::optional<AtlasSetup> setup;
  try {
    check_options(options);
    setup = atlas_setup(options.case_name, options.sets);
  } catch (const ConfigError& e) {
    report_input_error(e);
    return 2;
  }
  // Under mpirun rank 0 alone runs the atlas (its folder, lock, runs and files), and every rank
  // ends with its exit code (app/mpi_ranks.hpp).
  return on_rank_zero_alone(join_ranks(false),
                            [&] { return weigh_into_folder(options, *setup, start); });
}

namespace {

// The atlas in its folder: the lock, the runs (cached in DIR/runs/), atlas.h5, atlas.json and
// the page; the command's exit code.
int weigh_into_folder(const AtlasOptions& options, const AtlasSetup& setup_,
                      std::chrono::steady_clock::time_point start) {
  const AtlasSetup* setup = &setup_;
  const fs::path dir = options.out_dir.empty() ? fs::path("out") / (setup->scene.name + "-atlas")
                                               : fs::path(options.out_dir);
  std::optional<FolderLock> lock;  // one atlas at a time in a folder
  try {
    lock.emplace(dir);
    fs::create_directories(dir / "runs");
  } catch (const std::exception& e) {
    std::cerr << "granvv: error: " << e.what() << "\n";
    return 2;
  }
  catch_interruptions();
  const int jobs =
      options.jobs > 0 ? options.jobs : std::max(1, int(std::thread::hardware_concurrency()));
  AtlasRunner runner(setup->scene, dir / "runs", jobs, options.quiet);
  std::optional<WeighedLadder> atlas;
  try {
    atlas = weigh_ladder(*setup, {options.tolerance, options.budget}, runner);
  } catch (const std::runtime_error& e) {
    std::cerr << "granvv: error: atlas: " << e.what() << "\n";
    return 1;
  }
  if (!atlas) {
    std::cerr << "granvv: atlas interrupted; the " << runner.made() << " runs made are cached in "
              << (dir / "runs").string() << ", and a re-run of the same atlas keeps them\n";
    return interrupted_exit_code();
  }
  atlas->document["wall_seconds"] = seconds_since(start);
  try {
    write_atlas_h5(dir / "atlas.h5", atlas->runs, atlas->errors.numerical, atlas->errors.model,
                   atlas->observables);
    write_file_atomically(dir / "atlas.json", summary_text(atlas->document));
  } catch (const std::exception& e) {
    std::cerr << "granvv: error: atlas: " << e.what() << "\n";
    return 1;
  }
  if (atlas->best) {
    std::cerr << "atlas: at tolerance " << options.tolerance << " the cheapest adequate model is "
              << describe(atlas->runs[*atlas->best].setting) << "\n";
  } else {
    std::cerr << "atlas: no run meets tolerance " << options.tolerance << " on every observable\n";
  }
  std::cerr << "atlas: wrote " << (dir / "atlas.json").string() << " (" << atlas->runs.size()
            << " runs, " << runner.made() << " made now)\n";
  if (options.report) {
    const int status = build_report(dir);
    if (status != 0) {
      std::cerr << "granvv: error: atlas page failed (exit " << status
                << "); atlas.json is complete\n";
      return 1;
    }
  }
  return 0;
}

}  // namespace

}  // namespace granvv::app
