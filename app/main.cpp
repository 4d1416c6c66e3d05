// granvv: granular hydrodynamics side by side with particle simulations (docs/architecture.md).
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "app/atlas_command.hpp"
#include "app/output_folder.hpp"
#include "app/report_command.hpp"
#include "app/run_command.hpp"
#include "app/sweep_command.hpp"
#include "scene/case_catalog.hpp"
#include "scene/case_config.hpp"
#include "scene/md_checkpoint.hpp"

namespace {
using namespace granvv::app;

// CLI11 would only say "A subcommand is required" for a misspelt command: name the commands.
bool command_is_known(CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return true;
  const std::string command = argv[1];
  bool known = false;
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    names.push_back(sub->get_name());
    known |= sub->get_name() == command;
  }
  if (!known) {
    report_input_error(ConfigError("unknown command '" + abbreviated(command) +
                                   "'; the commands are " + join(names, ", ") +
                                   " (granvv --help)"));
  }
  return known;
}

// `granvv resume DIR`: the run of the case its checkpoint holds, continued.
int resume_command(const std::string& dir, bool quiet, bool report, int jobs) {
  const std::filesystem::path case_file = checkpoint_folder(dir) / "case.toml";
  if (!std::filesystem::is_regular_file(case_file)) {
    report_input_error(ConfigError("granvv resume: " + abbreviated(dir) +
                                   " holds no checkpoint (no " + abbreviated(case_file.string()) +
                                   "); only particle runs with md.checkpoint_interval > 0 "
                                   "leave one"));
    return 2;
  }
  RunOptions resumed;
  resumed.case_name = case_file.string();
  resumed.out_dir = dir;
  resumed.quiet = quiet;
  resumed.report = report;
  resumed.resume = true;
  resumed.jobs = jobs;
  const int code = run_command(resumed);
  if (hdf5_broken()) end_process_now(code);
  return code;
}

