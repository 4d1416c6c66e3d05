#include "atlas/atlas_runs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <variant>

#include "atlas/work_precision.hpp"
#include "compare/binned_energies.hpp"
#include "compare/ensemble_statistics.hpp"
#include "compare/model_comparison.hpp"
#include "hydro/validity_monitors.hpp"
#include "models/compare_scene.hpp"
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
// Bumped whenever what a cached run holds changes, so that old cache files are not read.
constexpr int kCacheFormat = 2;

// A resolved case's text without its comment lines (where the case came from, the --set list)
// and without one of its tables: a run does not depend on the [atlas] table (the grids and what
// is judged), so another grid or budget finds the runs it shares in the cache.
std::string without_table(const std::string& toml, const std::string& table) {
  std::string out, line;
  bool skipping = false;
  for (std::size_t start = 0; start < toml.size();) {
    std::size_t end = toml.find('\n', start);
    if (end == std::string::npos) end = toml.size();
    line = toml.substr(start, end - start);
    start = end + 1;
    if (!line.empty() && line[0] == '[') skipping = line == "[" + table + "]";
    if (!skipping && (line.empty() || line[0] != '#')) out += line + "\n";
  }
  return out;
}

// FNV-1a, 64 bit: names a cache file after the text of its resolved case (not a security hash).
std::string text_hash(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char out[17];
  std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
  return out;
}

}  // namespace

AtlasSetting hydro_setting(const std::string& model, int cells, double step_factor) {
  AtlasSetting s;
  s.model = model;
  s.cells = cells;
  s.step_factor = step_factor;
  return s;
}

bool is_hydro(const std::string& model) {
  return model.rfind("hydro/", 0) == 0;
}
bool is_particles(const std::string& model) {
  return model.rfind("particles/", 0) == 0;
}
bool is_lammps(const std::string& model) {
  return model == "particles/lammps";
}

HydroScene atlas_hydro_scene(const CaseConfig& config, const AtlasScene& scene) {
  HydroScene hydro = hydro_scene_from(config);
  hydro.convergence_cells.clear();
  if (scene.particles) {
    const auto md = md_scene_from(config, hydro);
    fields::FieldSeries times;  // align_hydro_with_md reads only the snapshots' times
    for (double t : config.reals("md.output_times")) {
      fields::FieldSnapshot s;
      s.t = t;
      times.snapshots.push_back(s);
    }
    align_hydro_with_md(hydro, md->spec.scene, config.real("md.t_end"), times);
  }
  return hydro;
}

