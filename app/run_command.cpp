#include "app/run_command.hpp"

#include <H5Cpp.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/null_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "app/compare_output.hpp"
#include "app/md_output.hpp"
#include "app/mpi_ranks.hpp"
#include "app/output_folder.hpp"
#include "app/pressure_output.hpp"
#include "app/report_command.hpp"
#include "app/results_file.hpp"
#include "app/summary.hpp"
#include "app/transport_output.hpp"
#include "compare/transport_coefficients.hpp"
#include "md_bridge/mpi_environment.hpp"
#include "models/compare_scene.hpp"
#include "models/model.hpp"
#include "scene/atomic_file.hpp"
#include "scene/case_catalog.hpp"
#include "scene/case_config.hpp"
#include "scene/hydro_scene.hpp"
#include "scene/initial_provenance.hpp"
#include "scene/input_fingerprint.hpp"
#include "scene/interruption.hpp"
#include "scene/md_checkpoint.hpp"
#include "scene/md_members.hpp"
#include "scene/md_scene.hpp"

namespace granvv::app {
namespace fs = std::filesystem;

namespace {

std::shared_ptr<spdlog::logger> make_logger(const fs::path& log_file, bool quiet) {
  auto console = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
  console->set_level(quiet ? spdlog::level::warn : spdlog::level::info);
  console->set_pattern("%^%l%$: %v");
  auto file = std::make_shared<spdlog::sinks::basic_file_sink_mt>(log_file.string(), true);
  file->set_level(spdlog::level::debug);
  file->set_pattern("[%Y-%m-%d %H:%M:%S.%e] %l: %v");
  auto logger = std::make_shared<spdlog::logger>("granvv", spdlog::sinks_init_list{console, file});
  logger->set_level(spdlog::level::debug);
  logger->flush_on(spdlog::level::info);
  return logger;
}

// Fraction done: by time towards t_end, or by decades of density towards the singularity.
double progress_fraction(const hydro::Progress& p) {
  const double by_time = p.t / p.t_end;
  const double by_density = p.n_max > 1.0 ? std::log(p.n_max) / std::log(p.stop_density) : 0.0;
  return std::clamp(std::max(by_time, by_density), 1e-9, 1.0);
}

// The particle engine with a progress line every progress_seconds and its throughput.
MdOutcome run_particles(const MdScene& scene, md::ParticleEngine& engine, double progress_seconds,
                        const MdCheckpointing& checkpointing, spdlog::logger& log) {
  const auto& sc = scene.spec.scene;
  log.info(
      "md: {} disks, Lx = {:.6g}, Ly = {:.6g} sigma, phi = {:.4g}, r = {:.6g} (K = {:.4g}, "
      "q = {:.4g}, {} unstable modes), ensemble of {}",
      sc.particles, sc.box_length, sc.box_width, sc.area_fraction, sc.restitution, sc.physics().K,
      sc.physics().q, sc.unstable_modes(), scene.ensemble);
  log.info("md: work estimate {}", scene.estimate.describe());
  if (!checkpointing.resume.empty()) {
    int finished = 0;
    std::string running;
    for (std::size_t m = 0; m < checkpointing.resume.size(); ++m) {
      const MemberCheckpoint& saved = checkpointing.resume[m];
      if (saved.missing) continue;
      if (saved.finished) {
        ++finished;
      } else {
        running += fmt::format(", member {} at t = {:.6g}", m + 1, md::resumed_time(saved.state));
      }
    }
    log.info("md: resuming from the checkpoints: {} finished member(s){}", finished, running);
  }
  auto last = std::chrono::steady_clock::now();
  ParticleModel model(
      scene, engine,
      [&](int member, const md::MdProgress& p) {
        stop_if_interrupted();
        const auto now = std::chrono::steady_clock::now();
        if (std::chrono::duration<double>(now - last).count() < progress_seconds) return;
        last = now;
        // The share of this member's work done, by the work estimate's model (a clustering
        // scene's collisions come late), at the member's measured wall time per share so far.
        const double f = scene.estimate.member_share_done(p.t, p.t_end);
        const md::EngineCost& cost = p.cost;  // its own unit: atom_steps, collisions
        log.info(
            "md member {}/{} t={:<9.5g} T={:<10.5g} steps {} {:.3g} {}/s ETA {:.1f} s", member + 1,
            scene.ensemble, p.t, p.T, p.steps, cost.per_second(), cost.work_unit,
            scene.estimate.seconds_left(member, scene.ensemble, scene.jobs, f, p.wall_seconds));
      },
      &checkpointing);
  model.run();
  const MdOutcome& out = model.outcome();
  if (out.threads > 1) {
    log.info("md: members ran {} at a time in threads on {} cores", out.threads, out.cores);
  }
  if (out.member_groups > 1) {
    log.info("md: members ran on {} groups of {} MPI rank(s), member m on group m mod {}",
             out.member_groups, out.ranks_per_group, out.member_groups);
  }
  log.info("md: restitution {:.6f} (target {:.6f}), {}", out.collision_rule.restitution,
           sc.restitution, out.collision_rule.description);
  log.info(
      "md: {:.3g} s wall, {:.3g} {}/s, Haff t0 = {:.5g} +- {:.2g} (kinetic theory "
      "{:.5g} with chi(phi), {:.5g} dilute)",
      out.wall_seconds, out.cost.per_second(), out.cost.work_unit, out.haff.t0, out.haff.t0_error,
      out.haff_t0_theory, out.haff_t0_theory_dilute);
  return out;
}

// The particle files (particles*.h5) of a run whose frames were written beside its
// checkpoints, hard-linked into the staging folder (the checkpoint keeps its own link until the
// run is complete). False if one could not be put there (it then stays with the checkpoints).
bool link_particle_files(const fs::path& from, const fs::path& to, spdlog::logger& log) {
  bool all = true;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(from, error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("particles", 0) != 0 || entry.path().extension() != ".h5") continue;
    fs::create_hard_link(entry.path(), to / name, error);
    if (error) fs::copy_file(entry.path(), to / name, fs::copy_options::overwrite_existing, error);
    if (error) {
      log.warn("cannot put {} beside the outputs ({}); it stays in {}", name, error.message(),
               from.string());
      all = false;
    }
  }
  return all;
}

// The continuum engine with a progress line every progress_seconds and its throughput.
HydroOutcome run_continuum(const HydroScene& scene, spdlog::logger& log) {
  auto last = std::chrono::steady_clock::now();  // first line after progress_seconds
  auto progress = [&](const hydro::Progress& p) {
    stop_if_interrupted();
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last).count() < scene.progress_seconds) return;
    last = now;
    const double f = progress_fraction(p);
    log.info("step {:>7} t={:<10.6g} dt={:<10.3e} ({}) n_max={:<10.4g} E={:<10.5g} ETA {:.1f} s",
             p.step, p.t, p.dt, p.limited_by, p.n_max, p.energy, p.wall_seconds * (1 - f) / f);
  };
  HydroModel model(scene, 0, progress);
  model.run();
  const HydroOutcome& outcome = model.outcome();
  const auto& run = outcome.run;
  log.info("hydro stopped: {} (status {}) at t = {:.6g} after {} steps ({} rejected)",
           run.stop_reason, hydro::to_string(run.status), run.snapshots.back().state.t, run.steps,
           run.rejected_steps);
  log.info("hydro throughput: {:.3g} s wall, {:.3g} cell-steps/s", run.wall_seconds,
           run.steps * double(scene.cells) / std::max(run.wall_seconds, 1e-12));
  if (outcome.singularity && run.status == hydro::RunStatus::singularity) {
    log.info("singularity time tau = {:.6g} from 1/n_max over n in [{:.3g}, {:.3g}]",
             outcome.singularity->tau, outcome.singularity->n_min, outcome.singularity->n_max);
  }
  return outcome;
}

