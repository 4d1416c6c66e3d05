#include "scene/md_scene.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include "compare/ensemble_fields.hpp"
#include "compare/particle_ensemble.hpp"
#include "compare/signal_to_noise.hpp"
#include "fields/constants.hpp"
#include "fields/field_series.hpp"
#include "hydro/flow_by_inertia.hpp"
#include "md_bridge/box_modes.hpp"
#include "md_bridge/particle_engine_registry.hpp"
#include "md_bridge/particle_sampler.hpp"
#include "scene/md_members.hpp"
#include "scene/work_estimate.hpp"

namespace granvv::app {

namespace {

// The key behind a scene_problem (md_bridge/particle_scene.hpp), checked in its order: the
// particle count comes from md.particles or, when that is 0, from physics.K; r from
// md.restitution or, when that is 0, from physics.q.
std::string scene_problem_key(const CaseConfig& c, const md::ParticleScene& sc) {
  if (!(sc.area_fraction > 0.0 && sc.area_fraction <= 0.5)) return "md.area_fraction";
  if (!(sc.box_width >= 4.0)) return "md.box_width";
  if (!(sc.restitution > 0.0 && sc.restitution <= 1.0)) {
    return c.real("md.restitution") > 0.0 ? "md.restitution" : "physics.q";
  }
  return c.integer("md.particles") > 0
             ? "md.particles"
             : key_to_blame(c, {"physics.K", "md.box_width", "md.area_fraction"});
}

[[noreturn]] void refuse(const CaseConfig& c, const std::string& key, const std::string& why) {
  const std::string origin = c.origin(key);
  throw ConfigError((origin == "default" ? c.source() : origin) + ": " + key + " = " +
                    abbreviated(format_value(c.value(key)), 80) + ": " + why);
}

// Samples of the initial density profile for the work estimate: enough points to resolve the
// profiles of the shipped scenes (a few modes across the box).
constexpr int kWorkProfileSamples = 256;

std::vector<double> profile_samples(const std::function<double(double)>& n) {
  std::vector<double> samples;
  if (!n) return samples;
  for (int i = 0; i < kWorkProfileSamples; ++i) {
    samples.push_back(n(-0.5 + (i + 0.5) / kWorkProfileSamples));
  }
  return samples;
}

// The flow by inertia's collapse time of the initial velocity profile (scaled; +inf without a
// smooth profile or where it nowhere converges).
double profile_collapse_time(const hydro::InitialFields& f) {
  if (!f.v || !f.dv || !f.n) return std::numeric_limits<double>::infinity();
  try {
    return hydro::FlowByInertia(f.v, f.dv, f.n).singularity_time();
  } catch (const std::invalid_argument&) {
    return std::numeric_limits<double>::infinity();
  }
}

// Work and output of the particle run. The work is the engine's own estimate, in its own unit
// (md_bridge/particle_work.hpp: LAMMPS atom-steps from the contact, event-driven collisions from
// Enskog's collision frequency); a sample interval below the engine's time step (LAMMPS only)
// is refused.
void check_particle_work(const CaseConfig& c, MdScene& s, double t_haff) {
  const auto& spec = s.spec;
  const auto& sc = spec.scene;
  const double n = double(sc.particles);
  md::ParticleWorkQuestion question;
  question.scene = sc;
  question.settings = s.engine_settings;
  question.hottest_temperature = std::max(1.0, compare::profile_maximum(spec.fields.T));
  question.fastest_flow =
      std::max(0.0, compare::profile_maximum([&](double x) {
                 return std::abs(spec.fields.v(x));  // x and t both scale with Lx: v is the same
               }));
  question.t_end = spec.t_end;
  question.haff_time = t_haff;
  question.ensemble = s.ensemble;
  question.initial_density = profile_samples(spec.fields.n);
  question.profile_collapse_time = sc.md_time(profile_collapse_time(spec.fields));
  md::ParticleWorkEstimate work;
  try {
    work = md::estimate_particle_work(s.engine, question);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(c.origin("md.engine") + ": md.engine = \"" + s.engine + "\": " + e.what());
  }
  const double dt0 = work.first_step;
  // The work and memory of one rank: its group's members (scene/md_members.hpp: m = group
  // mod G), the engine's work divided over the group's ranks where it divides (LAMMPS).
  ParticleRunEstimate& e = s.estimate;
  e.ranks = launched_ranks();
  MemberGroups groups;
  groups.size = e.ranks;
  try {
    const auto engine = make_engine(s, "");
    const int per_member = engine->ranks_per_member();
    if (per_member > 0 && e.ranks % per_member != 0) {
      refuse(c, std::string("md.") + md::kRanksPerMemberKey,
             "must divide the " + std::to_string(e.ranks) + " MPI rank" +
                 (e.ranks == 1 ? "" : "s") +
                 " of this run (mpirun -np); 0 runs each member on every rank");
    }
    groups = member_groups(*engine, e.ranks);
  } catch (const std::invalid_argument&) {  // refused below, with its key
  }
  const double share = work.divides_over_ranks ? 1.0 / groups.size : 1.0;
  const double members_here = std::ceil(double(s.ensemble) / groups.groups);
  e.work_per_rank = work.work * share * members_here / std::max(1, s.ensemble);
  e.unit = work.unit;
  e.rate = work.rate;
  e.member_work_until = work.member_work_until;
  e.member_groups = groups.groups;
  e.bytes_per_rank = work.bytes_fixed + work.bytes_per_disk * n * share +
                     (spec.snapshot_interval > 0.0 ? md::kFrameBytesPerDisk * n * share : 0.0);
  e.machine_bytes = machine_memory_bytes();
  const std::vector<std::string> size_keys = {"md.particles", "physics.K", "md.box_width",
                                              "md.area_fraction"};
  if (e.machine_bytes > 0.0 && e.bytes_per_rank > e.machine_bytes) {
    const std::string key = key_to_blame(c, size_keys);
    refuse(c, key,
           "the particle run (" + std::to_string(sc.particles) +
               " particles) needs more memory "
               "than this machine has: " +
               e.describe() + "; run on more ranks or a smaller scene");
  }
  if (!c.boolean("md.accept_long_run")) {
    refuse_beyond(c, work.keys, e.work_per_rank, work.limit, work.unit,
                  "the particle run (" + std::to_string(s.ensemble) + " x " +
                      std::to_string(sc.particles) + " disks" +
                      (dt0 > 0.0 ? ", first step ~" + format_real(dt0) : std::string()) + ", " +
                      e.describe() + ")",
                  "set md.accept_long_run = true to run it anyway");
  }
  // A sample interval below the step skips requested times: the run passes a snapshot time
  // within one step without stopping at it (the last one is lost). The step at the end of the
  // run, where adaptive stiffness has made it longest, is the one that counts.
  const double dt_end = work.last_step;
  if (dt0 > 0.0 && spec.sample_interval < dt_end) {
    refuse(c, "md.sample_interval",
           "below the particle time step (about " + format_real(dt0) + " at the start, " +
               format_real(dt_end) +
               " at md.t_end, MD time); the run cannot sample more often than every step");
  }
  const double segments =
      s.ensemble * (spec.t_end / spec.sample_interval +
                    (spec.snapshot_interval > 0 ? spec.t_end / spec.snapshot_interval : 0.0) +
                    double(spec.output_times.size()));
  refuse_beyond(c, {"md.sample_interval", "md.snapshot_interval", "md.t_end", "md.ensemble"},
                segments, kMaxSegments, "segments",
                "the particle run in segments (one per sample, frame or snapshot, each with its "
                "engine log)");
  const double frame_bytes =
      spec.snapshot_interval > 0
          ? s.ensemble * (spec.t_end / spec.snapshot_interval + 1.0) * n * 6.0 * sizeof(double)
          : 0.0;
  const double series_bytes = s.ensemble * (spec.t_end / spec.sample_interval + 1.0) * 16.0 *
                              sizeof(double) * (spec.snapshot_interval > 0 ? 6.0 : 1.0);
  refuse_beyond(c, {"md.snapshot_interval", "md.sample_interval", "md.t_end", "md.ensemble"},
                frame_bytes + series_bytes, kMaxOutputBytes, "bytes",
                "the particle output (H5MD frames and time series)");
}

// The members one after another on the one engine (which keeps its state from one to the next).
void run_members_in_turn(const MdScene& scene, md::ParticleEngine& engine,
                         const std::function<void(int, const md::MdProgress&)>& progress,
                         const MdCheckpointing* checkpointing, MdOutcome& out,
                         double& wall_before) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const bool saving = checkpointing && !checkpointing->out_dir.empty();
  const std::vector<MemberCheckpoint> none;
  const auto& resume = checkpointing ? checkpointing->resume : none;
  auto last_save = clock::now();
  auto since = [](clock::time_point t) {
    return std::chrono::duration<double>(clock::now() - t).count();
  };
  auto save = [&](int member, MemberCheckpoint c) {
    c.particle_part_wall_seconds = wall_before + since(start);
    try {
      save_member_checkpoint(checkpointing->out_dir, member, c, engine.comm());
      ++out.checkpoints_written;
    } catch (const std::exception& e) {
      if (checkpointing->warn) checkpointing->warn(e.what());
    }
    last_save = clock::now();
  };
  for (int m = 0; m < scene.ensemble; ++m) {
    const MemberCheckpoint* earlier =
        m < static_cast<int>(resume.size()) && !resume[std::size_t(m)].missing
            ? &resume[std::size_t(m)]
            : nullptr;
    if (earlier) wall_before = earlier->particle_part_wall_seconds;
    if (earlier && earlier->finished) {  // its result as it was, and the engine's totals after it
      engine.restore_state(earlier->state.engine);
      out.runs.push_back(earlier->state.so_far);
      ++out.members_restored;
    } else {
      md::MdRunSpec spec = scene.spec;
      spec.seed += static_cast<std::uint64_t>(m);
      spec.h5md_path = member_h5md_path(scene, m);
      md::MdCheckpoints checkpoints;
      if (saving) {
        checkpoints.due = [&] {
          return (checkpointing->interval_seconds > 0.0 &&
                  since(last_save) >= checkpointing->interval_seconds) ||
                 (checkpointing->stop_requested && checkpointing->stop_requested());
        };
        checkpoints.save = [&](const md::MdRunState& state) { save(m, {false, state, 0.0}); };
      }
      if (earlier) {
        checkpoints.resume_from = &earlier->state;
        out.resumed_member = m;
        out.resumed_t = md::resumed_time(earlier->state);
      }
      out.runs.push_back(md::run_md(
          spec, engine,
          [&](const md::MdProgress& p) {
            if (progress) progress(m, p);
          },
          checkpoints));
      if (saving) {  // the finished member, and the engine's totals after it
        md::MdRunState done;
        done.engine = engine.save_state(false);
        done.so_far = out.runs.back();
        int rank = 0;
        MPI_Comm_rank(engine.comm(), &rank);
        if (rank == 0) save(m, {true, done, 0.0});
      }
    }
  }
}

// The scene of given particles: their N and box, the case's restitution.
md::ParticleScene given_scene(const md::GivenParticles& given, double restitution) {
  md::ParticleScene sc;
  sc.particles = given.particles;
  sc.box_length = given.box_length;
  sc.box_width = given.box_width;
  sc.area_fraction = double(given.particles) * kPi / (4.0 * given.box_length * given.box_width);
  sc.restitution = restitution;
  return sc;
}

// The times of given particles (docs/recorded.md): a run stops only at their frames, so every
// md.output_times must be a frame time (it becomes that frame's time exactly); md.t_end, left
// at its default, is the last frame's and may not lie beyond it; md.sample_interval, left at
// its default, samples every frame; the ensemble is the members of the files.
void take_given_times(const CaseConfig& c, MdScene& s) {
  auto& spec = s.spec;
  const md::GivenParticles& given = *s.given;
  const std::vector<double>& frames = given.times;
  if (frames.size() < 2) {
    refuse(c, "md.engine",
           "the recorded files hold " + std::to_string(frames.size()) +
               " frame; a run needs at least two (" + given.members.front().front() + ")");
  }
  double spacing = 0.0;
  for (std::size_t i = 1; i < frames.size(); ++i)
    spacing = std::max(spacing, frames[i] - frames[i - 1]);
  if (c.origin("md.t_end") == "default") {
    spec.t_end = frames.back();
  } else if (spec.t_end > frames.back() && !fields::same_time(spec.t_end, frames.back())) {
    refuse(c, "md.t_end", "beyond the last recorded frame, at t = " + format_real(frames.back()));
  }
  if (c.origin("md.sample_interval") == "default") spec.sample_interval = spacing;
  for (double& t : spec.output_times) {
    const auto nearest = std::min_element(frames.begin(), frames.end(), [t](double a, double b) {
      return std::abs(a - t) < std::abs(b - t);
    });
    if (!fields::same_time(*nearest, t)) {
      refuse(c, "md.output_times",
             "t = " + format_real(t) + " is not a recorded frame time (the nearest is " +
                 format_real(*nearest) +
                 "); the snapshots of recorded particles are at their frames' own times");
    }
    t = *nearest;
  }
  const int members = int(given.members.size());
  if (c.origin("md.ensemble") != "default" && s.ensemble != members) {
    refuse(c, "md.ensemble",
           "the recorded files hold " + std::to_string(members) +
               " members (one per entry of md.recorded.files)");
  }
  s.ensemble = members;
}

}  // namespace

