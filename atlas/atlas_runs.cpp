#include "atlas/atlas_runs.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "atlas/work_precision.hpp"
#include "models/model_family.hpp"
#include "scene/atomic_file.hpp"
#include "scene/case_config.hpp"
#include "scene/input_fingerprint.hpp"
#include "scene/interruption.hpp"
#include "scene/json_numbers.hpp"

namespace granvv::app {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using atlas::kNoValue;
// Bumped whenever what a cached run holds changes, so that old cache files are not read.
constexpr int kCacheFormat = 3;

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

namespace {

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

bool is_number_or_null(const json& x) {
  return x.is_number() || x.is_null();
}

json transport_json(const std::optional<AtlasTransportFit>& t) {
  if (!t) return nullptr;
  return {{"coefficient", t->coefficient},
          {"factor", number_or_null(t->factor)},
          {"error", number_or_null(t->error)},
          {"chi2", number_or_null(t->chi2)},
          {"degrees_of_freedom", t->degrees_of_freedom},
          {"at_grid_edge", t->at_grid_edge},
          {"wall_seconds", t->wall_seconds},
          {"failure", t->failure}};
}

AtlasTransportFit transport_from_json(const json& j) {
  auto number = [&](const char* key) {
    return j[key].is_number() ? j[key].get<double>() : kNoValue;
  };
  AtlasTransportFit t;
  t.coefficient = j["coefficient"].get<std::string>();
  t.factor = number("factor");
  t.error = number("error");
  t.chi2 = number("chi2");
  t.degrees_of_freedom = j["degrees_of_freedom"].get<int>();
  t.at_grid_edge = j["at_grid_edge"].get<bool>();
  t.wall_seconds = j["wall_seconds"].get<double>();
  t.failure = j["failure"].get<std::string>();
  return t;
}

// "" if the entry's transport fit is what transport_json writes; `needed`: the family keeps a
// fit for this scene, so a finished run cached without one (before fits were kept) runs again.
std::string transport_problem(const json& j, bool needed) {
  if (!j.contains("transport") || j["transport"].is_null()) {
    return needed && j["status"] == "ok" ? "cached without its transport fit" : "";
  }
  const json& t = j["transport"];
  if (!t.is_object()) return "transport is not an object";
  for (const char* key : {"coefficient", "failure"}) {
    if (!t.contains(key) || !t[key].is_string())
      return std::string("transport.") + key + " is not a text";
  }
  for (const char* key : {"factor", "error", "chi2"}) {
    if (!t.contains(key) || !is_number_or_null(t[key]))
      return std::string("transport.") + key + " is not a number";
  }
  if (!t.contains("wall_seconds") || !t["wall_seconds"].is_number())
    return "transport.wall_seconds is not a number";
  if (!t.contains("degrees_of_freedom") || !t["degrees_of_freedom"].is_number_integer())
    return "transport.degrees_of_freedom is not an integer";
  if (!t.contains("at_grid_edge") || !t["at_grid_edge"].is_boolean())
    return "transport.at_grid_edge is not true or false";
  return "";
}

json run_json(const AtlasRun& r, const json& inputs) {
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
  j["transport"] = transport_json(r.transport);
  j["inputs"] = inputs;
  return j;
}

// "" if `a` is an array of numbers or nulls (of `size` entries unless size < 0).
std::string numbers_problem(const json& j, const char* key, long long size = -1) {
  if (!j.contains(key) || !j[key].is_array()) return std::string(key) + " is not a list";
  for (const auto& x : j[key]) {
    if (!is_number_or_null(x)) return std::string(key) + " holds a value that is not a number";
  }
  if (size >= 0 && (long long)j[key].size() != size)
    return std::string(key) + " has " + std::to_string(j[key].size()) + " entries, not " +
           std::to_string(size);
  return "";
}

std::string object_of_numbers_problem(const json& j, const char* key) {
  if (!j.contains(key) || !j[key].is_object()) return std::string(key) + " is not an object";
  for (const auto& [k, v] : j[key].items()) {
    if (!is_number_or_null(v)) return std::string(key) + "." + k + " is not a number";
  }
  return "";
}

// "" if a snapshot of the entry's fields is what run_json writes for the atlas's bins.
std::string snapshot_problem(const json& s, double t, int bins) {
  if (!s.is_object() || !s.contains("t") || !s["t"].is_number())
    return "a snapshot without its time";
  if (s["t"].get<double>() != t) return "a snapshot at another time than its times list";
  for (const auto& c : fields::field_columns()) {
    for (const std::string& name : {std::string(c.name), std::string(c.name) + "_stderr"}) {
      if (!s.contains(name)) continue;
      if (!s[name].is_array() || s[name].size() != std::size_t(bins))
        return "the snapshot column " + name + " does not have one value per bin";
      for (const auto& x : s[name]) {
        if (!is_number_or_null(x)) return "the snapshot column " + name + " holds a non-number";
      }
    }
  }
  return "";
}

// Why a cache entry is not a run that run_json wrote for this scene ("" if it is): every value
// of the right type, the energies one per compared time, the times among the scene's and the
// fields one snapshot per time on the scene's bins, and the transport fit where the family keeps
// one. An edited or damaged entry is run again.
std::string entry_problem(const json& j, const AtlasScene& scene, bool needs_transport) {
  if (!j.is_object()) return "not a JSON object";
  if (!j.contains("format") || !j["format"].is_number_integer() ||
      j["format"].get<long long>() != kCacheFormat)
    return "another cache format";
  if (!j.contains("inputs")) return "no fingerprint of its inputs";
  for (const char* key : {"status", "reason", "work_unit"}) {
    if (!j.contains(key) || !j[key].is_string()) return std::string(key) + " is not a text";
  }
  for (const char* key : {"wall_seconds", "work"}) {
    if (!j.contains(key) || !j[key].is_number()) return std::string(key) + " is not a number";
  }
  if (!j.contains("rejected_steps") || !j["rejected_steps"].is_number_integer())
    return "rejected_steps is not an integer";
  if (auto p = numbers_problem(j, "times"); !p.empty()) return p;
  const json& times = j["times"];
  if (times.size() > scene.times.size()) return "more times than the atlas compares";
  for (const auto& t : times) {
    if (!t.is_number() ||
        std::find(scene.times.begin(), scene.times.end(), t.get<double>()) == scene.times.end())
      return "a time the atlas does not compare";
  }
  const auto n = (long long)times.size();
  for (const char* key : {"thermal", "flow", "thermal_error", "flow_error"}) {
    if (auto p = numbers_problem(j, key, n); !p.empty()) return p;
  }
  for (const char* key : {"scalars", "scalar_errors"}) {
    if (auto p = object_of_numbers_problem(j, key); !p.empty()) return p;
  }
  // A run cached before its monitors were kept is run again.
  if (auto p = object_of_numbers_problem(j, "monitors"); !p.empty()) return p;
  if (auto p = transport_problem(j, needs_transport); !p.empty()) return p;
  if (!j.contains("fields")) return "fields is missing";
  const json& f = j["fields"];
  if (f.is_null()) return n == 0 ? "" : "times without fields";
  if (!f.is_object() || !f.contains("bins") || !f["bins"].is_number_integer() ||
      f["bins"].get<long long>() != scene.bins)
    return "fields not on the atlas's " + std::to_string(scene.bins) + " bins";
  if (!f.contains("snapshots") || !f["snapshots"].is_array() ||
      (long long)f["snapshots"].size() != n)
    return "fields without one snapshot per time";
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (auto p = snapshot_problem(f["snapshots"][k], times[k].get<double>(), scene.bins);
        !p.empty())
      return p;
  }
  return "";
}

// The run of an entry that entry_problem accepted.
AtlasRun run_from_json(const json& j, const AtlasSetting& setting) {
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
  for (const auto& [k, v] : j["monitors"].items())
    r.monitor_crossings[k] = v.is_number() ? v.get<double>() : kNoValue;
  if (j.contains("transport") && !j["transport"].is_null()) {
    r.transport = transport_from_json(j["transport"]);
  }
  r.cached = true;
  return r;
}

}  // namespace

