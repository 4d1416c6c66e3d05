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
#include "atlas/atlas_power.hpp"
#include "atlas/atlas_runs.hpp"
#include "atlas/dem_map.hpp"
#include "atlas/detectable_error.hpp"
#include "atlas/recommendation.hpp"
#include "atlas/stability_search.hpp"
#include "atlas/work_precision.hpp"
#include "fields/hdf5_datasets.hpp"
#include "models/model.hpp"
#include "models/model_family.hpp"
#include "models/setting_run.hpp"
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
// Stability boundaries: the knob is pushed by this factor at most kPushes times from the case's
// own setting, then the first failure is bisected kRefinements times on a log scale.
constexpr int kPushes = 6, kRefinements = 2;
// A run is over-resolved when its numerical error is below this fraction of its model error:
// refining it further cannot bring it closer to the richest model.
constexpr double kOverResolved = 0.1;
// The knob every ensemble family shares (models/particle_family.hpp): its size.
constexpr const char* kEnsemble = "ensemble";

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

// Every family, and why it does not apply; the Haff ODE runs on every scene, even where it
// cannot follow the fields, because it costs microseconds and the atlas shows how far it is.
std::vector<LadderRung> ladder_of(const AtlasScene& scene) {
  std::vector<LadderRung> rungs;
  for (const ModelFamily* family : model_families()) {
    rungs.push_back({family->name(), family->not_applicable(scene).value_or("")});
  }
  return rungs;
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
        jobs_ == 1 || std::any_of(settings.begin(), settings.end(), [](const AtlasSetting& s) {
          return !model_family(s.model).runs_on_threads();
        });
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
    std::vector<double> wall, work;
    std::map<std::string, std::vector<double>> knobs;  // every family's knobs, by name
    const std::vector<KnobSpec> columns = all_knobs();
    for (const auto& r : runs) {
      names.push_back(r.setting.model), status.push_back(r.status);
      for (const KnobSpec& k : columns) {
        const auto it = r.setting.knobs.find(k.name);
        knobs[k.name].push_back(it == r.setting.knobs.end() ? k.absent : it->second);
      }
      wall.push_back(r.cost.wall_seconds), work.push_back(r.cost.work);
    }
    h5::write_strings(g, "model", names);
    h5::write_strings(g, "status", status);
    for (const KnobSpec& k : columns) h5::write_vector(g, k.name, knobs[k.name]);
    h5::write_vector(g, "wall_seconds", wall);
    h5::write_vector(g, "work", work);
    h5::write_attribute(g, "missing",
                        "NaN: the run does not give the observable; a knob the run's model does "
                        "not have holds its neutral value (0, or 1 for a factor)");
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
                             const ModelFamily& reference_family, std::vector<double> epsilons,
                             BudgetShares& budget, int jobs, AtlasRunner& runner,
                             double total_budget) {
  // The hydro the case itself runs, at its own setting, takes the injected errors.
  const ModelFamily* hydro = nullptr;
  for (const ModelFamily* f : model_families()) {
    if (f->kind() == FamilyKind::discretised && f->is_case_model(scene)) hydro = f;
  }
  const AtlasRun* unperturbed = nullptr;
  std::vector<const AtlasRun*> particle_runs;
  const AtlasSetting own_particles = reference_family.case_setting(scene);
  for (const auto& r : runs) {
    if (hydro && r.setting == hydro->case_setting(scene)) unperturbed = &r;
    // The reference's runs at the case's own setting but for the ensemble size.
    const bool own_setting =
        reference_family.with_knob(r.setting, kEnsemble, own_particles.knob(kEnsemble)) ==
        own_particles;
    if (r.setting.model == reference_family.name() && r.status == "ok" && r.fields && own_setting) {
      particle_runs.push_back(&r);
    }
  }
  std::stable_sort(particle_runs.begin(), particle_runs.end(),
                   [](const AtlasRun* a, const AtlasRun* b) {
                     return a->setting.knob(kEnsemble) < b->setting.knob(kEnsemble);
                   });
  const double share = budget.share();
  budget.done();
  if (!unperturbed || unperturbed->status != "ok") {
    return {{"skipped", "the case's own hydro (" +
                            (hydro ? hydro->name() : "closure " + scene.closure) +
                            ") did not finish, so there is nothing to inject errors into"}};
  }
  const double each = std::max(unperturbed->cost.wall_seconds, 1e-3);
  const std::size_t per_eps = comparison_power_settings(*hydro, scene, {1.0}).size();
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
  const std::vector<AtlasSetting> settings = comparison_power_settings(*hydro, scene, epsilons);
  const std::vector<AtlasRun> hydro_runs =
      runner.run(settings, std::vector<double>(settings.size(), each));
  budget.spend(estimate_of(epsilons.size()));
  json power = comparison_power(*hydro, scene, *unperturbed, hydro_runs, particle_runs, epsilons);
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
  std::vector<double> injected_errors;  // the comparison power's eps grid
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
    scene.config = std::make_shared<const CaseConfig>(
        CaseConfig::from_string(scene.source.text, scene.source.origin, scene.sets));
    const CaseConfig& config = *scene.config;
    const HydroScene hydro = hydro_scene_from(config);
    scene.case_hydro = std::make_shared<const HydroScene>(hydro);
    scene.name = config.name();
    scene.particles = config.boolean("md.enabled");
    scene.bins = config.int_value("atlas.bins");
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
    injected_errors = config.reals("atlas.injected_errors");
    if (injected_errors.empty()) injected_errors = atlas::default_injected_errors();
    ladder = ladder_of(scene);
    // The compared times: the hydro's own output times, or those of a particle scene.
    const HydroScene aligned = atlas_hydro_scene(config, scene);
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

  // 2. The exact solutions, each one run; then the families with knobs: those whose runs go on
  // threads (the hydro) planned together, then the others (the particles, which call MPI) in
  // turn, the richest first.
  std::vector<AtlasRun> runs;
  std::vector<const ModelFamily*> threaded, in_turn;
  json skipped = json::array();
  for (const auto& rung : ladder) {
    if (!rung.skipped.empty()) continue;
    const ModelFamily& family = model_family(rung.model);
    if (family.kind() == FamilyKind::exact) {
      runs.push_back(runner.run_one(family.pilot(scene)));
    } else if (family.runs_on_threads()) {
      threaded.push_back(&family);
    } else {
      in_turn.insert(in_turn.begin(), &family);
    }
  }
  // The families that share the budget: each of those, and in a particle scene the comparison
  // power.
  BudgetShares budget(options.budget,
                      int(threaded.size() + in_turn.size() + (in_turn.empty() ? 0 : 1)));
  // 3. Each family's grid within its share: the pilot first (its cost calibrates the estimates),
  // then what the family plans first (its reference, its own contact), then the cheapest.
  auto plan = [&](const ModelFamily& family, const AtlasRun& pilot, double share, int parallel,
                  std::vector<AtlasSetting>& settings, std::vector<double>& estimates) {
    double planned_seconds = pilot.cost.wall_seconds;
    std::vector<AtlasSetting> grid = family.grid(scene);
    std::stable_sort(grid.begin(), grid.end(), [&](const AtlasSetting& a, const AtlasSetting& b) {
      const bool fa = family.plan_first(a, scene), fb = family.plan_first(b, scene);
      if (fa != fb) return fa;
      return family.estimate(a, pilot, scene) < family.estimate(b, pilot, scene);
    });
    for (const auto& s : grid) {
      if (s == pilot.setting) continue;
      const double e = family.estimate(s, pilot, scene);
      if ((planned_seconds + e) / parallel > share) {
        skipped.push_back(skipped_for_budget(s, e, share, options.budget));
        continue;
      }
      planned_seconds += e;
      settings.push_back(s);
      estimates.push_back(e);
    }
    budget.spend(planned_seconds / parallel);
    budget.done();
  };
  {
    std::vector<AtlasSetting> planned;
    std::vector<double> estimates;
    for (const ModelFamily* family : threaded) {
      const double share = budget.share();
      runs.push_back(runner.run_one(family->pilot(scene)));
      plan(*family, runs.back(), share, jobs, planned, estimates);
    }
    auto more = runner.run(planned, estimates);
    runs.insert(runs.end(), more.begin(), more.end());
  }
  if (interruption_signal()) return interrupted();
  for (const ModelFamily* family : in_turn) {
    const double share = budget.share();
    const AtlasRun pilot = runner.run_one(family->pilot(scene));
    runs.push_back(pilot);
    if (interruption_signal()) return interrupted();
    if (pilot.status == "refused") {  // the scene is not one this family takes: no grid
      skipped.push_back(
          {{"setting", setting_json(pilot.setting)},
           {"reason", "the pilot was refused, so is every setting: " + pilot.reason}});
      budget.done();
      continue;
    }
    std::vector<AtlasSetting> planned;
    std::vector<double> estimates;
    plan(*family, pilot, share, 1, planned, estimates);
    auto more = runner.run(planned, estimates);
    runs.insert(runs.end(), more.begin(), more.end());
    if (interruption_signal()) return interrupted();
  }

  // 4. References: each family's finest run that finished (of the case's own scene); the richest
  // family's is the reference of the model errors.
  auto finest_of = [&](const ModelFamily& family) -> const AtlasRun* {
    const AtlasRun* best = nullptr;
    for (const auto& r : runs) {
      if (r.setting.model != family.name() || r.status != "ok") continue;
      if (!family.may_be_reference(r.setting)) continue;
      if (!best || family.finer(r.setting, best->setting)) best = &r;
    }
    return best;
  };
  std::map<std::string, const AtlasRun*> own_reference;
  std::string richest;
  for (const auto& rung : ladder) {
    const ModelFamily& family = model_family(rung.model);
    if (family.kind() == FamilyKind::exact) continue;
    if (const AtlasRun* f = finest_of(family)) own_reference[rung.model] = f, richest = rung.model;
  }
  if (richest.empty()) {
    std::cerr << "granvv: error: atlas: no hydro or particle run finished, so there is no "
                 "reference to measure errors against\n";
    return 1;
  }
  const AtlasRun& reference = *own_reference[richest];
  const ModelFamily& reference_family = model_family(richest);
  const bool particle_reference = reference_family.kind() == FamilyKind::ensemble;
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
      if (!reference_family.coarser_neighbour(r.setting, reference.setting)) continue;
      for (const auto& [k, v] : observable_errors(r, reference, observables)) {
        convergence[k] = std::max(convergence.count(k) ? convergence[k] : 0.0, v.error);
      }
    }
  }

  // The comparison power: the case's own hydro with injected model errors, judged side by side
  // against every run of the reference engine (its ensemble sizes are the particle cost axis).
  json power = nullptr;
  if (particle_reference) {
    power = comparison_power_within(scene, runs, reference_family, injected_errors, budget, jobs,
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
    const auto rank = [](const std::string& m) { return ladder_rank(m); };
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

  // 6. Stability boundaries of each family with knobs to push, around the case's own setting.
  // A run's state against its own finest run is worked out once: from its numerical error for a
  // grid run, on arrival for a probe.
  json stability = json::array();
  for (const ModelFamily* family : threaded) {
    if (family->stability_pushes().empty() || !own_reference.count(family->name())) continue;
    const AtlasRun& ref = *own_reference[family->name()];
    auto classify = [&](const AtlasRun& r, const ObservableErrors& errors) -> std::string {
      if (r.status != "ok") return r.status;
      return largest(errors_of(errors)) > options.tolerance ? "error_above_tolerance" : "";
    };
    std::map<std::map<std::string, double>, std::string> state;  // knobs -> failure
    std::vector<const AtlasRun*> drawn_runs;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      if (runs[i].setting.model != family->name()) continue;
      if (state.emplace(runs[i].setting.knobs, classify(runs[i], numerical[i])).second) {
        drawn_runs.push_back(&runs[i]);
      }
    }
    std::vector<AtlasRun> probed;  // the boundary searches' runs, drawn on the map too
    probed.reserve(family->stability_pushes().size() * (kPushes + kRefinements + 1));
    auto state_of = [&](const AtlasSetting& s) {
      if (const auto it = state.find(s.knobs); it != state.end()) return it->second;
      probed.push_back(runner.run_one(s));
      drawn_runs.push_back(&probed.back());
      return state[s.knobs] =
                 classify(probed.back(), observable_errors(probed.back(), ref, observables));
    };
    const AtlasSetting own = family->case_setting(scene);
    json boundaries = json::array();
    for (const KnobPush& push : family->stability_pushes()) {
      bool integer = false;
      for (const KnobSpec& k : family->knobs()) {
        if (k.name == push.knob) integer = k.type == KnobSpec::Type::integer;
      }
      auto probe = [&](double knob) {
        if (interruption_signal()) return std::string("interrupted");
        return state_of(family->with_knob(own, push.knob, integer ? std::round(knob) : knob));
      };
      if (!state_of(own).empty()) {
        boundaries.push_back({{"knob", push.knob},
                              {"note",
                               "the case's own setting already fails against the "
                               "finest run; no boundary searched"}});
        continue;
      }
      const atlas::StabilityBoundary b = atlas::find_stability_boundary(
          own.knob(push.knob), push.factor, kPushes, kRefinements, probe);
      boundaries.push_back({{"knob", push.knob},
                            {"direction", push.factor > 1 ? "up" : "down"},
                            {"stable", b.stable},
                            {"failed", b.failure.empty() ? json(nullptr) : json(b.failed)},
                            {"failure", b.failure.empty() ? json(nullptr) : json(b.failure)},
                            {"probes", b.probes}});
    }
    auto knobs_json = [&](const AtlasSetting& s) {
      json j = family->setting_json(s);
      j.erase("model");
      return j;
    };
    json grid_points = json::array();
    for (const AtlasRun* r : drawn_runs) {
      const std::string& c = state.at(r->setting.knobs);
      json point = knobs_json(r->setting);
      point["state"] = c.empty() ? "ok" : c;
      grid_points.push_back(point);
    }
    stability.push_back({{"model", family->name()},
                         {"default", knobs_json(own)},
                         {"grid", grid_points},
                         {"boundaries", boundaries}});
  }
  // The DEM's stability and bias map of each family with contact knobs, against the richest
  // ensemble family without them (the hard disks).
  json dem = nullptr;
  for (const ModelFamily* family : in_turn) {
    if (!family->has_contact_map()) continue;
    const AtlasRun* hard = nullptr;
    for (const ModelFamily* other : in_turn) {  // richest first
      if (!hard && !other->has_contact_map() && own_reference.count(other->name())) {
        hard = own_reference[other->name()];
      }
    }
    dem = dem_map(*family, scene, runs, model_error, observables, hard, scene.t0_theory,
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
    if (model_family(r.setting.model).kind() == FamilyKind::ensemble && r.status == "ok") {
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
    const ModelStyle style = model_family(rung.model).style();
    ladder_rows.push_back({{"model", rung.model},
                           {"runs", rung.skipped.empty()},
                           {"reason", rung.skipped.empty() ? json(nullptr) : json(rung.skipped)},
                           {"style", {{"color", style.color}, {"marker", style.marker}}}});
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