SignalToNoise initial_signal_to_noise(const MdScene& scene) {
  const auto& sc = scene.spec.scene;
  const auto flow = compare::largest_flow_component(scene.spec.fields.v, scene.spec.fields.vy);
  return compare::velocity_signal_to_noise(flow, sc.number_density(), sc.box_width, sc.box_length,
                                           scene.spec.bins);
}

SignalToNoise initial_gradient_signal_to_noise(const MdScene& scene) {
  const auto& sc = scene.spec.scene;
  return compare::gradient_signal_to_noise(scene.spec.fields.dv, sc.unstable_modes(), sc.particles);
}

SignalToNoise initial_mode_signal_to_noise(const MdScene& scene) {
  return compare::mode_signal_to_noise(scene.spec.fields.v, scene.spec.scene.particles);
}

void read_engine_keys(const CaseConfig& c, const std::string& engine, md::EngineSettings& settings,
                      md::EngineTexts& texts) {
  for (const KeySpec& key : case_schema()) {
    const auto owner = key_owner(key.key);
    const std::string section = key.section();
    if ((section != "md" && section.rfind("md.", 0) != 0) || (owner && owner->model != engine))
      continue;
    if (key.type == ValueType::real) settings[key.key] = c.real(key.key);
    if (key.type == ValueType::integer) settings[key.key] = double(c.integer(key.key));
    if (key.type == ValueType::boolean) settings[key.key] = c.boolean(key.key) ? 1 : 0;
    if (owner && key.type == ValueType::string) texts[key.key] = {c.string(key.key)};
    if (owner && key.type == ValueType::string_array) texts[key.key] = c.strings(key.key);
  }
}