AtlasRun run_atlas_setting(const AtlasScene& scene, const AtlasSetting& setting,
                           const fs::path& cache_dir) {
  const ModelFamily& family = model_family(setting.model);
  AtlasRun run;
  run.setting = setting;
  std::optional<CaseConfig> config;
  try {
    config = setting_case(scene, setting);
  } catch (const ConfigError& e) {
    run.status = "refused";
    run.reason = e.what();
    return run;
  }
  // The run's inputs: its resolved case (no [atlas] table) and every file it reads. The cache
  // file is named by both, and holds them, so that a changed file is a new run.
  const json inputs = input_fingerprint(*config, {"atlas"});
  std::string key = without_table(config->resolved_toml(), "atlas");
  key += "\n# atlas: " + setting.model + " bins " + std::to_string(scene.bins) + " times";
  for (double t : scene.times) key += " " + format_real(t);
  for (const auto& file : inputs["files"])
    key += "\n# file " + file["path"].get<std::string>() + " " + file["sha256"].get<std::string>();
  const fs::path cache_file = cache_dir / (text_hash(key) + ".json");
  if (std::ifstream in(cache_file); in) {
    const json j = json::parse(in, nullptr, false);
    std::string problem =
        j.is_discarded() ? "not JSON" : entry_problem(j, scene, family.keeps_transport_fit(scene));
    if (problem.empty()) {
      const std::string changed = fingerprint_difference(j["inputs"], inputs);
      if (!changed.empty()) problem = "made from other inputs: " + changed;
    }
    if (problem.empty()) {
      try {  // entry_problem checked every value read; a type it missed is a damaged entry
        AtlasRun cached = run_from_json(j, setting);
        family.judge(scene, cached);
        return cached;
      } catch (const json::exception& e) {
        problem = std::string("a value of another type: ") + e.what();
      }
    }
    run.cache_note = "the cache entry " + cache_file.string() + " is not used (" + problem +
                     "): the setting runs again";
  }
  try {
    family.run(scene, *config, run);
  } catch (const ConfigError& e) {
    run.status = "refused";
    run.reason = e.what();
    return run;
  } catch (const Interrupted& e) {
    run.status = "interrupted";
    run.reason = e.what();
    return run;
  }
  write_file_atomically(cache_file, run_json(run, inputs).dump() + "\n");
  family.judge(scene, run);
  return run;
}

}  // namespace granvv::app