// The end of the output protocol (docs/outputs.md): the summary and the report are written into
// the staging folder, which then replaces the previous outputs, or, for an interrupted run, is
// kept beside them as interrupted-run/. If not even the summary can be written, nothing of this
// run is kept and the previous outputs stay as they were.
int finish_outputs(OutputFolder& folder, nlohmann::json& summary, spdlog::logger& log,
                   bool interrupted, bool report, int exit_code) {
  const fs::path work = folder.staging();
  const fs::path dir = folder.target();
  std::string failure;
  try {
    if (fs::exists(work / "results.h5")) {
      write_output(Ranks{}, work / "results.h5",
                   [&] { stamp_run_id(work / "results.h5", folder.run_id()); });
    }
    write_file_atomically(work / "summary.json", summary_text(summary));
  } catch (const std::exception& e) {
    failure = e.what();
  } catch (const H5::Exception& e) {  // write_output converts these; kept for safety
    mark_hdf5_broken();
    failure = e.getFuncName() + ": " + e.getDetailMsg();
  }
  if (!failure.empty()) {  // a full disk: the data files make room for an honest summary
    folder.remove_staged_data();
    const std::string earlier = summary.value("error", std::string());
    summary["status"] = interrupted ? "interrupted" : "failed";
    summary["error"] = (earlier.empty() ? "" : earlier + "; ") + "cannot write the outputs (" +
                       failure + "); results.h5 and the particle files were removed to make room";
    exit_code = interrupted ? exit_code : 1;
    try {
      write_file_atomically(work / "summary.json", summary_text(summary));
    } catch (const std::exception& e) {
      log.error("cannot write the outputs ({}); {} keeps what it held before this run", e.what(),
                dir.string());
      folder.abandon();
      return 1;
    }
    log.error("{}", summary["error"].get<std::string>());
  }
  if (interrupted) {
    log.warn("the previous outputs in {} are kept; this run's are in {}", dir.string(),
             (dir / "interrupted-run").string());
    try {
      folder.keep_as_interrupted();
    } catch (const std::exception& e) {
      log.error("cannot keep the interrupted run's outputs: {}", e.what());
      folder.abandon();
    }
    return interrupted_exit_code();
  }
  if (report && fs::exists(work / "results.h5")) {
    const int status = build_report(work);
    if (status != 0) {
      log.error("report script failed (exit {}); results.h5 and summary.json are complete", status);
      exit_code = exit_code ? exit_code : 1;
    }
  }
  try {
    folder.commit();
  } catch (const std::exception& e) {
    log.error("cannot move the outputs into {}: {}; {}", dir.string(), e.what(),
              folder.commit_begun() ? "the next run or `granvv report` finishes the replacement"
                                    : dir.string() + " keeps what it held before this run");
    return 1;
  }
  log.info("wrote {}", (dir / "summary.json").string());
  if (report && fs::exists(dir / "report.html")) {
    log.info("report: {}", (dir / "report.html").string());
  }
  return exit_code;
}

