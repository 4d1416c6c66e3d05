#include "app/atlas_command.hpp"

#include <H5Cpp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "app/output_folder.hpp"
#include "app/report_command.hpp"
#include "app/summary.hpp"
#include "atlas/atlas_analysis.hpp"
#include "atlas/atlas_particles.hpp"
#include "atlas/atlas_power.hpp"
#include "atlas/atlas_runs.hpp"
#include "atlas/detectable_error.hpp"
#include "atlas/recommendation.hpp"
#include "atlas/stability_search.hpp"
#include "atlas/work_precision.hpp"
#include "fields/hdf5_datasets.hpp"
#include "hydro/closure.hpp"
#include "md_bridge/particle_engine_registry.hpp"
#include "models/model.hpp"
#include "scene/atomic_file.hpp"
#include "scene/case_config.hpp"
#include "scene/hydro_scene.hpp"
#include "scene/interruption.hpp"
#include "scene/json_numbers.hpp"
#include "scene/md_scene.hpp"

namespace granvv::app {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using atlas::kNoValue;
// The default grid around the case's own setting (docs/atlas.md): cells times these, and these
// factors on the step bounds. The finest corner is each hydro's converged reference.
const std::vector<double> kCellFactors = {0.25, 0.5, 1.0, 2.0, 4.0, 8.0};
const std::vector<double> kStepFactors = {0.25, 0.5, 1.0, 2.0, 4.0};
// Stability boundaries: the knob is pushed by this factor at most kPushes times from the case's
// own setting, then the first failure is bisected kRefinements times on a log scale.
constexpr int kPushes = 6, kRefinements = 2;
// A run is over-resolved when its numerical error is below this fraction of its model error:
// refining it further cannot bring it closer to the richest model.
constexpr double kOverResolved = 0.1;
// The particles' default grid (docs/atlas.md): the event-driven engine at these ensemble sizes,
// LAMMPS at md.max_overlap and md.steps_per_contact times these (the schema refuses what lies
// beyond its ranges, and the map shows those as refused).
const std::vector<int> kEnsembles = {1, 2, 4, 8, 16, 32, 64, 128, 256, 512};
const std::vector<double> kOverlapFactors = {0.5, 1.0, 2.0, 5.0, 10.0};
const std::vector<double> kContactStepFactors = {1.0 / 3.0, 0.5, 1.0, 2.0};
// The ladder from the poorest model to the richest; a scene runs the ones that apply. The
// event-driven hard disks are the paper's own model, and the richest.
const std::vector<std::string> kLadder = {"haff_ode",         "flow_by_inertia",
                                          "hydro/dilute",     "hydro/enskog",
                                          "particles/lammps", "particles/event_driven"};

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> items;
  std::string item;
  for (char c : s + ",") {
    if (c == ',') {
      if (!item.empty()) items.push_back(item);
      item.clear();
    } else if (c != ' ') {
      item += c;
    }
  }
  return items;
}

// atlas.observables, expanded: "scene" by the scene's type, "crossing_times" into one name per
// crossing level below the stop density.
std::vector<std::string> judged_observables(const CaseConfig& c, bool homogeneous, bool particles,
                                            const std::vector<double>& levels) {
  const std::string text = c.string("atlas.observables");
  std::vector<std::string> asked = split_list(text);
  if (asked.empty()) {
    throw ConfigError(c.origin("atlas.observables") + ": atlas.observables = \"" + text +
                      "\": give \"scene\" or one or more of " +
                      join(atlas_observable_names(), ", "));
  }
  if (asked == std::vector<std::string>{"scene"}) {
    asked = !homogeneous
                ? std::vector<std::string>{"crossing_times", "thermal_energy", "kinetic_energy",
                                           "field_n",        "field_v_x",      "field_T"}
            : particles ? std::vector<std::string>{"thermal_energy", "haff_t0"}
                        : std::vector<std::string>{"thermal_energy"};
  }
  std::vector<std::string> names;
  for (const auto& a : asked) {
    const auto& allowed = atlas_observable_names();
    if (std::find(allowed.begin(), allowed.end(), a) == allowed.end()) {
      throw ConfigError(c.origin("atlas.observables") + ": atlas.observables = \"" + text +
                        "\": '" + a + "' is not an observable; allowed: scene, or " +
                        join(allowed, ", "));
    }
    if (a == "crossing_times") {
      for (double level : levels) names.push_back(crossing_time_name(level));
    } else {
      names.push_back(a);
    }
  }
  return names;
}

struct LadderRung {
  std::string model;
  std::string skipped;  // why it does not apply (empty: it runs)
};

// Every rung that applies; the Haff ODE runs on every scene, even where it cannot follow the
// fields, because it costs microseconds and the atlas shows how far it is.
std::vector<LadderRung> ladder_of(const AtlasScene& scene) {
  std::vector<LadderRung> rungs;
  for (const auto& model : kLadder) {
    LadderRung r{model, ""};
    if (model == "flow_by_inertia" && !scene.has_inertia_reference) {
      r.skipped = "the initial velocity has no flow-by-inertia reference";
    }
    if (model == "hydro/enskog" && !(scene.area_fraction > 0.0)) {
      r.skipped = "needs physics.area_fraction > 0 (the area fraction of the disks)";
    }
    if (is_particles(model)) {
      const auto engines = md::particle_engine_names();
      if (!scene.particles) {
        r.skipped = "md.enabled = false";
      } else if (std::find(engines.begin(), engines.end(), model.substr(10)) == engines.end()) {
        r.skipped = "this build has no particle engine \"" + model.substr(10) + "\"";
      }
    }
    rungs.push_back(r);
  }
  return rungs;
}