std::optional<MdScene> md_scene_from(const CaseConfig& c, const HydroScene& hydro) {
  if (!c.boolean("md.enabled")) return std::nullopt;
  MdScene s;
  auto& spec = s.spec;
  s.engine = c.string("md.engine");
  read_engine_keys(c, s.engine, s.engine_settings, s.engine_texts);
  const double r_key = c.real("md.restitution");
  const double r = r_key > 0.0 ? r_key : 1.0 - 2.0 * hydro.physics.q;
  try {
    s.given = md::given_particles(s.engine, s.engine_settings, s.engine_texts);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(c.origin("md.engine") + ": md.engine = \"" + s.engine + "\": " + e.what());
  }
  if (s.given) {
    spec.scene = given_scene(*s.given, r);
  } else {
    const double phi = c.real("md.area_fraction"), ly = c.real("md.box_width");
    const long long n = c.int_value("md.particles");
    spec.scene = n > 0 ? md::scene_from_particles(n, phi, ly, r)
                       : md::scene_from_scaled(hydro.physics.K, 0.5 * (1.0 - r), phi, ly);
  }
  const std::string problem = md::scene_problem(spec.scene);
  if (!problem.empty()) {
    refuse(c, s.given ? "md.engine" : scene_problem_key(c, spec.scene),
           "impossible particle scene: " + problem);
  }
  try {
    spec.fields = hydro::make_initial_fields(hydro.initial, hydro.physics);
  } catch (const hydro::InitialFieldError& e) {
    throw initial_field_refusal(c, e);
  }
  spec.seed = static_cast<std::uint64_t>(c.int_value("md.seed"));
  spec.t_end = c.real("md.t_end");
  spec.sample_interval = c.real("md.sample_interval");
  spec.output_times = c.reals("md.output_times");
  spec.bins = c.int_value("md.bins");
  spec.kernel = c.string("md.kernel");
  spec.kernel_width = c.real("md.kernel_width");
  s.ensemble = c.int_value("md.ensemble");
  s.checkpoint_interval = c.real("md.checkpoint_interval");
  s.haff_mode_energy_fraction = c.real("md.haff_mode_energy_fraction");
  spec.snapshot_interval = c.real("md.snapshot_interval");
  const double t_haff = md::haff_time_md(spec.scene, md::enskog_chi(spec.scene.area_fraction));
  if (c.string("md.time_unit") == "haff") {  // times given in kinetic-theory Haff times
    const double t0 = t_haff;
    if (!(std::isfinite(t0) && t0 > 0.0)) {
      refuse(c, c.real("md.restitution") > 0.0 ? "md.restitution" : "physics.q",
             "the gas does not cool (r = " + format_real(spec.scene.restitution) +
                 "), so its Haff time is infinite and md.time_unit = \"haff\" " + "(from " +
                 c.origin("md.time_unit") + ") gives no end time; use r < 1 or " +
                 "md.time_unit = \"md\"");
    }
    spec.t_end *= t0;
    spec.sample_interval *= t0;
    for (double& t : spec.output_times) t *= t0;
  }
  if (s.given) take_given_times(c, s);
  if (spec.sample_interval > spec.t_end) {
    throw ConfigError(c.origin("md.sample_interval") +
                      ": md.sample_interval = " + format_real(spec.sample_interval) +
                      ": must be <= md.t_end = " + format_real(spec.t_end));
  }
  // What the coarse-grainer and the sampler would refuse, refused here with the key named.
  try {
    md::CoarseGrainer check({-0.5 * spec.scene.box_length, spec.scene.box_length, 0.0,
                             spec.scene.box_width, spec.bins, spec.kernel, spec.kernel_width});
    (void)check;
  } catch (const std::invalid_argument& e) {
    throw ConfigError(c.origin("md.kernel_width") +
                      ": md.kernel_width = " + format_real(spec.kernel_width) + ": " + e.what());
  }
  // The densest point of the initial profile must still take disks without overlap.
  const double n_max = std::max(0.0, compare::profile_maximum(spec.fields.n));
  if (n_max * spec.scene.area_fraction > 0.5) {
    throw ConfigError(c.origin("md.area_fraction") +
                      ": md.area_fraction = " + format_real(spec.scene.area_fraction) +
                      ": the initial density peak n/n0 = " + format_real(n_max) +
                      " would need a local area fraction above 0.5");
  }
  check_particle_work(c, s, t_haff);
  if (c.boolean("compare.enabled")) {  // the hydro then runs to md.t_end in scaled units
    check_hydro_work(c, hydro, spec.t_end / spec.scene.box_length, "md.t_end");
  }
  try {
    (void)make_engine(s, "");
  } catch (const std::invalid_argument& e) {
    throw ConfigError(c.origin("md.engine") + ": md.engine = \"" + s.engine + "\": " + e.what());
  }
  if (!s.given) {  // the fields where the sampler tabulates them
    try {
      md::check_sampled_profile(spec.scene, spec.fields);
    } catch (const hydro::InitialFieldError& e) {
      throw initial_field_refusal(c, e);
    } catch (const std::invalid_argument& e) {  // the sampler's profile cannot be packed
      throw ConfigError(c.origin("md.area_fraction") + ": md.area_fraction = " +
                        format_real(spec.scene.area_fraction) + ": " + e.what());
    }
  }
  return s;
}