// compare.closures with more than one closure: every further closure's hydro runs against the
// same particle ensemble and is compared on its own. results.h5 gets /hydro_closures/<name> (its
// hydro) and /compare/closures/<name> (its comparison, the first closure's too); the compare
// block gets `closures` {<name>: its compare block with its own hydro block} and
// `closure_order`. The first closure's hydro, /hydro and the compare block are as without the list.
void compare_closures(const CompareScene& compare, const HydroScene& first,
                      const HydroOutcome& first_outcome, const CompareOutcome& first_compared,
                      const MdScene& md_scene, const MdOutcome& md, const Ranks& ranks,
                      const fs::path& results, nlohmann::json& block, spdlog::logger& log) {
  write_output(ranks, results, [&] {
    create_group(results, "/compare/closures");
    create_group(results, "/hydro_closures");
  });
  nlohmann::json entries = nlohmann::json::object();
  for (const std::string& name : compare.closures) {
    HydroScene scene = first;
    scene.closure = name;
    std::optional<HydroOutcome> run;
    std::optional<CompareOutcome> own;
    if (name != first.closure) {
      log.info("hydro ({}): the same particles, closure \"{}\"", name, name);
      run = run_continuum(scene, log);
      own = compare_engines(compare, scene, *run, md_scene, md);
      write_output(ranks, results,
                   [&] { write_hydro_results(results, scene, *run, "/hydro_closures/" + name); });
    }
    const HydroOutcome& outcome = run ? *run : first_outcome;
    const CompareOutcome& compared = own ? *own : first_compared;
    write_output(ranks, results, [&] {
      write_compare_results(results, compare, md_scene, compared, "/compare/closures/" + name);
    });
    entries[name] = closure_comparison_summary(compare, scene, outcome, md_scene, md, compared);
    log.info("compare ({}): {}", name, compared.verdict);
  }
  block["closures"] = entries;
  block["closure_order"] = compare.closures;
}