struct Grid {
  std::vector<int> cells;
  std::vector<double> factors;
  std::vector<int> ensembles;            // the event-driven engine's
  std::vector<double> particle_factors;  // and its particle counts
  std::vector<double> max_overlaps;
  std::vector<int> steps_per_contacts;
  std::vector<double> injected_errors;  // the comparison power's eps
};

Grid grid_of(const CaseConfig& c, const AtlasScene& scene) {
  Grid g;
  for (long long n : c.integers("atlas.cells")) g.cells.push_back(int(n));
  g.factors = c.reals("atlas.step_factors");
  if (g.cells.empty()) {
    for (double f : kCellFactors) {
      const int n = std::max(4, int(std::lround(scene.case_cells * f)));
      if (g.cells.empty() || n > g.cells.back()) g.cells.push_back(n);
    }
  }
  if (g.factors.empty()) g.factors = kStepFactors;
  for (long long m : c.integers("atlas.ensembles")) g.ensembles.push_back(int(m));
  if (g.ensembles.empty()) g.ensembles = kEnsembles;
  g.particle_factors = c.reals("atlas.particle_factors");
  g.max_overlaps = c.reals("atlas.max_overlaps");
  if (g.max_overlaps.empty()) {
    for (double f : kOverlapFactors) g.max_overlaps.push_back(scene.case_max_overlap * f);
  }
  for (long long k : c.integers("atlas.steps_per_contacts")) g.steps_per_contacts.push_back(int(k));
  if (g.steps_per_contacts.empty()) {
    for (double f : kContactStepFactors) {
      const int k = int(std::lround(scene.case_steps_per_contact * f));
      if (g.steps_per_contacts.empty() || k > g.steps_per_contacts.back()) {
        g.steps_per_contacts.push_back(k);
      }
    }
  }
  g.injected_errors = c.reals("atlas.injected_errors");
  if (g.injected_errors.empty()) g.injected_errors = atlas::default_injected_errors();
  return g;
}

// A run's estimated wall seconds from the pilot (the case's own setting): the work is cells
// times steps, and the steps grow as the cells where the sound limit binds and as 1/factor.
double estimate(const AtlasSetting& s, const AtlasRun& pilot, int case_cells) {
  if (!is_hydro(s.model)) return 0.0;
  const double c = double(s.cells) / case_cells;
  return std::max(pilot.cost.wall_seconds, 1e-3) * std::max(c * c, c) / s.step_factor;
}

json errors_json(const std::map<std::string, double>& e) {
  json j = json::object();
  for (const auto& [k, v] : e) j[k] = v;
  return j;
}

double largest(const std::map<std::string, double>& e) {
  double m = 0.0;
  for (const auto& [k, v] : e) m = std::max(m, v);
  return e.empty() ? kNoValue : m;
}

// Runs the settings with up to `jobs` at a time, each taken from the cache when it is there,
// with a progress line per finished run.
class AtlasRunner {
 public:
  AtlasRunner(const AtlasScene& scene, fs::path cache, int jobs, bool quiet)
      : scene_(scene), cache_(std::move(cache)), jobs_(jobs), quiet_(quiet) {}

  std::vector<AtlasRun> run(const std::vector<AtlasSetting>& settings,
                            const std::vector<double>& estimates) {
    std::vector<AtlasRun> runs(settings.size());
    std::atomic<std::size_t> next{0};
    double left = 0.0;
    for (double e : estimates) left += e;
    auto work = [&] {
      for (std::size_t i = next++; i < settings.size(); i = next++) {
        if (interruption_signal()) return;
        runs[i] = run_atlas_setting(scene_, settings[i], cache_);
        std::lock_guard<std::mutex> lock(mutex_);
        ++done_;
        made_ += !runs[i].cached && runs[i].status != "refused";
        left -= estimates[i];
        spent_ += runs[i].cached ? 0.0 : runs[i].cost.wall_seconds;
        if (!quiet_) {
          std::fprintf(stderr, "atlas: %d runs done, %zu left, ETA %.0f s (%s: %s, %.3g s%s)\n",
                       done_, settings.size() - std::min(settings.size(), next.load()),
                       std::max(0.0, left) / jobs_, describe(settings[i]).c_str(),
                       runs[i].status.c_str(), runs[i].cost.wall_seconds,
                       runs[i].cached ? ", cached" : "");
        }
      }
    };
    // Particle runs call MPI (single-threaded) and are one engine each: on this thread, in turn.
    const bool serial =
        jobs_ == 1 || std::any_of(settings.begin(), settings.end(),
                                  [](const AtlasSetting& s) { return is_particles(s.model); });
    if (serial) {
      work();
      return runs;
    }
    std::vector<std::thread> pool;
    for (int j = 0; j < std::min<int>(jobs_, int(settings.size())); ++j) pool.emplace_back(work);
    for (auto& t : pool) t.join();
    return runs;
  }
  AtlasRun run_one(const AtlasSetting& s) { return run({s}, {0.0}).front(); }
  double spent() const { return spent_; }
  int made() const { return made_; }
  int done() const { return done_; }

