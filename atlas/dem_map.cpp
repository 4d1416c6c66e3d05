#include "atlas/dem_map.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <tuple>

#include "atlas/recommendation.hpp"
#include "atlas/relative_bias.hpp"
#include "atlas/work_precision.hpp"
#include "scene/json_numbers.hpp"

namespace granvv::app {
using nlohmann::json;

namespace {

// A run's contact: its knobs other than the ensemble size, in the map's order.
std::tuple<double, double, double> contact_of(const AtlasSetting& s) {
  return {s.knob(kMaxOverlapKnob), s.knob(kStepsPerContactKnob), s.knob(kAdaptiveStiffnessKnob)};
}
json contact_json(const ModelFamily& family, const AtlasSetting& s) {
  json j = family.knobs_json(s);
  j.erase(kEnsembleKnob);
  return j;
}

double scalar(const AtlasRun& r, const std::string& name, bool error = false) {
  const auto& m = error ? r.scalar_errors : r.scalars;
  const auto it = m.find(name);
  return it == m.end() ? atlas::kNoValue : it->second;
}

// The bias of one scalar of run against the hard disks' as {bias, error} JSON (null: none).
void put_bias(json& point, const std::string& key, const AtlasRun& run, const AtlasRun* hard,
              const std::string& name) {
  const atlas::RelativeBias b =
      hard ? atlas::relative_bias(scalar(run, name), scalar(run, name, true), scalar(*hard, name),
                                  scalar(*hard, name, true))
           : atlas::RelativeBias{atlas::kNoValue, atlas::kNoValue};
  point[key + "_bias"] = number_or_null(b.value);
  point[key + "_bias_error"] = number_or_null(b.error);
}

}  // namespace

json dem_map(const ModelFamily& family, const AtlasScene& scene, const std::vector<AtlasRun>& runs,
             const std::vector<ObservableErrors>& model_error,
             const std::vector<std::string>& observables, const AtlasRun* hard_disks,
             double t0_theory, double tolerance, double sigmas) {
  // The largest ensemble at each contact setting.
  std::map<std::tuple<double, double, double>, std::size_t> chosen;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const AtlasSetting& s = runs[i].setting;
    if (s.model != family.name() || runs[i].status == "refused" ||
        runs[i].status == "interrupted") {
      continue;
    }
    const auto key = contact_of(s);
    const auto it = chosen.find(key);
    if (it == chosen.end() ||
        s.knob(kEnsembleKnob) > runs[it->second].setting.knob(kEnsembleKnob)) {
      chosen[key] = i;
    }
  }
  json points = json::array();
  std::map<std::tuple<double, double, double>, std::string> state_at;
  for (const auto& [key, i] : chosen) {
    const AtlasRun& r = runs[i];
    std::string state = r.status;
    if (r.status == "ok") {
      state = "ok";
      const ObservableErrors t0_only =
          hard_disks ? observable_errors(r, *hard_disks, {"haff_t0"}) : ObservableErrors{};
      const auto t0e = t0_only.find("haff_t0");
      if (t0e != t0_only.end() &&
          !atlas::within_tolerance(t0e->second.error, t0e->second.reference_error, tolerance,
                                   sigmas)) {
        state = "t0_bias_above_tolerance";
      } else if (!atlas::adequate({r.cost.wall_seconds, errors_of(model_error[i]),
                                   reference_errors_of(model_error[i])},
                                  observables, tolerance, sigmas)) {
        state = "error_above_tolerance";
      }
    }
    state_at[key] = state;
    json p = family.knobs_json(r.setting);
    p.update({{"state", state},
              {"wall_seconds", r.cost.wall_seconds},
              {"work", r.cost.work},
              {"work_unit", r.cost.work_unit},
              {"haff_t0", number_or_null(scalar(r, "haff_t0"))},
              {"haff_t0_error", number_or_null(scalar(r, "haff_t0", true))},
              {"compressibility", number_or_null(scalar(r, "compressibility"))},
              {"compressibility_error", number_or_null(scalar(r, "compressibility", true))}});
    put_bias(p, "t0", r, hard_disks, "haff_t0");
    put_bias(p, "pressure", r, hard_disks, "pressure");
    put_bias(p, "compressibility", r, hard_disks, "compressibility");
    p["t0_bias_kinetic_theory"] = number_or_null(
        atlas::relative_bias(scalar(r, "haff_t0"), scalar(r, "haff_t0", true), t0_theory, 0.0)
            .value);
    points.push_back(p);
  }
  // Boundaries along each knob from the case's own contact: the grid's points in the push
  // direction, the last that is ok and the first that is not.
  json boundaries = json::array();
  const AtlasSetting case_setting = family.case_setting(scene);
  const auto own = contact_of(case_setting);
  const auto [case_overlap, case_steps, case_adaptive] = own;
  for (const bool overlap_knob : {true, false}) {
    const char* knob = overlap_knob ? kMaxOverlapKnob : kStepsPerContactKnob;
    json b = {{"knob", knob}, {"direction", overlap_knob ? "up" : "down"}};
    if (!state_at.count(own)) {
      b["note"] = "the case's own contact did not run";
    } else if (state_at[own] != "ok") {
      b["note"] = "the case's own contact already fails (" + state_at[own] +
                  "); no boundary along the grid";
    } else {
      std::vector<std::pair<double, std::string>> line;  // knob value, state; push order
      for (const auto& [key, state] : state_at) {
        const auto& [ov, spc, adaptive] = key;
        if (adaptive != case_adaptive) continue;
        if (overlap_knob && spc == case_steps && ov >= case_overlap) line.push_back({ov, state});
        if (!overlap_knob && ov == case_overlap && spc <= case_steps) line.push_back({spc, state});
      }
      std::sort(line.begin(), line.end());
      if (!overlap_knob) std::reverse(line.begin(), line.end());
      double stable = line.front().first;
      json failed = nullptr, failure = nullptr;
      for (const auto& [value, state] : line) {
        if (state != "ok") {
          failed = value, failure = state;
          break;
        }
        stable = value;
      }
      b.update({{"stable", stable}, {"failed", failed}, {"failure", failure}});
    }
    boundaries.push_back(b);
  }
  json against = nullptr;
  if (hard_disks) {
    against = {
        {"setting", describe(hard_disks->setting)},
        {"haff_t0", number_or_null(scalar(*hard_disks, "haff_t0"))},
        {"haff_t0_error", number_or_null(scalar(*hard_disks, "haff_t0", true))},
        {"pressure", number_or_null(scalar(*hard_disks, "pressure"))},
        {"compressibility", number_or_null(scalar(*hard_disks, "compressibility"))},
        {"compressibility_error", number_or_null(scalar(*hard_disks, "compressibility", true))}};
  }
  return {{"against", against},
          {"t0_kinetic_theory", number_or_null(t0_theory)},
          {"default", contact_json(family, case_setting)},
          {"points", points},
          {"boundaries", boundaries}};
}

}  // namespace granvv::app