std::unique_ptr<md::ParticleEngine> make_engine(const MdScene& scene, const std::string& log_dir,
                                                MPI_Comm comm) {
  md::ParticleEngineSetup setup;
  setup.scene = scene.spec.scene;
  setup.settings = scene.engine_settings;
  setup.texts = scene.engine_texts;
  setup.log_dir = log_dir;
  setup.comm = comm;
  return md::make_particle_engine(scene.engine, setup);
}

std::string member_h5md_path(const MdScene& scene, int member) {
  const std::string& path = scene.spec.h5md_path;
  if (path.empty() || scene.ensemble <= 1) return path;
  const std::filesystem::path p = path;  // particles.h5 -> particles_m1.h5
  return (p.parent_path() /
          (p.stem().string() + "_m" + std::to_string(member) + p.extension().string()))
      .string();
}

MdOutcome run_md_scene(const MdScene& scene, md::ParticleEngine& engine,
                       const std::function<void(int, const md::MdProgress&)>& progress,
                       const MdCheckpointing* checkpointing) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  MdOutcome out;
  const auto& sc = scene.spec.scene;
  out.engine = engine.name();
  out.collision_rule = engine.check_collision_rule();
  if (md::misses_restitution(out.collision_rule, sc.restitution)) {
    std::ostringstream why;
    why << "restitution " << out.collision_rule.restitution << " ("
        << out.collision_rule.description << ") misses md.restitution = " << sc.restitution
        << " by more than " << md::kRestitutionTolerance << "; refusing the run";
    throw std::runtime_error(why.str());
  }
  double wall_before = 0.0;  // the particle part of the runs this one continues
  auto since = [](clock::time_point t) {
    return std::chrono::duration<double>(clock::now() - t).count();
  };
  md::MpiEnvironment::ensure();
  int ranks = 1;
  MPI_Comm_size(engine.comm(), &ranks);
  const MemberGroups groups = member_groups(engine, ranks);
  out.member_groups = groups.groups;
  out.ranks_per_group = groups.size;
  if (groups.apart) {
    if (checkpointing) {
      for (const MemberCheckpoint& c : checkpointing->resume)
        if (!c.missing) wall_before = std::max(wall_before, c.particle_part_wall_seconds);
    }
    // The members' engines log where this one would (its log file's folder).
    const std::string log = engine.log_path();
    const std::string log_dir =
        log == "none" ? std::string() : std::filesystem::path(log).parent_path().string();
    MembersApart apart = run_members_apart(
        scene, engine.comm(), groups, engine.independent_members() ? scene.jobs : 1, log_dir,
        progress, checkpointing, [&] { return wall_before + since(start); });
    // The ensemble's totals, member by member, as one engine running them in turn has them.
    for (std::size_t m = 0; m < apart.records.size(); ++m) {
      if (m == 0) {
        engine.restore_state(apart.records[m].totals);
      } else {
        engine.add_totals(apart.records[m].totals);
      }
      out.runs.push_back(std::move(apart.records[m].run));
    }
    out.threads = apart.threads;
    out.cores = apart.cores;
    out.checkpoints_written = apart.checkpoints_written;
    out.resumed_member = apart.resumed_member;
    out.resumed_t = apart.resumed_t;
    out.members_restored = apart.members_restored;
  } else {
    run_members_in_turn(scene, engine, progress, checkpointing, out, wall_before);
  }
  std::vector<compare::MemberSamples> samples;
  for (const md::MdRunResult& run : out.runs) {
    const md::MdSeries& series = run.series;
    samples.push_back({series.t, series.T, series.mode_energy_fraction, series.pressure_xx,
                       series.pressure_yy, series.pressure_stderr, series.compressibility});
  }
  const compare::ParticleEnsemble ensemble =
      compare::reduce_particle_ensemble(samples, scene.haff_mode_energy_fraction, scene.spec.t_end);
  out.pressure = ensemble.pressure;
  out.compressibility = ensemble.compressibility;
  out.mode_energy_fraction = ensemble.mode_energy_fraction;
  out.homogeneous = ensemble.homogeneous;
  out.linear_mode_onset = md::linear_mode_onset_md(sc, scene.haff_mode_energy_fraction);
  out.haff = ensemble.haff;
  out.haff_t0_theory = md::haff_time_md(sc, md::enskog_chi(sc.area_fraction));
  out.haff_t0_theory_dilute = md::haff_time_md(sc, 1.0);
  out.T = ensemble.T;
  std::vector<fields::FieldSeries> members;
  for (const auto& run : out.runs) members.push_back(run.fields);
  out.fields = compare::ensemble_field_series(members);
  out.cost = engine.cost();
  out.engine_details = engine.details();
  out.wall_seconds = wall_before + since(start);
  return out;
}

}  // namespace granvv::app