 private:
  const AtlasScene& scene_;
  fs::path cache_;
  int jobs_;
  bool quiet_;
  std::mutex mutex_;
  int done_ = 0, made_ = 0;
  double spent_ = 0.0;
};

void write_atlas_h5(const fs::path& file, const std::vector<AtlasRun>& runs,
                    const std::vector<ObservableErrors>& numerical,
                    const std::vector<ObservableErrors>& model,
                    const std::vector<std::string>& observables) {
  const fs::path tmp = file.string() + ".partial";
  {
    H5::H5File f(tmp.string(), H5F_ACC_TRUNC);
    H5::Group g = f.createGroup("runs");
    std::vector<std::string> names, status;
    std::vector<double> cells, factor, ensemble, particle_factor, overlap, spc, adaptive, wall,
        work;
    for (const auto& r : runs) {
      names.push_back(r.setting.model), status.push_back(r.status);
      cells.push_back(r.setting.cells), factor.push_back(r.setting.step_factor);
      ensemble.push_back(r.setting.ensemble), overlap.push_back(r.setting.max_overlap);
      particle_factor.push_back(r.setting.particle_factor);
      spc.push_back(r.setting.steps_per_contact), adaptive.push_back(r.setting.adaptive_stiffness);
      wall.push_back(r.cost.wall_seconds), work.push_back(r.cost.work);
    }
    h5::write_strings(g, "model", names);
    h5::write_strings(g, "status", status);
    h5::write_vector(g, "cells", cells);
    h5::write_vector(g, "step_factor", factor);
    h5::write_vector(g, "ensemble", ensemble);
    h5::write_vector(g, "particle_factor", particle_factor);
    h5::write_vector(g, "max_overlap", overlap);
    h5::write_vector(g, "steps_per_contact", spc);
    h5::write_vector(g, "adaptive_stiffness", adaptive);
    h5::write_vector(g, "wall_seconds", wall);
    h5::write_vector(g, "work", work);
    h5::write_attribute(g, "missing", "NaN: the run does not give the observable; 0: no such knob");
    auto group = [&](const char* name, const std::vector<ObservableErrors>& errors,
                     bool reference_error) {
      H5::Group e = g.createGroup(name);
      for (const auto& o : observables) {
        std::vector<double> v;
        for (const auto& m : errors) {
          const auto it = m.find(o);
          v.push_back(it == m.end()     ? kNoValue
                      : reference_error ? it->second.reference_error
                                        : it->second.error);
        }
        h5::write_vector(e, o, v);
      }
    };
    group("numerical_error", numerical, false);
    group("model_error", model, false);
    group("reference_statistical_error", model, true);
  }
  fs::rename(tmp, file);
}

// How much of --budget a family of rungs may plan: the budget left over the families left to
// plan, so that what one family leaves passes to the next (docs/atlas.md).
class BudgetShares {
 public:
  BudgetShares(double budget, int families) : budget_(budget), left_(std::max(1, families)) {}
  // The share of the next family; its use is then charged with spend and closed with done.
  double share() const { return std::max(0.0, budget_ - used_) / left_; }
  void spend(double seconds) { used_ += seconds; }
  void done() { left_ = std::max(1, left_ - 1); }

 private:
  double budget_;
  int left_;
  double used_ = 0.0;
};

json skipped_for_budget(const AtlasSetting& s, double estimate, double share, double budget) {
  return {{"setting", setting_json(s)},
          {"estimate_seconds", estimate},
          {"reason", "its estimated " + format_real(estimate) + " s would pass the share of " +
                         s.model + " in the budget (" + format_real(share) + " s of --budget " +
                         format_real(budget) + ")"}};
}

// The comparison power within its share of the budget (atlas/atlas_power.hpp): the eps grid is
// thinned to every other value until its hydro runs fit, and skipped with the reason if even
// two values do not.
json comparison_power_within(const AtlasScene& scene, const std::vector<AtlasRun>& runs,
                             const std::string& reference_model, std::vector<double> epsilons,
                             BudgetShares& budget, int jobs, AtlasRunner& runner,
                             double total_budget) {
  const AtlasRun* unperturbed = nullptr;
  std::vector<const AtlasRun*> particle_runs;
  for (const auto& r : runs) {
    if (r.setting.model == "hydro/" + scene.closure && r.setting.cells == scene.case_cells &&
        r.setting.step_factor == 1.0) {
      unperturbed = &r;
    }
    const bool own_contact = !is_lammps(reference_model) ||
                             (r.setting.max_overlap == scene.case_max_overlap &&
                              r.setting.steps_per_contact == scene.case_steps_per_contact &&
                              r.setting.adaptive_stiffness == scene.case_adaptive_stiffness);
    if (r.setting.model == reference_model && r.status == "ok" && r.fields && own_contact &&
        r.setting.particle_factor == 1.0) {
      particle_runs.push_back(&r);
    }
  }
  std::stable_sort(particle_runs.begin(), particle_runs.end(),
                   [](const AtlasRun* a, const AtlasRun* b) {
                     return a->setting.ensemble < b->setting.ensemble;
                   });
  const double share = budget.share();
  budget.done();
  if (!unperturbed || unperturbed->status != "ok") {
    return {{"skipped", "the case's own hydro (hydro/" + scene.closure +
                            ") did not finish, so there is nothing to inject errors into"}};
  }
  const double each = std::max(unperturbed->cost.wall_seconds, 1e-3);
  const std::size_t per_eps = comparison_power_settings(scene, {1.0}).size();
  auto estimate_of = [&](std::size_t n) { return each * double(per_eps * n) / jobs; };
  int thinned = 0;
  while (epsilons.size() > 2 && estimate_of(epsilons.size()) > share) {
    std::vector<double> kept;
    for (std::size_t i = 0; i < epsilons.size(); i += 2) kept.push_back(epsilons[i]);
    epsilons = kept;
    ++thinned;
  }
  if (estimate_of(epsilons.size()) > share) {
    return {{"skipped", "its " + std::to_string(per_eps * epsilons.size()) +
                            " hydro runs, estimated " + format_real(estimate_of(epsilons.size())) +
                            " s, would pass its share of the budget (" + format_real(share) +
                            " s of --budget " + format_real(total_budget) + ")"}};
  }
  const std::vector<AtlasSetting> settings = comparison_power_settings(scene, epsilons);
  const std::vector<AtlasRun> hydro_runs =
      runner.run(settings, std::vector<double>(settings.size(), each));
  budget.spend(estimate_of(epsilons.size()));
  json power = comparison_power(scene, *unperturbed, hydro_runs, particle_runs, epsilons);
  power["thinned"] = thinned;  // times the default grid was halved to fit the budget
  return power;
}

}  // namespace