// `granvv list`: the scenes of cases/ with their descriptions.
int list_command() {
  std::vector<SceneListing> scenes;
  try {
    scenes = list_scenes();
  } catch (const ConfigError& e) {
    report_input_error(e);
    return 2;
  }
  for (const auto& s : scenes) {
    std::cout << s.name << "  " << s.description;
    if (!s.reference.empty()) std::cout << "  [" << s.reference << "]";
    std::cout << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace granvv::app;
  CLI::App app{"granvv: granular hydrodynamics verified against exact solutions and MD"};
  app.set_version_flag("--version", GRANVV_VERSION);
  app.require_subcommand(1);

  RunOptions run;
  auto* run_cmd = app.add_subcommand("run", "run a scene (no CASE: the embedded quickstart)");
  run_cmd->add_option("case", run.case_name, "case file or scene name from `granvv list`");
  run_cmd->add_option("--out", run.out_dir, "output folder (default out/<case name>)");
  run_cmd->add_option("--set", run.sets, "override a case key: --set physics.K=1e-3 (TOML value)")
      ->allow_extra_args(false);
  run_cmd->add_flag("--dry-run", run.dry_run, "print the resolved configuration and stop");
  run_cmd->add_flag("--quiet", run.quiet, "no progress lines on stderr");
  bool no_report = false;
  run_cmd->add_flag("--no-report", no_report, "skip report.html (results.h5, summary.json only)");
  run_cmd->add_flag("--resume", run.resume,
                    "continue the checkpoints in the output folder if they are of this case");
  constexpr const char* kJobsHelp =
      "cores for the ensemble's members (default: the cores, shared among the MPI ranks of the "
      "machine; with more members than N, N + 1 run and pass the N cores round); the results do "
      "not depend on it. The event-driven engine only: LAMMPS "
      "runs its members one after another (its library instances are not independent)";
  run_cmd->add_option("--jobs", run.jobs, kJobsHelp)->check(CLI::PositiveNumber);

  std::string resume_dir;
  bool resume_quiet = false, resume_no_report = false;
  auto* resume_cmd = app.add_subcommand(
      "resume", "continue the interrupted run in DIR from its last checkpoint (its own case)");
  resume_cmd->add_option("dir", resume_dir, "output folder of the interrupted run")->required();
  resume_cmd->add_flag("--quiet", resume_quiet, "no progress lines on stderr");
  resume_cmd->add_flag("--no-report", resume_no_report, "skip report.html");
  int resume_jobs = 0;
  resume_cmd->add_option("--jobs", resume_jobs, kJobsHelp)->check(CLI::PositiveNumber);

  SweepOptions sweep;
  auto* sweep_cmd = app.add_subcommand(
      "sweep", "run a scene once per value of one key: --set KEY=V1,V2,... (and a sweep report)");
  sweep_cmd->add_option("case", sweep.case_name, "case file or scene name from `granvv list`")
      ->required();
  sweep_cmd->add_option("--out", sweep.out_dir, "output folder (default out/<case>-sweep-<key>)");
  sweep_cmd
      ->add_option("--set", sweep.sets,
                   "KEY=V1,V2,... sweeps KEY; KEY=V applies to every point (TOML value)")
      ->allow_extra_args(false);
  sweep_cmd->add_flag("--quiet", sweep.quiet, "no progress lines of the runs on stderr");
  bool sweep_no_report = false;
  sweep_cmd->add_flag("--no-report", sweep_no_report, "skip the reports (json and h5 only)");
  sweep_cmd
      ->add_option("--power-r-min", sweep.power_r_min,
                   "fit the power of (1 - r^2) over restitutions >= this")
      ->check(CLI::Range(0.0, 1.0));

  AtlasOptions atlas;
  auto* atlas_cmd = app.add_subcommand(
      "atlas",
      "every model of a scene against cost: work-precision, stability, cheapest adequate model");
  atlas_cmd->add_option("case", atlas.case_name, "case file or scene name from `granvv list`")
      ->required();
  atlas_cmd->add_option("--set", atlas.sets, "override a case key (TOML value)")
      ->allow_extra_args(false);
  atlas_cmd->add_option("--tolerance", atlas.tolerance,
                        "relative error a model must meet on every observable (default 1e-2)");
  atlas_cmd->add_option("--budget", atlas.budget, "wall seconds for the runs (default 300)");
  atlas_cmd->add_option("--jobs", atlas.jobs, "runs at a time (default: the core count)");
  atlas_cmd->add_option("--out", atlas.out_dir, "output folder (default out/<case>-atlas)");
  atlas_cmd->add_flag("--quiet", atlas.quiet, "no progress lines on stderr");
  bool atlas_no_report = false;
  atlas_cmd->add_flag("--no-report", atlas_no_report, "skip atlas.html");

  auto* list_cmd = app.add_subcommand("list", "list the scenes in cases/");

  std::string report_dir;
  auto* report_cmd = app.add_subcommand(
      "report", "rebuild DIR/report.html from DIR/results.h5 (a run) or DIR/sweep.json (a sweep)");
  report_cmd->add_option("dir", report_dir, "output folder of a run or a sweep")->required();

  std::string movie_dir, movie_out;
  auto* movie_cmd = app.add_subcommand(
      "movie", "animate the particle frames of the run in DIR beside the density profiles (a GIF)");
  movie_cmd->add_option("dir", movie_dir, "output folder of a particle run that wrote frames")
      ->required();
  movie_cmd->add_option("--out", movie_out, "the animation, a .gif (default DIR/movie.gif)");

  if (!command_is_known(app, argc, argv)) return 2;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  if (*run_cmd) {
    run.report = !no_report;
    const int code = run_command(run);
    if (hdf5_broken()) end_process_now(code);
    return code;
  }
  if (*resume_cmd) return resume_command(resume_dir, resume_quiet, !resume_no_report, resume_jobs);
  if (*sweep_cmd) {
    sweep.report = !sweep_no_report;
    return sweep_command(sweep);
  }
  if (*atlas_cmd) {
    atlas.report = !atlas_no_report;
    return atlas_command(atlas);
  }
  if (*list_cmd) return list_command();
  if (*report_cmd) return report_command(report_dir);
  if (*movie_cmd) {
    std::vector<std::string> args{movie_dir};
    if (!movie_out.empty()) args.insert(args.end(), {"--out", movie_out});
    return run_python_script("particle_movie.py", args);
  }
  return 2;
}