namespace {

// How a hydro run ended, in the atlas's failure names (atlas/atlas_runs.hpp).
std::string hydro_status(const HydroOutcome& out) {
  const auto& run = out.run;
  switch (run.status) {
    case hydro::RunStatus::completed:
      return "ok";
    case hydro::RunStatus::singularity:
      return run.stop_reason.find("min_cell_width") != std::string::npos ? "unresolved_singularity"
                                                                         : "ok";
    case hydro::RunStatus::closure_limit:
      return "closure_limit";
    case hydro::RunStatus::failed:
      if (run.stop_reason.find("admissible") != std::string::npos) return "inadmissible_step";
      if (run.stop_reason.find("non-finite") != std::string::npos) return "non_finite";
      return "step_underflow";
  }
  return "failed";
}

// The compared times as a series without fields, to pair a model's snapshots with.
fields::FieldSeries compared_times(const AtlasScene& scene) {
  fields::FieldSeries times;
  for (double t : scene.times) {
    fields::FieldSnapshot s;
    s.t = t;
    times.snapshots.push_back(s);
  }
  return times;
}

compare::EnergiesPerParticle energies(const fields::FieldSnapshot& s) {
  fields::FieldSnapshot full = s;  // flow by inertia has no T, a 1D hydro may have no v_y
  if (full.T.empty()) full.T.assign(full.n.size(), 0.0);
  if (full.v_y.empty()) full.v_y.assign(full.n.size(), 0.0);
  return compare::box_energies(full);
}

// The run's compared times, energies, fields and scalars from a model's result.
void take_result(const AtlasScene& scene, const fields::ModelResult& r, AtlasRun& run) {
  run.cost = r.cost;
  for (const auto& o : r.observables) {
    run.scalars[o.name] = o.value;
    run.scalar_errors[o.name] = o.standard_error;
  }
  if (!r.fields) return;
  fields::FieldSeries kept = fields::FieldSeries::on_bins(-0.5, 1.0, scene.bins);
  for (const auto& [i, j] : compare::common_snapshots(compared_times(scene), *r.fields)) {
    const fields::FieldSnapshot& s = r.fields->snapshots[j];
    const compare::EnergiesPerParticle e = energies(s);
    run.times.push_back(scene.times[i]);
    run.thermal.push_back(s.T.empty() ? kNoValue : e.thermal);
    run.flow.push_back(e.flow);
    run.thermal_error.push_back(kNoValue);
    run.flow_error.push_back(kNoValue);
    kept.snapshots.push_back(s);
  }
  run.fields = std::move(kept);
}

// The ensemble standard errors of the box energies at the kept times: the scatter of the
// members' own box energies (each member's snapshot j is the mean's snapshot j,
// compare/ensemble_fields.hpp). Energies per particle are the same in MD and scaled units.
void take_energy_errors(const AtlasScene& scene, const fields::ModelResult& r,
                        const MdOutcome& outcome, AtlasRun& run) {
  if (!r.fields) return;
  std::size_t k = 0;
  for (const auto& [i, j] : compare::common_snapshots(compared_times(scene), *r.fields)) {
    (void)i;
    std::vector<std::vector<double>> thermal, flow;
    for (const auto& member : outcome.runs) {
      if (j >= member.fields.snapshots.size()) continue;
      const compare::EnergiesPerParticle e = energies(member.fields.snapshots[j]);
      thermal.push_back({e.thermal});
      flow.push_back({e.flow});
    }
    if (!thermal.empty()) {
      run.thermal_error[k] = compare::ensemble_statistics(thermal).standard_error[0];
      run.flow_error[k] = compare::ensemble_statistics(flow).standard_error[0];
    }
    ++k;
  }
}

// An engine without a contact virial in the box pressure (the event-driven one: its collisional
// transfer is the series value collision_virial_pressure, the mean over the interval since the
// previous sample) gets its pressure here, as the kinetic n0 T plus that transfer, with T the
// mean of the interval's two ends (the gas cools during it): P/(n0 T0) and P/(n0 T) averaged
// over each member's samples, then their mean and standard error over the members.
void take_collisional_pressure(const MdScene& md, const MdOutcome& outcome, AtlasRun& run) {
  if (std::isfinite(run.scalars["pressure"])) return;
  const double n0 = md.spec.scene.number_density();
  std::vector<std::vector<double>> pressure, compressibility;
  for (const auto& member : outcome.runs) {
    const auto& series = member.series;
    const std::vector<double>* transfer = nullptr;
    for (const auto& [name, values] : series.engine) {
      if (name == "collision_virial_pressure") transfer = &values;
    }
    if (!transfer || transfer->size() != series.T.size() || series.T.size() < 2) return;
    double p = 0.0, z = 0.0;
    for (std::size_t s = 1; s < series.T.size(); ++s) {
      const double T = 0.5 * (series.T[s - 1] + series.T[s]);
      p += (n0 * T + (*transfer)[s]) / n0;
      z += 1.0 + (*transfer)[s] / (n0 * T);
    }
    pressure.push_back({p / double(series.T.size() - 1)});
    compressibility.push_back({z / double(series.T.size() - 1)});
  }
  const auto p = compare::ensemble_statistics(pressure);
  const auto z = compare::ensemble_statistics(compressibility);
  run.scalars["pressure"] = p.mean[0], run.scalar_errors["pressure"] = p.standard_error[0];
  run.scalars["compressibility"] = z.mean[0];
  run.scalar_errors["compressibility"] = z.standard_error[0];
}

// A deterministic model too quick to time in one run (below kShortestTimed) is run again, up to
// kTimingRepeats times in all, and costs its fastest run: in a run of microseconds one context
// switch or page fault would otherwise decide which model is the cheapest.
constexpr double kShortestTimed = 1e-3;
constexpr int kTimingRepeats = 50;
void time_by_fastest(fields::ModelCost& cost, const std::function<fields::ModelCost()>& rerun) {
  double spent = cost.wall_seconds;
  for (int k = 1; k < kTimingRepeats && spent < kShortestTimed; ++k) {
    const double again = rerun().wall_seconds;
    spent += again;
    cost.wall_seconds = std::min(cost.wall_seconds, again);
  }
}

// The event-driven engine's share of collisions whose restitution its collapse rules changed
// (md_bridge/hard_disk_collision.hpp), as its summary detail and as the atlas keeps it.
constexpr const char* kCollapseRuleDetail = "collapse_rule.fraction_changed";
constexpr const char* kCollapseRuleScalar = "collapse_rule_fraction_changed";

// A finished particle run whose collapse rules changed more than the limit of its collisions
// is no longer the hard-disk gas of constant r (docs/atlas.md): judged here, after the cache,
// so that the limit (an [atlas] key) can change without running it again.
void judge_collapse_rule(AtlasRun& run, double limit) {
  const auto f = run.scalars.find(kCollapseRuleScalar);
  if (run.status != "ok" || f == run.scalars.end() || !(f->second > limit)) return;
  run.status = "collapse_rule_active";
  run.reason = "the collapse rules changed the restitution of " + format_real(f->second) +
               " of all collisions, above atlas.collapse_rule_limit = " + format_real(limit);
}

// A particle run that threw, in the atlas's failure names (atlas/atlas_runs.hpp).
std::string particle_failure(const std::string& what) {
  if (what.find("misses md.restitution") != std::string::npos) return "restitution_check_missed";
  if (what.find("event-rate runaway") != std::string::npos) return "event_rate_runaway";
  return "engine_failed";
}

// NaN is not JSON: absent values are null in the cache as in every output (docs/outputs.md).
json numbers(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(number_or_null(x));
  return a;
}
std::vector<double> numbers_from(const json& a) {
  std::vector<double> v;
  for (const auto& x : a) v.push_back(x.is_number() ? x.get<double>() : kNoValue);
  return v;
}

json series_json(const fields::FieldSeries& f) {
  json snaps = json::array();
  for (const auto& s : f.snapshots) {
    json snap = {{"t", s.t}};
    for (const auto& c : fields::field_columns()) {
      if (!(s.*c.values).empty()) snap[c.name] = numbers(s.*c.values);
      if (c.standard_error && !(s.*c.standard_error).empty()) {
        snap[std::string(c.name) + "_stderr"] = numbers(s.*c.standard_error);
      }
    }
    snaps.push_back(snap);
  }
  return {{"bins", f.bin_edges.size() - 1}, {"snapshots", snaps}};
}

fields::FieldSeries series_from_json(const json& j) {
  fields::FieldSeries f = fields::FieldSeries::on_bins(-0.5, 1.0, j["bins"].get<int>());
  for (const auto& s : j["snapshots"]) {
    fields::FieldSnapshot snap;
    snap.t = s["t"].get<double>();
    snap.label = "output";
    for (const auto& c : fields::field_columns()) {
      if (s.contains(c.name)) snap.*c.values = numbers_from(s[c.name]);
      const std::string e = std::string(c.name) + "_stderr";
      if (c.standard_error && s.contains(e)) snap.*c.standard_error = numbers_from(s[e]);
    }
    f.snapshots.push_back(std::move(snap));
  }
  return f;
}

json run_json(const AtlasRun& r) {
  json j = {{"format", kCacheFormat},
            {"status", r.status},
            {"reason", r.reason},
            {"wall_seconds", r.cost.wall_seconds},
            {"work", r.cost.work},
            {"work_unit", r.cost.work_unit},
            {"rejected_steps", r.rejected_steps},
            {"times", r.times},
            {"thermal", numbers(r.thermal)},
            {"flow", numbers(r.flow)},
            {"thermal_error", numbers(r.thermal_error)},
            {"flow_error", numbers(r.flow_error)}};
  json scalars = json::object(), errors = json::object();
  for (const auto& [k, v] : r.scalars) scalars[k] = number_or_null(v);
  for (const auto& [k, v] : r.scalar_errors) errors[k] = number_or_null(v);
  j["scalars"] = scalars;
  j["scalar_errors"] = errors;
  j["fields"] = r.fields ? series_json(*r.fields) : json(nullptr);
  j["monitors"] = r.monitor_crossings;
  return j;
}

std::optional<AtlasRun> run_from_json(const json& j, const AtlasSetting& setting) {
  if (!j.is_object() || j.value("format", 0) != kCacheFormat) return std::nullopt;
  // A hydro cached before its monitors were kept is run again (hydro runs are cheap).
  if (is_hydro(setting.model) && !j.contains("monitors")) return std::nullopt;
  AtlasRun r;
  r.setting = setting;
  r.status = j["status"].get<std::string>();
  r.reason = j["reason"].get<std::string>();
  r.cost = {j["wall_seconds"].get<double>(), j["work"].get<double>(),
            j["work_unit"].get<std::string>()};
  r.rejected_steps = j["rejected_steps"].get<long long>();
  for (const auto& [k, v] : j["scalars"].items())
    r.scalars[k] = v.is_number() ? v.get<double>() : kNoValue;
  for (const auto& [k, v] : j["scalar_errors"].items()) {
    r.scalar_errors[k] = v.is_number() ? v.get<double>() : kNoValue;
  }
  r.times = j["times"].get<std::vector<double>>();
  r.thermal = numbers_from(j["thermal"]);
  r.flow = numbers_from(j["flow"]);
  r.thermal_error = numbers_from(j["thermal_error"]);
  r.flow_error = numbers_from(j["flow_error"]);
  if (!j["fields"].is_null()) r.fields = series_from_json(j["fields"]);
  if (j.contains("monitors"))
    r.monitor_crossings = j["monitors"].get<std::map<std::string, double>>();
  r.cached = true;
  return r;
}

}  // namespace