int atlas_command(const AtlasOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  // 1. The scene, validated before anything runs.
  AtlasScene scene;
  std::vector<std::string> observables;
  std::vector<LadderRung> ladder;
  Grid grid;
  std::string initial_type;
  double stop_density = 0.0;
  try {
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
    scene.source = locate_case(options.case_name);
    scene.sets = options.sets;
    const CaseConfig config =
        CaseConfig::from_string(scene.source.text, scene.source.origin, scene.sets);
    HydroScene hydro = hydro_scene_from(config);
    scene.name = config.name();
    scene.particles = config.boolean("md.enabled");
    scene.bins = config.int_value("atlas.bins");
    scene.collapse_rule_limit = config.real("atlas.collapse_rule_limit");
    scene.case_cells = hydro.cells;
    scene.case_cfl = hydro.control.time_step.cfl;
    scene.case_dt_max = hydro.control.time_step.dt_max;
    scene.case_max_compression = hydro.control.time_step.max_compression;
    scene.area_fraction = hydro.area_fraction;
    scene.sigmas = config.real("compare.sigmas");
    scene.closure = hydro.closure;
    scene.agreement_fraction = config.real("compare.agreement_fraction");
    scene.transverse = hydro.transverse;
    if (scene.particles) {
      // Every model is compared on the particles' bins: their ensemble mean has its error there.
      const int md_bins = config.int_value("md.bins");
      if (config.origin("atlas.bins") != "default" && scene.bins != md_bins) {
        throw ConfigError(config.origin("atlas.bins") +
                          ": atlas.bins = " + std::to_string(scene.bins) +
                          ": a particle scene is compared on md.bins = " + std::to_string(md_bins) +
                          "; leave atlas.bins unset or equal to it");
      }
      scene.bins = md_bins;
      const std::optional<MdScene> md = md_scene_from(config, hydro);
      scene.case_ensemble = md->ensemble;
      scene.case_box_width = config.real("md.box_width");
      scene.case_particles = config.int_value("md.particles");
      scene.case_max_overlap = config.real("md.max_overlap");
      scene.case_steps_per_contact = config.int_value("md.steps_per_contact");
      scene.case_adaptive_stiffness = config.boolean("md.adaptive_stiffness");
      scene.particle_count = md->spec.scene.particles;
      scene.md_t_end = md->spec.t_end;
      scene.md_t_haff =
          md::haff_time_md(md->spec.scene, md::enskog_chi(md->spec.scene.area_fraction));
      scene.t0_theory = md->spec.scene.scaled_time(scene.md_t_haff);
      scene.signal_to_noise = initial_signal_to_noise(*md).ratio();
    }
    initial_type = hydro.initial.type;
    scene.has_inertia_reference = hydro::inertia_reference(hydro.initial).has_value();
    stop_density = hydro.control.stop_density;
    for (double level : hydro.control.crossing_densities) {
      if (level < stop_density && initial_type != "uniform") scene.crossing_levels.push_back(level);
    }
    observables = judged_observables(config, initial_type == "uniform", scene.particles,
                                     scene.crossing_levels);
    grid = grid_of(config, scene);
    ladder = ladder_of(scene);
    // The compared times: the hydro's own output times, or those of a particle scene.
    AtlasSetting probe;
    probe.model = "hydro/" + hydro.closure;
    probe.cells = scene.case_cells;
    probe.step_factor = 1.0;
    const CaseConfig first = CaseConfig::from_string(scene.source.text, scene.source.origin,
                                                     setting_overrides(scene, probe));
    const HydroScene aligned = atlas_hydro_scene(first, scene);
    scene.times = aligned.control.output_times;
    if (scene.times.empty()) scene.times.push_back(aligned.control.t_end);
  } catch (const ConfigError& e) {
    report_input_error(e);
    return 2;
  }
  const fs::path dir = options.out_dir.empty() ? fs::path("out") / (scene.name + "-atlas")
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
  AtlasRunner runner(scene, dir / "runs", jobs, options.quiet);
  auto interrupted = [&] {
    std::cerr << "granvv: atlas interrupted; the " << runner.made() << " runs made are cached in "
              << (dir / "runs").string() << ", and a re-run of the same atlas keeps them\n";
    return interrupted_exit_code();
  };

  // 2. The exact solutions, and the pilot: each hydro at the case's own setting.
  std::vector<AtlasRun> runs;
  std::vector<std::string> hydro_models, particle_models;
  json skipped = json::array();
  for (const auto& rung : ladder) {
    if (!rung.skipped.empty()) continue;
    if (is_hydro(rung.model)) {
      hydro_models.push_back(rung.model);
    } else if (is_particles(rung.model)) {
      particle_models.insert(particle_models.begin(), rung.model);  // the hard disks first
    } else {
      AtlasSetting s;
      s.model = rung.model;
      runs.push_back(runner.run_one(s));
    }
  }
  // The families that share the budget: each hydro, each particle engine and, in a particle
  // scene, the comparison power.
  BudgetShares budget(options.budget, int(hydro_models.size() + particle_models.size() +
                                          (particle_models.empty() ? 0 : 1)));
  std::vector<AtlasSetting> planned;
  std::vector<double> estimates;
  for (const auto& model : hydro_models) {
    const double share = budget.share();
    const AtlasRun pilot = runner.run_one(hydro_setting(model, scene.case_cells, 1.0));
    runs.push_back(pilot);
    double planned_seconds = pilot.cost.wall_seconds;
    // 3. The grid within the budget: the finest corner (the reference) first, then the cheapest.
    std::vector<AtlasSetting> grid_settings;
    for (int c : grid.cells) {
      for (double f : grid.factors) {
        if (c == scene.case_cells && f == 1.0) continue;
        grid_settings.push_back(hydro_setting(model, c, f));
      }
    }
    const AtlasSetting finest = hydro_setting(model, grid.cells.back(), grid.factors.front());
    std::stable_sort(
        grid_settings.begin(), grid_settings.end(),
        [&](const AtlasSetting& a, const AtlasSetting& b) {
          const bool fa = a.cells == finest.cells && a.step_factor == finest.step_factor;
          const bool fb = b.cells == finest.cells && b.step_factor == finest.step_factor;
          if (fa != fb) return fa;
          return estimate(a, pilot, scene.case_cells) < estimate(b, pilot, scene.case_cells);
        });
    for (const auto& s : grid_settings) {
      const double e = estimate(s, pilot, scene.case_cells);
      if ((planned_seconds + e) / jobs > share) {
        skipped.push_back(skipped_for_budget(s, e, share, options.budget));
        continue;
      }
      planned_seconds += e;
      planned.push_back(s);
      estimates.push_back(e);
    }
    budget.spend(planned_seconds / jobs);
    budget.done();
  }
  {
    auto more = runner.run(planned, estimates);
    runs.insert(runs.end(), more.begin(), more.end());
  }
  if (interruption_signal()) return interrupted();
  // The particles, one engine at a time: each engine's pilot (the case's own setting at one
  // ensemble member), then its grid from the case's own setting upward in cost, within its share.
  for (const auto& model : particle_models) {
    const double share = budget.share();
    const AtlasRun pilot = runner.run_one(particle_pilot(scene, model));
    runs.push_back(pilot);
    if (interruption_signal()) return interrupted();
    if (pilot.status == "refused") {  // the scene is not one this engine takes: no grid
      skipped.push_back(
          {{"setting", setting_json(pilot.setting)},
           {"reason", "the pilot was refused, so is every setting: " + pilot.reason}});
      budget.done();
      continue;
    }
    double planned_seconds = pilot.cost.wall_seconds;
    std::vector<AtlasSetting> grid_settings =
        is_lammps(model)
            ? lammps_grid(scene, grid.max_overlaps, grid.steps_per_contacts)
            : event_driven_grid(grid.ensembles, grid.particle_factors, scene.case_ensemble);
    auto own = [&](const AtlasSetting& s) {
      return is_lammps(model) && s.max_overlap == scene.case_max_overlap &&
             s.steps_per_contact == scene.case_steps_per_contact &&
             s.adaptive_stiffness == scene.case_adaptive_stiffness;
    };
    std::stable_sort(grid_settings.begin(), grid_settings.end(),
                     [&](const AtlasSetting& a, const AtlasSetting& b) {
                       if (own(a) != own(b)) return own(a);
                       return particle_estimate(a, pilot, scene) <
                              particle_estimate(b, pilot, scene);
                     });
    std::vector<AtlasSetting> particle_plan;
    std::vector<double> particle_estimates;
    for (const auto& s : grid_settings) {
      if (describe(s) == describe(pilot.setting)) continue;
      const double e = particle_estimate(s, pilot, scene);
      if (planned_seconds + e > share) {
        skipped.push_back(skipped_for_budget(s, e, share, options.budget));
        continue;
      }
      planned_seconds += e;
      particle_plan.push_back(s);
      particle_estimates.push_back(e);
    }
    budget.spend(planned_seconds);
    budget.done();
    auto more = runner.run(particle_plan, particle_estimates);
    runs.insert(runs.end(), more.begin(), more.end());
    if (interruption_signal()) return interrupted();
  }

  // 4. References: each model's finest run that finished; the richest model's is the reference
  // of the model errors.
  auto finest_of = [&](const std::string& model) -> const AtlasRun* {
    const AtlasRun* best = nullptr;
    for (const auto& r : runs) {
      if (r.setting.model != model || r.status != "ok") continue;
      // The reference keeps the case's particle count: other counts are another scene's size.
      if (r.setting.particle_factor != 1.0) continue;
      const bool finer =
          !best || (is_particles(model) ? finer_particle_run(r.setting, best->setting)
                                        : (r.setting.cells > best->setting.cells ||
                                           (r.setting.cells == best->setting.cells &&
                                            r.setting.step_factor < best->setting.step_factor)));
      if (finer) best = &r;
    }
    return best;
  };
  std::map<std::string, const AtlasRun*> own_reference;
  std::string richest;
  for (const auto& rung : ladder) {
    if (!is_hydro(rung.model) && !is_particles(rung.model)) continue;
    if (const AtlasRun* f = finest_of(rung.model))
      own_reference[rung.model] = f, richest = rung.model;
  }
  if (richest.empty()) {
    std::cerr << "granvv: error: atlas: no hydro or particle run finished, so there is no "
                 "reference to measure errors against\n";
    return 1;
  }
  const AtlasRun& reference = *own_reference[richest];
  const bool particle_reference = is_particles(richest);
  // What the reference itself does not give (a density level the peak never reached, the
  // crossing times the particles do not report) cannot be judged: it is dropped from the
  // observables, and atlas.json says so.
  json not_judged = json::array();
  {
    const std::vector<std::string> given = provided_observables(reference, observables);
    for (const auto& name : observables) {
      if (std::find(given.begin(), given.end(), name) == given.end()) not_judged.push_back(name);
    }
    observables = given;
  }
  // The reference's own error: a hydro's from its neighbours one step coarser in cells and in
  // step; the particles' is their ensemble standard error (the hard disks have no other knob).
  const std::map<std::string, double> statistical = statistical_errors(reference, observables);
  std::map<std::string, double> convergence;
  if (particle_reference) {
    convergence = statistical;
  } else {
    for (const auto& r : runs) {
      if (r.setting.model != richest || r.status != "ok" || &r == &reference) continue;
      const bool coarser_cells = r.setting.step_factor == reference.setting.step_factor &&
                                 r.setting.cells < reference.setting.cells &&
                                 2 * r.setting.cells >= reference.setting.cells;
      const bool coarser_step = r.setting.cells == reference.setting.cells &&
                                r.setting.step_factor > reference.setting.step_factor &&
                                r.setting.step_factor <= 2 * reference.setting.step_factor;
      if (!coarser_cells && !coarser_step) continue;
      for (const auto& [k, v] : observable_errors(r, reference, observables)) {
        convergence[k] = std::max(convergence.count(k) ? convergence[k] : 0.0, v.error);
      }
    }
  }

  // The comparison power: the case's own hydro with injected model errors, judged side by side
  // against every run of the reference engine (its ensemble sizes are the particle cost axis).
  json power = nullptr;
  if (particle_reference) {
    power = comparison_power_within(scene, runs, richest, grid.injected_errors, budget, jobs,
                                    runner, options.budget);
    if (interruption_signal()) return interrupted();
  }

  // 5. Errors, fronts, recommendation.
  std::vector<ObservableErrors> numerical(runs.size()), model_error(runs.size());
  std::vector<atlas::Candidate> candidates;
  std::vector<std::size_t> candidate_run;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const AtlasRun& r = runs[i];
    if (r.status != "ok") continue;
    if (own_reference.count(r.setting.model)) {
      numerical[i] = observable_errors(r, *own_reference[r.setting.model], observables);
    }
    if (&r == &reference) {
      for (const auto& [k, v] : convergence) {
        model_error[i][k] = {v, statistical.count(k) ? statistical.at(k) : kNoValue};
      }
    } else {
      model_error[i] = observable_errors(r, reference, observables);
    }
    candidates.push_back(
        {r.cost.wall_seconds, errors_of(model_error[i]), reference_errors_of(model_error[i])});
    candidate_run.push_back(i);
  }
  const std::optional<std::size_t> best =
      atlas::cheapest_adequate(candidates, observables, options.tolerance, scene.sigmas);
  json recommendation;
  if (best) {
    const AtlasRun& r = runs[candidate_run[*best]];
    recommendation = {{"tolerance", options.tolerance},
                      {"sigmas", scene.sigmas},
                      {"model", r.setting.model},
                      {"setting", setting_json(r.setting)},
                      {"cost",
                       {{"wall_seconds", r.cost.wall_seconds},
                        {"work", r.cost.work},
                        {"work_unit", r.cost.work_unit}}},
                      {"error", errors_json(errors_of(model_error[candidate_run[*best]]))},
                      {"reference_statistical_error",
                       errors_json(reference_errors_of(model_error[candidate_run[*best]]))}};
    // The next rung up: the cheapest adequate run of a richer model, else the cheapest of the
    // next richer model that ran.
    const auto rank = [](const std::string& m) {
      return std::find(kLadder.begin(), kLadder.end(), m) - kLadder.begin();
    };
    json next = nullptr;
    for (int pass = 0; pass < 2 && next.is_null(); ++pass) {
      const AtlasRun* pick = nullptr;
      for (std::size_t k = 0; k < candidates.size(); ++k) {
        const AtlasRun& c = runs[candidate_run[k]];
        if (rank(c.setting.model) <= rank(r.setting.model)) continue;
        if (pass == 0 &&
            !atlas::adequate(candidates[k], observables, options.tolerance, scene.sigmas)) {
          continue;
        }
        if (!pick || c.cost.wall_seconds < pick->cost.wall_seconds) pick = &c;
      }
      if (pick) {
        next = {{"model", pick->setting.model},
                {"setting", setting_json(pick->setting)},
                {"adequate", pass == 0},
                {"cost", {{"wall_seconds", pick->cost.wall_seconds}, {"work", pick->cost.work}}}};
      }
    }
    recommendation["next_rung"] = next;
  } else {
    recommendation = {{"tolerance", options.tolerance},
                      {"sigmas", scene.sigmas},
                      {"model", nullptr},
                      {"reason", "no run meets the tolerance on every observable"}};
  }
  std::map<std::string, std::vector<bool>> fronts;  // per observable, over the runs
  for (const auto& name : observables) {
    std::vector<double> cost, error;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const auto it = model_error[i].find(name);
      cost.push_back(runs[i].status == "ok" ? runs[i].cost.wall_seconds : kNoValue);
      error.push_back(it == model_error[i].end() ? kNoValue : it->second.error);
    }
    fronts[name] = atlas::pareto_front(cost, error);
  }

  // 6. Stability boundaries of each hydro around the case's own setting. A run's state against
  // its own finest run is worked out once: from its numerical error for a grid run, on arrival
  // for a probe.
  json stability = json::array();
  for (const auto& model : hydro_models) {
    if (!own_reference.count(model)) continue;
    const AtlasRun& ref = *own_reference[model];
    auto classify = [&](const AtlasRun& r, const ObservableErrors& errors) -> std::string {
      if (r.status != "ok") return r.status;
      return largest(errors_of(errors)) > options.tolerance ? "error_above_tolerance" : "";
    };
    std::map<std::pair<int, double>, std::string> state;  // (cells, step factor) -> failure
    std::vector<const AtlasRun*> drawn_runs;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      if (runs[i].setting.model != model) continue;
      if (state
              .emplace(std::pair{runs[i].setting.cells, runs[i].setting.step_factor},
                       classify(runs[i], numerical[i]))
              .second) {
        drawn_runs.push_back(&runs[i]);
      }
    }
    std::vector<AtlasRun> probed;  // the boundary searches' runs, drawn on the map too
    probed.reserve(2 * (kPushes + kRefinements + 1));
    auto state_of = [&](const AtlasSetting& s) {
      const std::pair key{s.cells, s.step_factor};
      if (const auto it = state.find(key); it != state.end()) return it->second;
      probed.push_back(runner.run_one(s));
      drawn_runs.push_back(&probed.back());
      return state[key] =
                 classify(probed.back(), observable_errors(probed.back(), ref, observables));
    };
    json boundaries = json::array();
    struct Push {
      const char* knob;
      double factor;
    };
    for (const Push push : {Push{"step_factor", 2.0}, Push{"cells", 0.5}}) {
      const bool cells = std::string(push.knob) == "cells";
      auto probe = [&](double knob) {
        if (interruption_signal()) return std::string("interrupted");
        return state_of(hydro_setting(model, cells ? int(std::lround(knob)) : scene.case_cells,
                                      cells ? 1.0 : knob));
      };
      const double start_knob = cells ? scene.case_cells : 1.0;
      if (!state_of(hydro_setting(model, scene.case_cells, 1.0)).empty()) {
        boundaries.push_back({{"knob", push.knob},
                              {"note",
                               "the case's own setting already fails against the "
                               "finest run; no boundary searched"}});
        continue;
      }
      const atlas::StabilityBoundary b =
          atlas::find_stability_boundary(start_knob, push.factor, kPushes, kRefinements, probe);
      boundaries.push_back({{"knob", push.knob},
                            {"direction", push.factor > 1 ? "up" : "down"},
                            {"stable", b.stable},
                            {"failed", b.failure.empty() ? json(nullptr) : json(b.failed)},
                            {"failure", b.failure.empty() ? json(nullptr) : json(b.failure)},
                            {"probes", b.probes}});
    }
    json grid_points = json::array();
    for (const AtlasRun* r : drawn_runs) {
      const std::string& c = state.at({r->setting.cells, r->setting.step_factor});
      grid_points.push_back({{"cells", r->setting.cells},
                             {"step_factor", r->setting.step_factor},
                             {"state", c.empty() ? "ok" : c}});
    }
    stability.push_back({{"model", model},
                         {"default", {{"cells", scene.case_cells}, {"step_factor", 1.0}}},
                         {"grid", grid_points},
                         {"boundaries", boundaries}});
  }
  // The DEM's stability and bias map against the hard disks.
  json dem = nullptr;
  if (std::find(particle_models.begin(), particle_models.end(), "particles/lammps") !=
      particle_models.end()) {
    const auto hard = own_reference.find("particles/event_driven");
    dem = dem_map(scene, runs, model_error, observables,
                  hard == own_reference.end() ? nullptr : hard->second, scene.t0_theory,
                  options.tolerance, scene.sigmas);
  }

  // 7. The ladder timeline: how long each model's best run stays within the tolerance.
  json timeline = json::array();
  for (const auto& rung : ladder) {
    if (!rung.skipped.empty()) continue;
    const AtlasRun* best_run =
        own_reference.count(rung.model) ? own_reference[rung.model] : nullptr;
    for (const auto& r : runs) {
      if (!best_run && r.setting.model == rung.model && r.status == "ok") best_run = &r;
    }
    if (!best_run) continue;
    const std::vector<std::string> judged = provided_observables(*best_run, observables);
    const std::vector<ObservableError> e =
        error_over_time(*best_run, reference, judged, scene.sigmas);
    json until = nullptr, exceeded = nullptr;
    for (std::size_t i = 0; i < e.size(); ++i) {
      if (!atlas::within_tolerance(e[i].error, e[i].reference_error, options.tolerance,
                                   scene.sigmas)) {
        exceeded = reference.times[i];
        break;
      }
      until = reference.times[i];
    }
    json errs = json::array(), reference_errs = json::array();
    for (const auto& x : e) {
      errs.push_back(number_or_null(x.error));
      reference_errs.push_back(number_or_null(x.reference_error));
    }
    timeline.push_back({{"model", rung.model},
                        {"setting", setting_json(best_run->setting)},
                        {"judged", judged},
                        {"times", reference.times},
                        {"error", errs},
                        {"reference_statistical_error", reference_errs},
                        {"adequate_until", until},
                        {"exceeded_at", exceeded},
                        {"monitors", best_run->monitor_crossings}});
  }

  // 8. atlas.json, atlas.h5, atlas.html.
  json run_rows = json::array();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const AtlasRun& r = runs[i];
    json pareto = json::array();
    for (const auto& name : observables) {
      if (fronts[name][i]) pareto.push_back(name);
    }
    const double num = largest(errors_of(numerical[i])), mod = largest(errors_of(model_error[i]));
    json row = setting_json(r.setting);
    row.update({{"status", r.status},
                {"reason", r.reason},
                {"wall_seconds", r.cost.wall_seconds},
                {"work", r.cost.work},
                {"work_unit", r.cost.work_unit},
                {"rejected_steps", r.rejected_steps},
                {"cached", r.cached},
                {"numerical_error", errors_json(errors_of(numerical[i]))},
                {"model_error", errors_json(errors_of(model_error[i]))},
                {"reference_statistical_error", errors_json(reference_errors_of(model_error[i]))},
                {"over_resolved", r.setting.model != richest && std::isfinite(num) &&
                                      std::isfinite(mod) && num < kOverResolved * mod},
                {"pareto", pareto}});
    if (is_particles(r.setting.model) && r.status == "ok") {
      json sc = json::object();
      for (const auto& [k, v] : r.scalars) {
        sc[k] = {
            {"value", number_or_null(v)},
            {"error", number_or_null(r.scalar_errors.count(k) ? r.scalar_errors.at(k) : kNoValue)}};
      }
      row["scalars"] = sc;
    }
    run_rows.push_back(row);
  }
  json ladder_rows = json::array();
  for (const auto& rung : ladder) {
    ladder_rows.push_back({{"model", rung.model},
                           {"runs", rung.skipped.empty()},
                           {"reason", rung.skipped.empty() ? json(nullptr) : json(rung.skipped)}});
  }
  bool converged = true;
  for (const auto& [k, v] : convergence) converged &= v <= options.tolerance;
  json atlas = {
      {"recommendation", recommendation},
      {"case", scene.name},
      {"granvv_version", GRANVV_VERSION},
      {"status", "ok"},
      {"tolerance", options.tolerance},
      {"sigmas", scene.sigmas},
      {"budget_seconds", options.budget},
      {"jobs", jobs},
      {"observables", observables},
      {"observables_not_judged",
       {{"names", not_judged},
        {"why",
         "the reference run does not give them (a crossing level its peak "
         "density never reached, or a crossing time of the particles)"}}},
      {"times", scene.times},
      {"ladder", ladder_rows},
      {"reference",
       {{"setting", setting_json(reference.setting)},
        {"convergence", errors_json(convergence)},
        {"statistical_error", errors_json(statistical)},
        {"converged_to_tolerance", converged},
        {"how", particle_reference ? "the reference's ensemble standard error (relative; the "
                                     "event-driven hard disks have no discretisation knob)"
                                   : "largest difference to its neighbours one step coarser in "
                                     "cells and in step factor: an upper bound of its own error"}}},
      {"runs", run_rows},
      {"stability", stability},
      {"dem_map", dem},
      {"timeline", timeline},
      {"comparison_power", power},
      {"skipped", skipped},
      {"runs_made", runner.made()},
      {"run_seconds", runner.spent()},
      {"wall_seconds", seconds_since(start)}};
  try {
    write_atlas_h5(dir / "atlas.h5", runs, numerical, model_error, observables);
    write_file_atomically(dir / "atlas.json", summary_text(atlas));
  } catch (const std::exception& e) {
    std::cerr << "granvv: error: atlas: " << e.what() << "\n";
    return 1;
  }
  if (best) {
    std::cerr << "atlas: at tolerance " << options.tolerance << " the cheapest adequate model is "
              << describe(runs[candidate_run[*best]].setting) << "\n";
  } else {
    std::cerr << "atlas: no run meets tolerance " << options.tolerance << " on every observable\n";
  }
  std::cerr << "atlas: wrote " << (dir / "atlas.json").string() << " (" << runs.size() << " runs, "
            << runner.made() << " made now)\n";
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

}  // namespace granvv::app