// A resume continues the checkpoints of the same resolved case (every rank reads them): why it
// cannot (empty: it can), with the checkpoints it continues in resume_from.
std::string resume_problem(const nlohmann::json& inputs, const fs::path& dir,
                           const MdScene& md_scene, const Ranks& ranks,
                           std::vector<MemberCheckpoint>& resume_from) {
  const std::string difference = checkpoint_inputs_difference(dir, inputs);
  if (!difference.empty()) {
    return "cannot resume: the checkpoint in " + checkpoint_folder(dir).string() +
           " was made from other inputs (" + difference + "); run without --resume to start anew";
  }
  try {
    // A member saved in blocks is read back by its group's ranks, each its own block.
    const auto engine = make_engine(md_scene, "");
    const MemberGroups groups = member_groups(*engine, ranks.size);
    resume_from = load_member_checkpoints(dir, md_scene.ensemble, groups.rank_in_group(ranks.rank),
                                          groups.size);
    check_member_checkpoints(resume_from, md_scene.spec, *engine);
  } catch (const std::exception& e) {
    return std::string("cannot resume: ") + e.what() + "; remove " +
           checkpoint_folder(dir).string() + " to start anew";
  }
  return "";
}

// What the parts of one run share (run_command).
struct RunContext {
  const RunOptions& options;
  const CaseConfig& config;
  HydroScene& scene;
  std::optional<MdScene>& md_scene;
  const Ranks& ranks;
  bool writer;
  fs::path dir, work;
  OutputFolder* folder;  // the writer's; null on the other ranks
  spdlog::logger& log;
  nlohmann::json& summary;
  std::vector<MemberCheckpoint> resume_from;  // a resume's checkpoints
  std::optional<std::string> checkpointed;    // the resolved case of the folder's checkpoint
  bool frames_in_checkpoints = false;         // the particle files are beside the checkpoints
};

// The particle part of a run: the engine, its checkpoints (scene/md_checkpoint.hpp: the same
// choice on every rank, rank 0 writes them, and the particle files go with them until the
// particle part is done) and its frames. The summary on disk says "failed" until it returns,
// because the Debian LAMMPS ends the process on any error inside a command (docs/physics.md §10).
MdOutcome run_particle_part(RunContext& c) {
  c.summary["md"] = {{"status", "failed"}};
  c.md_scene->spec.creator_version = GRANVV_VERSION;
  const auto engine = make_engine(*c.md_scene, c.writer ? c.work.string() : "");
  MdCheckpointing checkpointing;
  checkpointing.resume = c.resume_from;
  bool checkpoint_folder_ok = true;
  if (c.md_scene->checkpoint_interval > 0.0) {
    checkpointing.out_dir = c.dir;
    checkpointing.interval_seconds = c.md_scene->checkpoint_interval;
    checkpointing.stop_requested = [&] {
      return checkpoint_folder_ok && interruption_signal() != 0;
    };
    checkpointing.warn = [&](const std::string& what) { c.log.warn("{}", what); };
    if (c.writer && c.resume_from.empty()) {
      if (c.checkpointed && !c.options.resume) {
        c.log.warn(
            "the checkpoint of an earlier run in {} is replaced (granvv run --resume "
            "would have continued it)",
            checkpoint_folder(c.dir).string());
      }
      try {
        start_checkpoints(c.dir, c.config.resolved_toml(), c.summary["inputs"]);
      } catch (const std::exception& e) {
        c.log.warn("no checkpoints for this run: {}", e.what());
        checkpoint_folder_ok = false;
        checkpointing.interval_seconds = 0.0;
      }
    }
  }
  c.frames_in_checkpoints = checkpoint_folder_ok && !checkpointing.out_dir.empty() &&
                            c.md_scene->spec.snapshot_interval > 0.0;
  if (checkpoint_folder_ok && !checkpointing.out_dir.empty()) {
    c.summary["checkpoint"] = {{"folder", checkpoint_folder(c.dir).string()},
                               {"resume", "granvv resume " + c.dir.string()}};
  }
  c.summary["md"]["error"] =
      "the process ended inside the particle run (see " +
      fs::path(engine->log_path()).filename().string() +
      " and run.log); results.h5 holds what was finished before it and particles*.h5 the "
      "particle frames written so far" +
      std::string(c.frames_in_checkpoints ? " (in " + checkpoint_folder(c.dir).string() + ")"
                                          : "") +
      std::string(c.summary.contains("checkpoint") ? "; `granvv resume " + c.dir.string() +
                                                         "` continues from the last checkpoint"
                                                   : "");
  const nlohmann::json status_so_far = c.summary["status"];
  c.summary["status"] = "failed";
  write_output(c.ranks, c.work / "summary.json",
               [&] { write_file_atomically(c.work / "summary.json", summary_text(c.summary)); });
  if (c.writer) c.folder->commit_at_exit(true);
  c.summary["status"] = status_so_far;
  c.log.info("md: {} engine, log in {}", engine->name(), engine->log_path());
  const fs::path frames_dir = c.frames_in_checkpoints ? checkpoint_folder(c.dir) : c.work;
  if (c.md_scene->spec.snapshot_interval > 0.0) {  // every rank writes its block there
    c.md_scene->spec.h5md_path =
        writers_value(c.ranks, c.writer ? (frames_dir / "particles.h5").string() : "");
  }
  MdOutcome particles =
      run_particles(*c.md_scene, *engine, c.scene.progress_seconds, checkpointing, c.log);
  if (c.writer) c.folder->commit_at_exit(false);
  return particles;
}

