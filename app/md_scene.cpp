#include "app/md_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include "compare/ensemble_fields.hpp"
#include "md_bridge/particle_engine_registry.hpp"
#include "md_bridge/particle_sampler.hpp"

namespace granvv::app {

namespace {

// The largest value of f on 4096 cell centres of [-1/2, 1/2).
double sampled_maximum(const std::function<double(double)>& f) {
  double largest = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4096; ++i) largest = std::max(largest, f(-0.5 + (i + 0.5) / 4096));
  return largest;
}

}  // namespace

SignalToNoise initial_signal_to_noise(const MdScene& scene) {
  const auto& sc = scene.spec.scene;
  const double bin = sc.box_length / scene.spec.bins;
  SignalToNoise s;
  s.noise = 1.0 / std::sqrt(sc.number_density() * sc.box_width * bin);
  s.signal =
      std::max(0.0, sampled_maximum([&](double x) { return std::abs(scene.spec.fields.v(x)); }));
  return s;
}

std::optional<MdScene> md_scene_from(const CaseConfig& c, const HydroScene& hydro) {
  if (!c.boolean("md.enabled")) return std::nullopt;
  MdScene s;
  auto& spec = s.spec;
  const double r_key = c.real("md.restitution");
  const double r = r_key > 0.0 ? r_key : 1.0 - 2.0 * hydro.physics.q;
  const double phi = c.real("md.area_fraction"), ly = c.real("md.box_width");
  const long long n = c.integer("md.particles");
  spec.scene = n > 0 ? md::scene_from_particles(n, phi, ly, r)
                     : md::scene_from_scaled(hydro.physics.K, 0.5 * (1.0 - r), phi, ly);
  const std::string problem = md::scene_problem(spec.scene);
  if (!problem.empty()) {
    throw ConfigError(c.origin("md.particles") + ": impossible particle scene: " + problem);
  }
  spec.fields = hydro::make_initial_fields(hydro.initial, hydro.physics);
  spec.seed = static_cast<std::uint64_t>(c.integer("md.seed"));
  spec.t_end = c.real("md.t_end");
  spec.sample_interval = c.real("md.sample_interval");
  spec.output_times = c.reals("md.output_times");
  spec.bins = static_cast<int>(c.integer("md.bins"));
  spec.kernel = c.string("md.kernel");
  spec.kernel_width = c.real("md.kernel_width");
  s.ensemble = static_cast<int>(c.integer("md.ensemble"));
  s.engine = c.string("md.engine");
  for (const KeySpec& key : case_schema()) {
    if (key.section() != "md") continue;
    if (key.type == ValueType::real) s.engine_settings[key.key] = c.real(key.key);
    if (key.type == ValueType::integer) s.engine_settings[key.key] = double(c.integer(key.key));
    if (key.type == ValueType::boolean) s.engine_settings[key.key] = c.boolean(key.key) ? 1 : 0;
  }
  spec.snapshot_interval = c.real("md.snapshot_interval");
  if (c.string("md.time_unit") == "haff") {  // times given in kinetic-theory Haff times
    const double t0 = md::haff_time_md(spec.scene, md::enskog_chi(spec.scene.area_fraction));
    spec.t_end *= t0;
    spec.sample_interval *= t0;
    for (double& t : spec.output_times) t *= t0;
  }
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
  const double n_max = std::max(0.0, sampled_maximum(spec.fields.n));
  if (n_max * spec.scene.area_fraction > 0.5) {
    throw ConfigError(c.origin("md.area_fraction") +
                      ": md.area_fraction = " + format_real(spec.scene.area_fraction) +
                      ": the initial density peak n/n0 = " + format_real(n_max) +
                      " would need a local area fraction above 0.5");
  }
  if (spec.scene.particles > 2'000'000) {
    throw ConfigError(c.origin("md.particles") + ": the scene needs " +
                      std::to_string(spec.scene.particles) +
                      " disks; above 2e6 a single-node run here takes too long (use MPI on a "
                      "cluster, or a larger K / smaller md.box_width)");
  }
  try {
    (void)make_engine(s, "");
  } catch (const std::invalid_argument& e) {
    throw ConfigError(c.origin("md.engine") + ": md.engine = \"" + s.engine + "\": " + e.what());
  }
  return s;
}

std::unique_ptr<md::ParticleEngine> make_engine(const MdScene& scene, const std::string& log_dir) {
  md::ParticleEngineSetup setup;
  setup.scene = scene.spec.scene;
  setup.settings = scene.engine_settings;
  setup.log_dir = log_dir;
  return md::make_particle_engine(scene.engine, setup);
}

MdOutcome run_md_scene(const MdScene& scene, md::ParticleEngine& engine,
                       const std::function<void(int, const md::MdProgress&)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  MdOutcome out;
  const auto& sc = scene.spec.scene;
  out.engine = engine.name();
  out.collision_rule = engine.check_collision_rule();
  if (std::abs(out.collision_rule.restitution - sc.restitution) > 1e-3) {
    std::ostringstream why;
    why << "restitution " << out.collision_rule.restitution << " ("
        << out.collision_rule.description << ") misses md.restitution = " << sc.restitution
        << " by more than 1e-3; refusing the run";
    throw std::runtime_error(why.str());
  }
  std::vector<std::vector<double>> ts, Ts;
  for (int m = 0; m < scene.ensemble; ++m) {
    md::MdRunSpec spec = scene.spec;
    spec.seed += static_cast<std::uint64_t>(m);
    if (!spec.h5md_path.empty() && scene.ensemble > 1) {  // particles.h5 -> particles_m1.h5
      const std::filesystem::path p = spec.h5md_path;
      spec.h5md_path = (p.parent_path() /
                        (p.stem().string() + "_m" + std::to_string(m) + p.extension().string()))
                           .string();
    }
    out.runs.push_back(md::run_md(spec, engine, [&](const md::MdProgress& p) {
      if (progress) progress(m, p);
    }));
    ts.push_back(out.runs.back().series.t);
    Ts.push_back(out.runs.back().series.T);
  }
  try {
    out.haff = compare::fit_haff_ensemble(ts, Ts, 0.0, scene.spec.t_end);
  } catch (const std::invalid_argument&) {  // too few samples, or no cooling: no fit (null)
    out.haff.t0 = out.haff.t0_error = out.haff.T0 = std::nan("");
  }
  out.haff_t0_theory = md::haff_time_md(sc, md::enskog_chi(sc.area_fraction));
  out.haff_t0_theory_dilute = md::haff_time_md(sc, 1.0);
  out.T = compare::ensemble_statistics(Ts);
  std::vector<fields::FieldSeries> members;
  for (const auto& run : out.runs) members.push_back(run.fields);
  out.fields = compare::ensemble_field_series(members);
  out.cost = engine.cost();
  out.engine_details = engine.details();
  out.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace granvv::app