std::string describe(const AtlasSetting& s) {
  char knobs[160] = "";
  if (is_hydro(s.model)) {
    std::snprintf(knobs, sizeof knobs, " cells=%d step_factor=%g", s.cells, s.step_factor);
  } else if (is_lammps(s.model)) {
    std::snprintf(knobs, sizeof knobs,
                  " ensemble=%d max_overlap=%g steps_per_contact=%d adaptive_stiffness=%s",
                  s.ensemble, s.max_overlap, s.steps_per_contact,
                  s.adaptive_stiffness ? "true" : "false");
  } else if (is_particles(s.model)) {
    std::snprintf(knobs, sizeof knobs, " ensemble=%d", s.ensemble);
  }
  std::string text = s.model + knobs;
  if (s.particle_factor != 1.0) text += " particle_factor=" + format_real(s.particle_factor);
  if (!s.injected.empty()) text += " " + s.injected + "=" + format_real(s.injected_factor);
  return text;
}

json setting_json(const AtlasSetting& s) {
  json j = {{"model", s.model}};
  if (is_hydro(s.model)) j["cells"] = s.cells, j["step_factor"] = s.step_factor;
  if (is_particles(s.model)) j["ensemble"] = s.ensemble;
  if (is_particles(s.model) && !is_lammps(s.model)) j["particle_factor"] = s.particle_factor;
  if (is_lammps(s.model)) {
    j["max_overlap"] = s.max_overlap;
    j["steps_per_contact"] = s.steps_per_contact;
    j["adaptive_stiffness"] = s.adaptive_stiffness;
  }
  if (!s.injected.empty()) j[s.injected] = s.injected_factor;
  return j;
}