// The transport measurement of a comparison (models/transport_measurement.hpp). A measurement
// that cannot be made (a hydro of the factor grid failed or stopped before the particles' last
// snapshot) leaves the rest of the run as it is: its block says why, with null values.
void measure_transport_part(RunContext& c, const CompareScene& compare_scene, const MdOutcome& md) {
  const CompareScene::Transport& transport = *compare_scene.transport;
  try {
    if (const compare::TransportFluxFit* kind =
            compare::find_transport_flux_fit(transport.coefficient)) {
      const HeatFluxMeasurement m =
          measure_heat_flux(*kind, transport, compare_scene.closures, c.scene, *c.md_scene, md);
      write_output(c.ranks, c.work / "results.h5",
                   [&] { write_heat_flux_results(c.work / "results.h5", m); });
      c.summary["transport"] = heat_flux_summary(m);
      c.log.info(
          "transport: from the particles' heat flux, kappa = {:.4g} +- {:.4g} and mu = {:.4g} +- "
          "{:.4g} of the elastic dilute values, Burnett theta = {:.3g} +- {:.2g} (correlation "
          "{:.3g}, chi2 {:.3g} for {} degrees of freedom)",
          m.fit.conductivity, m.fit.conductivity_error, m.fit.mu, m.fit.mu_error, m.fit.burnett,
          m.fit.burnett_error, m.fit.correlation, m.fit.chi2, m.fit.degrees_of_freedom);
      return;
    }
    if (const compare::TransportPair* pair = compare::find_transport_pair(transport.coefficient)) {
      const TransportPairMeasurement m = measure_transport_pair(
          *pair, transport, compare_scene.closures, c.scene, *c.md_scene, md);
      write_output(c.ranks, c.work / "results.h5",
                   [&] { write_transport_pair_results(c.work / "results.h5", m); });
      c.summary["transport"] = transport_pair_summary(m);
      c.log.info(
          "transport: {} = {:.4g} +- {:.4g} and {} = {:.4g} +- {:.4g} of the elastic dilute "
          "values (correlation {:.3g}, chi2 {:.3g} for {} degrees of freedom)",
          m.first.name, m.first.measured, m.first.error, m.second.name, m.second.measured,
          m.second.error, m.fit.correlation, m.fit.chi2, m.fit.degrees_of_freedom);
      return;
    }
    const TransportMeasurement m =
        measure_transport(transport, compare_scene.closures, c.scene, *c.md_scene, md);
    write_output(c.ranks, c.work / "results.h5",
                 [&] { write_transport_results(c.work / "results.h5", m); });
    c.summary["transport"] = transport_summary(m);
    c.log.info(
        "transport: {} = {:.4g} +- {:.4g} of the elastic dilute value (factor {:.4g} "
        "+- {:.4g} on the {} closure's, chi2 {:.3g} for {} degrees of freedom)",
        m.coefficient, m.measured, m.error, m.fit.factor, m.fit.error, m.closure, m.fit.chi2,
        m.fit.degrees_of_freedom);
  } catch (const std::runtime_error& e) {
    c.log.warn("transport: {} not measured: {}", transport.coefficient, e.what());
    c.summary["transport"] = {{transport.coefficient,
                               {{"measured", nullptr},
                                {"error", nullptr},
                                {"closures", nlohmann::json::object()},
                                {"failure", e.what()}}}};
  }
}

