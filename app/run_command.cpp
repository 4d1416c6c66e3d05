#include "app/run_command.hpp"

#include <mpi.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/null_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>

#include "app/atomic_file.hpp"
#include "app/case_catalog.hpp"
#include "app/case_config.hpp"
#include "app/compare_output.hpp"
#include "app/compare_scene.hpp"
#include "app/hydro_scene.hpp"
#include "app/md_output.hpp"
#include "app/md_scene.hpp"
#include "app/report_command.hpp"
#include "app/results_file.hpp"
#include "app/summary.hpp"
#include "md_bridge/mpi_environment.hpp"

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
                        spdlog::logger& log) {
  const auto& sc = scene.spec.scene;
  log.info(
      "md: {} disks, Lx = {:.6g}, Ly = {:.6g} sigma, phi = {:.4g}, r = {:.6g} (K = {:.4g}, "
      "q = {:.4g}, {} unstable modes), ensemble of {}",
      sc.particles, sc.box_length, sc.box_width, sc.area_fraction, sc.restitution, sc.physics().K,
      sc.physics().q, sc.unstable_modes(), scene.ensemble);
  auto last = std::chrono::steady_clock::now();
  const MdOutcome out = run_md_scene(scene, engine, [&](int member, const md::MdProgress& p) {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last).count() < progress_seconds) return;
    last = now;
    const double f = std::clamp(p.t / p.t_end, 1e-9, 1.0);
    log.info("md member {}/{} t={:<9.5g} T={:<10.5g} steps {} {:.3g} atom-steps/s ETA {:.1f} s",
             member + 1, scene.ensemble, p.t, p.T, p.steps,
             p.steps * double(sc.particles) / std::max(p.wall_seconds, 1e-12),
             p.wall_seconds * (1 - f) / f + p.wall_seconds * (scene.ensemble - member - 1) / f);
  });
  log.info("md: restitution {:.6f} (target {:.6f}), {}", out.collision_rule.restitution,
           sc.restitution, out.collision_rule.description);
  log.info(
      "md: {:.3g} s wall, {:.3g} {}/s, Haff t0 = {:.5g} +- {:.2g} (kinetic theory "
      "{:.5g} with chi(phi), {:.5g} dilute)",
      out.wall_seconds, out.cost.per_second(), out.cost.work_unit, out.haff.t0, out.haff.t0_error,
      out.haff_t0_theory, out.haff_t0_theory_dilute);
  return out;
}