std::vector<std::string> setting_overrides(const AtlasScene& scene, const AtlasSetting& s) {
  std::vector<std::string> sets = scene.sets;
  if (is_hydro(s.model)) {
    sets.push_back("hydro.closure=" + toml_quoted(s.model.substr(6)));
    sets.push_back("hydro.cells=" + std::to_string(s.cells));
    sets.push_back("hydro.cfl=" + format_real(scene.case_cfl * s.step_factor));
    sets.push_back("hydro.dt_max=" + format_real(scene.case_dt_max * s.step_factor));
    sets.push_back("hydro.max_compression=" +
                   format_real(scene.case_max_compression * s.step_factor));
    if (!s.injected.empty()) {
      sets.push_back("hydro." + s.injected + "=" + format_real(s.injected_factor));
    }
  } else if (is_particles(s.model)) {
    sets.push_back("md.engine=" + toml_quoted(s.model.substr(10)));
    sets.push_back("md.ensemble=" + std::to_string(s.ensemble));
    if (s.particle_factor != 1.0) {
      sets.push_back("md.box_width=" + format_real(scene.case_box_width * s.particle_factor));
      if (scene.case_particles > 0) {
        sets.push_back("md.particles=" + std::to_string(std::llround(double(scene.case_particles) *
                                                                     s.particle_factor)));
      }
    }
    if (is_lammps(s.model)) {
      sets.push_back("md.max_overlap=" + format_real(s.max_overlap));
      sets.push_back("md.steps_per_contact=" + std::to_string(s.steps_per_contact));
      sets.push_back(std::string("md.adaptive_stiffness=") +
                     (s.adaptive_stiffness ? "true" : "false"));
    }
  }
  return sets;
}