// The parts of a run in order, each part's results written as soon as it has finished: in a
// comparison the particles first (the hydro starts from their coarse-grained t = 0 fields or the
// case's, and is sampled at their snapshot times), the hydro, the particles of a scene without a
// comparison, the comparison. md keeps the particles' outcome when a later part fails.
void run_parts(RunContext& c, const std::optional<CompareScene>& compare_scene,
               const RunMetadata& meta, std::optional<MdOutcome>& md, int& exit_code) {
  write_output(c.ranks, c.work / "case.toml",
               [&] { write_file_atomically(c.work / "case.toml", c.config.resolved_toml()); });
  // In a comparison the particles run first: the hydro starts from their coarse-grained
  // t = 0 fields (or the case's) and is sampled at their snapshot times. Each part's results
  // are written as soon as it has finished.
  write_output(c.ranks, c.work / "results.h5",
               [&] { create_results_file(c.work / "results.h5", meta); });
  auto finish_particles = [&]() {
    write_output(c.ranks, c.work / "results.h5",
                 [&] { write_md_results(c.work / "results.h5", *c.md_scene, *md); });
    c.summary["md"] = md_summary(*c.md_scene, *md);
  };
  if (compare_scene) {
    md = run_particle_part(c);
    finish_particles();
    const hydro::Physics given = c.scene.physics;
    prepare_comparison_hydro(c.scene, *compare_scene, *c.md_scene, md->fields);
    if (compare_scene->hydro_from_md) {
      c.log.info(
          "hydro: starting from the MD's coarse-grained t = 0 fields ({} bins, {} "
          "members)",
          c.md_scene->spec.bins, md->runs.size());
    }
    c.log.info(
        "hydro: K = {:.6g}, q = {:.6g} from the particle scene (case: physics.K = {:.6g}, "
        "physics.q = {:.6g})",
        c.scene.physics.K, c.scene.physics.q, given.K, given.q);
    c.log.info("hydro: t_end = {:.6g} (md.t_end / Lx), {} output times", c.scene.control.t_end,
               c.scene.control.output_times.size());
  }
  std::optional<HydroOutcome> outcome;
  if (c.config.boolean("hydro.enabled")) {
    outcome = run_continuum(c.scene, c.log);
    const auto& run = outcome->run;
    write_output(c.ranks, c.work / "results.h5",
                 [&] { write_hydro_results(c.work / "results.h5", c.scene, *outcome); });
    c.summary["hydro"] = hydro_summary(c.scene, *outcome);
    c.summary["status"] = hydro::to_string(run.status);
    if (run.status == hydro::RunStatus::failed) {
      c.log.error("hydro run failed: {}", run.stop_reason);
      exit_code = 1;
    }
  } else {
    c.log.info("hydro: not run (hydro.enabled = false)");
  }
  if (c.md_scene) {
    if (!md) {
      md = run_particle_part(c);
      finish_particles();
    }
    if (!outcome || c.summary["status"] == "ok") c.summary["status"] = md->runs.back().status;
  }
  if (compare_scene) {
    const CompareOutcome compared =
        compare_engines(*compare_scene, c.scene, *outcome, *c.md_scene, *md);
    write_output(c.ranks, c.work / "results.h5", [&] {
      write_compare_results(c.work / "results.h5", *compare_scene, *c.md_scene, compared);
      write_pressure_comparison(c.work / "results.h5", c.scene, compare_scene->closures,
                                *c.md_scene, *md);
    });
    c.summary["compare"] =
        compare_summary(*compare_scene, c.scene, *outcome, *c.md_scene, *md, compared);
    if (compare_scene->closures.size() > 1) {
      compare_closures(*compare_scene, c.scene, *outcome, compared, *c.md_scene, *md, c.ranks,
                       c.work / "results.h5", c.summary["compare"], c.log);
    }
    if (compare_scene->transport) measure_transport_part(c, *compare_scene, *md);
    c.log.info("compare: {}", compared.verdict);
    c.log.info("compare: cost hydro {:.3g} s wall, md {:.3g} s wall ({:.3g} {})",
               outcome->run.wall_seconds, md->wall_seconds, md->cost.work, md->cost.work_unit);
  }
}