// The continuum engine with a progress line every progress_seconds and its throughput.
HydroOutcome run_continuum(const HydroScene& scene, spdlog::logger& log) {
  auto last = std::chrono::steady_clock::now();  // first line after progress_seconds
  auto progress = [&](const hydro::Progress& p) {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last).count() < scene.progress_seconds) return;
    last = now;
    const double f = progress_fraction(p);
    log.info("step {:>7} t={:<10.6g} dt={:<10.3e} ({}) n_max={:<10.4g} E={:<10.5g} ETA {:.1f} s",
             p.step, p.t, p.dt, p.limited_by, p.n_max, p.energy, p.wall_seconds * (1 - f) / f);
  };
  HydroOutcome outcome = run_hydro_scene(scene, progress);
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
    return 0;
  }

  // Under mpirun every rank runs the scene (the particle engine is collective); rank 0 alone
  // writes the outputs and the log.
  int rank = 0;
  if (md_scene) {
    md::MpiEnvironment::ensure();
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  }
  const bool writer = rank == 0;
  const fs::path dir =
      options.out_dir.empty() ? fs::path("out") / config.name() : fs::path(options.out_dir);
  std::error_code ec;
  if (writer) fs::create_directories(dir, ec);
  if (ec) {
    std::cerr << "granvv: error: cannot create output folder " << dir << ": " << ec.message()
              << "\n";
    return 1;
  }
  auto log = writer ? make_logger(dir / "run.log", options.quiet)
                    : std::make_shared<spdlog::logger>(
                          "granvv", std::make_shared<spdlog::sinks::null_sink_mt>());
  log->info("granvv {} running case '{}' into {}", GRANVV_VERSION, config.name(), dir.string());
  log->info("resolved configuration:\n{}", config.resolved_toml());
  if (writer) write_file_atomically(dir / "case.toml", config.resolved_toml());

  nlohmann::json summary = {
      {"case", config.name()},      {"status", "failed"}, {"granvv_version", GRANVV_VERSION},
      {"output_dir", dir.string()}, {"hydro", nullptr},   {"md", nullptr},
      {"compare", nullptr}};
  int exit_code = 0;
  try {
    const RunMetadata meta{config.name(), GRANVV_VERSION, config.resolved_toml(),
                           config.flattened()};
    // The particle engine; the summary on disk says "failed" until it returns, because the
    // Debian LAMMPS ends the process on any error inside a command (docs/physics.md §10).
    auto run_particle_engine = [&]() {
      summary["md"] = {{"status", "failed"}};
      md_scene->spec.creator_version = GRANVV_VERSION;
      const auto engine = make_engine(*md_scene, writer ? dir.string() : "");
      summary["md"]["error"] =
          "the process ended inside the particle run (see " +
          fs::path(engine->log_path()).filename().string() +
          " and run.log); results.h5 holds what was finished before it and particles*.h5 the "
          "particle frames written so far";
      const nlohmann::json status_so_far = summary["status"];
      summary["status"] = "failed";
      if (writer) write_file_atomically(dir / "summary.json", summary_text(summary));
      summary["status"] = status_so_far;
      log->info("md: {} engine, log in {}", engine->name(), engine->log_path());
      if (md_scene->spec.snapshot_interval > 0.0) {
        md_scene->spec.h5md_path = (dir / "particles.h5").string();
      }
      return run_particles(*md_scene, *engine, scene.progress_seconds, *log);
    };

    // In a comparison the particles run first: the hydro starts from their coarse-grained
    // t = 0 fields (or the case's) and is sampled at their snapshot times.
    std::optional<MdOutcome> md;
    if (compare_scene) {
      md = run_particle_engine();
      const auto& sc = md_scene->spec.scene;
      if (compare_scene->hydro_from_md) {
        scene.given_fields = fields_from_snapshot(md->snapshots.front(), sc);
        log->info(
            "hydro: starting from the MD's coarse-grained t = 0 fields ({} bins, {} "
            "members)",
            md_scene->spec.bins, md->runs.size());
      }
      const hydro::Physics given = scene.physics;
      align_hydro_with_md(scene, sc, md_scene->spec.t_end, md->snapshots);
      log->info(
          "hydro: K = {:.6g}, q = {:.6g} from the particle scene (case: physics.K = {:.6g}, "
          "physics.q = {:.6g})",
          scene.physics.K, scene.physics.q, given.K, given.q);
      log->info("hydro: t_end = {:.6g} (md.t_end / Lx), {} output times", scene.control.t_end,
                scene.control.output_times.size());
    }
    const HydroOutcome outcome = run_continuum(scene, *log);
    const auto& run = outcome.run;
    if (writer) write_results_file(dir / "results.h5", meta, scene, outcome);
    summary["hydro"] = hydro_summary(scene, outcome);
    summary["status"] = hydro::to_string(run.status);
    if (run.status == hydro::RunStatus::failed) {
      log->error("hydro run failed: {}", run.stop_reason);
      exit_code = 1;
    }
    if (md_scene) {
      if (!md) md = run_particle_engine();
      if (writer) write_md_results(dir / "results.h5", *md_scene, *md);
      summary["md"] = md_summary(*md_scene, *md);
      if (summary["status"] == "ok") summary["status"] = md->runs.back().status;
    }
    if (compare_scene) {
      const CompareOutcome compared =
          compare_engines(*compare_scene, scene, outcome, *md_scene, *md);
      if (writer) write_compare_results(dir / "results.h5", *compare_scene, *md_scene, compared);
      summary["compare"] =
          compare_summary(*compare_scene, scene, outcome, *md_scene, *md, compared);
      log->info("compare: {}", compared.verdict);
      log->info("compare: cost hydro {:.3g} s wall, md {:.3g} s wall ({:.3g} {})", run.wall_seconds,
                md->wall_seconds, md->cost.work, md->cost.work_unit);
    }
  } catch (const std::exception& e) {
    log->error("run failed: {}", e.what());
    summary["status"] = "failed";
    summary["error"] = e.what();
    if (summary["md"].is_object()) summary["md"]["error"] = e.what();
    exit_code = 1;
  }
  if (!writer) return exit_code;
  write_file_atomically(dir / "summary.json", summary_text(summary));
  log->info("wrote {}", (dir / "summary.json").string());

  if (options.report && fs::exists(dir / "results.h5")) {
    const int status = build_report(dir);
    if (status != 0) {
      log->error("report script failed (exit {}); results.h5 and summary.json are complete",
                 status);
      exit_code = exit_code ? exit_code : 1;
    } else {
      log->info("report: {}", (dir / "report.html").string());
    }
  }
  return exit_code;
}

}  // namespace granvv::app