AtlasRun run_atlas_setting(const AtlasScene& scene, const AtlasSetting& setting,
                           const fs::path& cache_dir) {
  AtlasRun run;
  run.setting = setting;
  std::optional<CaseConfig> config;
  try {
    config = CaseConfig::from_string(scene.source.text, scene.source.origin,
                                     setting_overrides(scene, setting));
  } catch (const ConfigError& e) {
    run.status = "refused";
    run.reason = e.what();
    return run;
  }
  std::string key = without_table(config->resolved_toml(), "atlas");
  key += "\n# atlas: " + setting.model + " bins " + std::to_string(scene.bins) + " times";
  for (double t : scene.times) key += " " + format_real(t);
  const fs::path cache_file = cache_dir / (text_hash(key) + ".json");
  {
    std::ifstream in(cache_file);
    if (in) {
      try {
        json j;
        in >> j;
        if (auto cached = run_from_json(j, setting)) {
          judge_collapse_rule(*cached, scene.collapse_rule_limit);
          return *cached;
        }
      } catch (const std::exception&) {
        // an unreadable cache file is run again and rewritten
      }
    }
  }
  try {
    if (is_particles(setting.model)) {
      const std::optional<MdScene> md = md_scene_from(*config, hydro_scene_from(*config));
      const auto engine = make_engine(*md, "");
      // A signal stops the run at its next sample (scene/interruption.hpp).
      ParticleModel model(*md, *engine, [](int, const md::MdProgress&) { stop_if_interrupted(); });
      fields::ModelResult r = model.run();
      // A soft-contact engine reaches a compared time to within its time step (the largest,
      // at the end of a run with adaptive stiffness): its snapshot stands for that time.
      const double slack = md->spec.scene.scaled_time(engine->time_resolution());
      for (auto& snap : r.fields->snapshots) {
        for (double t : scene.times) {
          if (std::abs(snap.t - t) <= slack) snap.t = t;
        }
      }
      take_result(scene, r, run);
      take_energy_errors(scene, r, model.outcome(), run);
      take_collisional_pressure(*md, model.outcome(), run);
      for (const auto& d : model.outcome().engine_details) {
        if (d.key == kCollapseRuleDetail && std::holds_alternative<double>(d.value))
          run.scalars[kCollapseRuleScalar] = std::get<double>(d.value);
      }
      run.status = "ok";
    } else {
      const HydroScene hydro = atlas_hydro_scene(*config, scene);
      if (is_hydro(setting.model)) {
        HydroModel model(hydro, scene.bins);
        const fields::ModelResult r = model.run();
        run.status = hydro_status(model.outcome());
        run.reason = model.outcome().run.stop_reason;
        run.rejected_steps = model.outcome().run.rejected_steps;
        for (const auto& d : hydro::monitor_definitions()) {
          const auto& crossing = model.outcome().run.validity.first_crossing[int(d.monitor)];
          if (crossing) run.monitor_crossings[d.name] = crossing->time;
        }
        take_result(scene, r, run);
        time_by_fastest(run.cost, [&] { return HydroModel(hydro, scene.bins).run().cost; });
      } else if (setting.model == "haff_ode") {
        auto haff = [&] { return make_haff_model(hydro.physics, scene.times, scene.bins)->run(); };
        take_result(scene, haff(), run);
        time_by_fastest(run.cost, [&] { return haff().cost; });
        run.status = "ok";
      } else {
        auto inertia = [&] {
          return make_inertia_model(hydro.initial, hydro.physics, scene.times, scene.bins,
                                    scene.crossing_levels)
              ->run();
        };
        take_result(scene, inertia(), run);
        time_by_fastest(run.cost, [&] { return inertia().cost; });
        run.status = "ok";
      }
    }
  } catch (const ConfigError& e) {
    run.status = "refused";
    run.reason = e.what();
    return run;
  } catch (const Interrupted& e) {
    run.status = "interrupted";
    run.reason = e.what();
    return run;
  } catch (const std::runtime_error& e) {  // the particle engine failed: kept, it is an outcome
    if (!is_particles(setting.model)) throw;
    run = AtlasRun{};
    run.setting = setting;
    run.status = particle_failure(e.what());
    run.reason = e.what();
  }
  write_file_atomically(cache_file, run_json(run).dump() + "\n");
  judge_collapse_rule(run, scene.collapse_rule_limit);
  return run;
}

}  // namespace granvv::app