// A particle run that finished is kept even if a later part failed: a failed write removes
// the half-written results.h5 (app/output_folder.hpp), so its /md group is written again.
// Whether the file is gone is known on the writer; every rank takes the same branch, since
// write_output is collective.
void keep_finished_particles(RunContext& c, const RunMetadata& meta, const MdOutcome& md) {
  if (!all_ranks_ok(c.ranks, !(c.writer && !fs::exists(c.work / "results.h5")))) {
    try {
      write_output(c.ranks, c.work / "results.h5", [&] {
        create_results_file(c.work / "results.h5", meta);
        write_md_results(c.work / "results.h5", *c.md_scene, md);
      });
    } catch (const std::exception& e) {
      c.log.error("the finished particle results could not be written: {}", e.what());
    }
  }
  if (!c.summary["md"].contains("particles")) {
    const nlohmann::json error = c.summary["md"].value("error", nlohmann::json());
    c.summary["md"] = md_summary(*c.md_scene, md);
    if (!error.is_null()) c.summary["md"]["error"] = error;
  }
}

// Ensemble members at a time (--jobs): as asked, or the machine's cores shared among its ranks.
int member_jobs(const RunOptions& options, const Ranks& ranks) {
  if (options.jobs > 0) return options.jobs;
  const int cores = std::max(1, int(std::thread::hardware_concurrency()));
  const int here = ranks.size > 1 ? md::MpiEnvironment::ranks_on_this_machine(MPI_COMM_WORLD) : 1;
  return std::max(1, cores / here);
}

// The files the initial state is read from, with their SHA-256, in the summary and the log.
void record_initial_files(const HydroScene& scene, nlohmann::json& summary, spdlog::logger& log) {
  if (hydro::initial_files(scene.initial).empty()) return;
  summary["initial"] = initial_provenance(scene.initial);
  for (const auto& file : summary["initial"]["files"]) {
    log.info("initial state from {} (sha256 {})", file["path"].get<std::string>(),
             file["sha256"].get<std::string>());
  }
}

// A run that failed: its status and reason in the summary (and its particle part's); exit 1.
int record_failure(const std::string& message, nlohmann::json& summary, spdlog::logger& log) {
  log.error("run failed: {}", message);
  summary["status"] = "failed";
  summary["error"] = message;
  if (summary["md"].is_object()) summary["md"]["error"] = message;
  return 1;
}

}  // namespace

