#include "app/atlas_runs.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "app/atomic_file.hpp"
#include "app/case_config.hpp"
#include "app/compare_scene.hpp"
#include "app/hydro_scene.hpp"
#include "app/json_numbers.hpp"
#include "app/md_scene.hpp"
#include "app/model.hpp"
#include "compare/binned_energies.hpp"

namespace granvv::app {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Bumped whenever what a cached run holds changes, so that old cache files are not read.
constexpr int kCacheFormat = 1;

bool is_hydro(const AtlasSetting& s) {
  return s.model.rfind("hydro/", 0) == 0;
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

// How a hydro run ended, in the atlas's failure names (app/atlas_runs.hpp).
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

// The run's compared times, energies and fields from a model's result.
void take_result(const AtlasScene& scene, const fields::ModelResult& r, AtlasRun& run) {
  run.cost = r.cost;
  for (const auto& o : r.observables) {
    if (o.name.rfind("crossing_time_n", 0) == 0) run.crossing_times[o.name] = o.value;
  }
  if (!r.fields) return;
  fields::FieldSeries kept = fields::FieldSeries::on_bins(-0.5, 1.0, scene.bins);
  for (double t : scene.times) {
    for (const auto& s : r.fields->snapshots) {
      if (std::abs(s.t - t) > 1e-9 * std::max(1.0, t)) continue;
      fields::FieldSnapshot full = s;  // flow by inertia has no T, a 1D hydro may have no v_y
      if (full.T.empty()) full.T.assign(full.n.size(), 0.0);
      if (full.v_y.empty()) full.v_y.assign(full.n.size(), 0.0);
      const compare::EnergiesPerParticle e = compare::box_energies(full);
      run.times.push_back(t);
      run.thermal.push_back(s.T.empty() ? kNaN : e.thermal);
      run.flow.push_back(e.flow);
      kept.snapshots.push_back(s);
      break;
    }
  }
  run.fields = std::move(kept);
}

json series_json(const fields::FieldSeries& f) {
  json snaps = json::array();
  for (const auto& s : f.snapshots) {
    snaps.push_back({{"t", s.t}, {"n", s.n}, {"v_x", s.v_x}, {"v_y", s.v_y}, {"T", s.T}});
  }
  return {{"bins", f.bin_edges.size() - 1}, {"snapshots", snaps}};
}

fields::FieldSeries series_from_json(const json& j) {
  fields::FieldSeries f = fields::FieldSeries::on_bins(-0.5, 1.0, j["bins"].get<int>());
  const int bins = j["bins"].get<int>();
  for (const auto& s : j["snapshots"]) {
    fields::FieldSnapshot snap;
    snap.t = s["t"].get<double>();
    snap.label = "output";
    for (int b = 0; b < bins; ++b) snap.x.push_back(-0.5 + (b + 0.5) / bins);
    snap.n = s["n"].get<std::vector<double>>();
    snap.v_x = s["v_x"].get<std::vector<double>>();
    snap.v_y = s["v_y"].get<std::vector<double>>();
    snap.T = s["T"].get<std::vector<double>>();
    f.snapshots.push_back(std::move(snap));
  }
  return f;
}

// NaN is not JSON: absent values are null in the cache as in every output (docs/outputs.md).
json numbers(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(number_or_null(x));
  return a;
}
std::vector<double> numbers_from(const json& a) {
  std::vector<double> v;
  for (const auto& x : a) v.push_back(x.is_number() ? x.get<double>() : kNaN);
  return v;
}

json run_json(const AtlasRun& r) {
  json j = {{"format", kCacheFormat},
            {"status", r.status},
            {"reason", r.reason},
            {"wall_seconds", r.cost.wall_seconds},
            {"work", r.cost.work},
            {"work_unit", r.cost.work_unit},
            {"rejected_steps", r.rejected_steps},
            {"crossing_times", r.crossing_times},
            {"times", r.times},
            {"thermal", numbers(r.thermal)},
            {"flow", numbers(r.flow)}};
  j["fields"] = r.fields ? series_json(*r.fields) : json(nullptr);
  return j;
}

std::optional<AtlasRun> run_from_json(const json& j, const AtlasSetting& setting) {
  if (!j.is_object() || j.value("format", 0) != kCacheFormat) return std::nullopt;
  AtlasRun r;
  r.setting = setting;
  r.status = j["status"].get<std::string>();
  r.reason = j["reason"].get<std::string>();
  r.cost = {j["wall_seconds"].get<double>(), j["work"].get<double>(),
            j["work_unit"].get<std::string>()};
  r.rejected_steps = j["rejected_steps"].get<long long>();
  r.crossing_times = j["crossing_times"].get<std::map<std::string, double>>();
  r.times = j["times"].get<std::vector<double>>();
  r.thermal = numbers_from(j["thermal"]);
  r.flow = numbers_from(j["flow"]);
  if (!j["fields"].is_null()) r.fields = series_from_json(j["fields"]);
  r.cached = true;
  return r;
}

}  // namespace

std::string describe(const AtlasSetting& s) {
  if (!is_hydro(s)) return s.model;
  char knobs[96];
  std::snprintf(knobs, sizeof knobs, " cells=%d step_factor=%g", s.cells, s.step_factor);
  return s.model + knobs;
}

std::vector<std::string> setting_overrides(const AtlasScene& scene, const AtlasSetting& s) {
  std::vector<std::string> sets = scene.sets;
  if (!is_hydro(s)) return sets;
  sets.push_back("hydro.closure=" + toml_quoted(s.model.substr(6)));
  sets.push_back("hydro.cells=" + std::to_string(s.cells));
  sets.push_back("hydro.cfl=" + format_real(scene.case_cfl * s.step_factor));
  sets.push_back("hydro.dt_max=" + format_real(scene.case_dt_max * s.step_factor));
  sets.push_back("hydro.max_compression=" +
                 format_real(scene.case_max_compression * s.step_factor));
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
  std::string key = config->resolved_toml();
  key += "\n# atlas: " + setting.model + " bins " + std::to_string(scene.bins) + " times";
  for (double t : scene.times) key += " " + format_real(t);
  const fs::path cache_file = cache_dir / (text_hash(key) + ".json");
  {
    std::ifstream in(cache_file);
    if (in) {
      try {
        json j;
        in >> j;
        if (auto cached = run_from_json(j, setting)) return *cached;
      } catch (const std::exception&) {
        // an unreadable cache file is run again and rewritten
      }
    }
  }
  try {
    const HydroScene hydro = atlas_hydro_scene(*config, scene);
    if (is_hydro(setting)) {
      HydroModel model(hydro, scene.bins);
      const fields::ModelResult r = model.run();
      run.status = hydro_status(model.outcome());
      run.reason = model.outcome().run.stop_reason;
      run.rejected_steps = model.outcome().run.rejected_steps;
      take_result(scene, r, run);
    } else if (setting.model == "haff_ode") {
      take_result(scene, make_haff_model(hydro.physics, scene.times, scene.bins)->run(), run);
      run.status = "ok";
    } else {
      take_result(scene,
                  make_inertia_model(hydro.initial, hydro.physics, scene.times, scene.bins,
                                     scene.crossing_levels)
                      ->run(),
                  run);
      run.status = "ok";
    }
  } catch (const ConfigError& e) {
    run.status = "refused";
    run.reason = e.what();
    return run;
  }
  write_file_atomically(cache_file, run_json(run).dump() + "\n");
  return run;
}

}  // namespace granvv::app