int run_command(const RunOptions& options) {
  // 1. Everything that can be wrong with the input is found before anything is written.
  std::optional<CaseConfig> loaded;
  HydroScene scene;
  std::optional<MdScene> md_scene;
  std::optional<CompareScene> compare_scene;
  try {
    const CaseSource source = locate_case(options.case_name);
    loaded = CaseConfig::from_string(source.text, source.origin, options.sets);
    refuse_keys_of_models_not_run(*loaded);
    scene = hydro_scene_from(*loaded);
    md_scene = md_scene_from(*loaded, scene);
    compare_scene = compare_scene_from(*loaded);
  } catch (const ConfigError& e) {
    report_input_error(e);
    return 2;
  }
  const CaseConfig& config = *loaded;
  if (options.dry_run) {
    std::cout << config.resolved_toml();
    if (md_scene) std::cout << "# md work estimate " << md_scene->estimate.describe() << "\n";
    return 0;
  }

  // Under mpirun every rank runs the scene (the particle engine is collective); rank 0 alone
  // writes, into the staging folder of the output protocol (app/output_folder.hpp), and every
  // rank learns whether the folder could be opened.
  const Ranks ranks = join_ranks(md_scene.has_value());
  const bool writer = ranks.writer();
  if (md_scene) md_scene->jobs = member_jobs(options, ranks);
  const fs::path dir =
      options.out_dir.empty() ? fs::path("out") / config.name() : fs::path(options.out_dir);
  std::optional<OutputFolder> folder;
  std::string folder_error;
  std::error_code exists_error;
  const bool dir_existed = fs::exists(dir, exists_error);
  if (writer) {
    try {
      folder.emplace(dir);
    } catch (const std::exception& e) {
      folder_error = e.what();
    }
  }
  if (!all_ranks_ok(ranks, folder_error.empty())) {
    if (writer) std::cerr << "granvv: error: " << folder_error << "\n";
    return 2;
  }
  std::vector<MemberCheckpoint> resume_from;
  const std::optional<std::string> checkpointed = checkpointed_case(dir);
  // What this run reads (its resolved case and the SHA-256 of its files): recorded in the
  // summary and the checkpoints, so that a result is reused or continued only for these inputs.
  const nlohmann::json inputs = input_fingerprint(config);
  const std::string resume_problem = first_ranks_problem(
      ranks, options.resume && checkpointed && md_scene
                 ? app::resume_problem(inputs, dir, *md_scene, ranks, resume_from)
                 : std::string());
  if (!resume_problem.empty()) {
    if (writer) std::cerr << "granvv: error: " << resume_problem << "\n";
    return 2;
  }
  // One rank can stop at its own safe point; several must not (the others would wait in a
  // collective step), so under mpirun -np > 1 a signal keeps its default action.
  if (ranks.size == 1) catch_interruptions();
  const fs::path work = writer ? folder->staging() : fs::path();
  std::shared_ptr<spdlog::logger> log;
  try {
    log = writer ? make_logger(work / "run.log", options.quiet)
                 : std::make_shared<spdlog::logger>(
                       "granvv", std::make_shared<spdlog::sinks::null_sink_mt>());
  } catch (const std::exception& e) {
    std::cerr << "granvv: error: cannot write " << (work / "run.log") << ": " << e.what() << "\n";
    return 1;
  }
  log->info("granvv {} running case '{}' into {}", GRANVV_VERSION, config.name(), dir.string());
  if (writer) {
    for (const auto& note : folder->notes()) log->warn("{}", note);
  }
  log->info("resolved configuration:\n{}", config.resolved_toml());

  nlohmann::json summary = {
      {"case", config.name()},      {"status", "failed"}, {"granvv_version", GRANVV_VERSION},
      {"output_dir", dir.string()}, {"hydro", nullptr},   {"md", nullptr},
      {"compare", nullptr}};
  if (writer) summary["run_id"] = folder->run_id();
  summary["inputs"] = inputs;
  record_initial_files(scene, summary, *log);
  RunContext context{options,     config,  scene,
                     md_scene,    ranks,   writer,
                     dir,         work,    writer ? &*folder : nullptr,
                     *log,        summary, std::move(resume_from),
                     checkpointed};
  int exit_code = 0;
  bool interrupted = false;
  std::optional<MdOutcome> md;  // kept when a later part fails
  const RunMetadata meta{config.name(), GRANVV_VERSION, config.resolved_toml(), config.flattened()};
  try {
    run_parts(context, compare_scene, meta, md, exit_code);
  } catch (const Interrupted& e) {
    log->warn("run stopped: {}", e.what());
    summary["status"] = "interrupted";
    summary["error"] = e.what();
    if (summary["md"].is_object()) summary["md"]["error"] = e.what();
    interrupted = true;
  } catch (const hydro::InitialFieldError& e) {
    // A field that is not finite at a point only the run evaluates (a disk's random position):
    // bad input, refused as the checks before the run refuse it. Nothing of this run is kept,
    // its checkpoints neither: a resume would meet the same value.
    const ConfigError refusal = initial_field_refusal(config, e);
    if (!writer) return 2;
    folder->commit_at_exit(false);
    folder->abandon();
    if (summary.contains("checkpoint")) remove_checkpoints(dir);
    folder.reset();  // releases the lock
    std::error_code ignored;
    if (!dir_existed) fs::remove_all(dir, ignored);  // as a refusal before the run leaves it
    report_input_error(refusal);
    return 2;
  } catch (const H5::Exception& e) {
    mark_hdf5_broken();
    exit_code = record_failure(e.getFuncName() + ": " + e.getDetailMsg(), summary, *log);
  } catch (const std::exception& e) {
    exit_code = record_failure(e.what(), summary, *log);
  }
  if (md && !interrupted) keep_finished_particles(context, meta, *md);
  if (!writer) return interrupted ? interrupted_exit_code() : exit_code;
  folder->commit_at_exit(false);
  const bool frames_linked =
      !context.frames_in_checkpoints || link_particle_files(checkpoint_folder(dir), work, *log);
  const bool checkpointed_run = summary.contains("checkpoint");
  if (checkpointed_run && (interrupted || exit_code != 0)) {
    log->info("the checkpoint is kept in {}; `granvv resume {}` continues the run",
              checkpoint_folder(dir).string(), dir.string());
  } else {
    summary.erase("checkpoint");  // removed once the outputs are in place
  }
  const int finished =
      finish_outputs(*folder, summary, *log, interrupted, options.report, exit_code);
  // A complete result no longer needs its checkpoints.
  if (checkpointed_run && finished == 0 && !interrupted && frames_linked) remove_checkpoints(dir);
  return finished;
}

}  // namespace granvv::app
