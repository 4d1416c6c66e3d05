// The stability map of a family (atlas/atlas_stability.hpp).
#include "atlas/atlas_stability.hpp"

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "atlas/atlas_judgement.hpp"
#include "atlas/stability_search.hpp"
#include "scene/interruption.hpp"

namespace granvv::app {
using nlohmann::json;

namespace {
// The knob is pushed by its factor at most kPushes times from the case's own setting, then the
// first failure is bisected kRefinements times on a log scale.
constexpr int kPushes = 6, kRefinements = 2;
}  // namespace

json stability_map(const ModelFamily& family, const AtlasScene& scene,
                   const std::vector<AtlasRun>& runs,
                   const std::vector<ObservableErrors>& numerical, const AtlasRun& finest,
                   const std::vector<std::string>& observables, double tolerance,
                   AtlasRunner& runner) {
  auto classify = [&](const AtlasRun& r, const ObservableErrors& errors) -> std::string {
    if (r.status != "ok") return r.status;
    return largest(errors_of(errors)) > tolerance ? "error_above_tolerance" : "";
  };
  std::map<std::map<std::string, double>, std::string> state;  // knobs -> failure
  std::vector<const AtlasRun*> drawn_runs;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (runs[i].setting.model != family.name()) continue;
    if (state.emplace(runs[i].setting.knobs, classify(runs[i], numerical[i])).second) {
      drawn_runs.push_back(&runs[i]);
    }
  }
  std::vector<AtlasRun> probed;  // the boundary searches' runs, drawn on the map too
  probed.reserve(family.stability_pushes().size() * (kPushes + kRefinements + 1));
  auto state_of = [&](const AtlasSetting& s) {
    if (const auto it = state.find(s.knobs); it != state.end()) return it->second;
    probed.push_back(runner.run_one(s));
    drawn_runs.push_back(&probed.back());
    return state[s.knobs] =
               classify(probed.back(), observable_errors(probed.back(), finest, observables));
  };
  const AtlasSetting own = family.case_setting(scene);
  json boundaries = json::array();
  for (const KnobPush& push : family.stability_pushes()) {
    bool integer = false;
    for (const KnobSpec& k : family.knobs()) {
      if (k.name == push.knob) integer = k.type == KnobSpec::Type::integer;
    }
    auto probe = [&](double knob) {
      if (interruption_signal()) return std::string("interrupted");
      return state_of(family.with_knob(own, push.knob, integer ? std::round(knob) : knob));
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
  json grid_points = json::array();
  for (const AtlasRun* r : drawn_runs) {
    const std::string& c = state.at(r->setting.knobs);
    json point = family.knobs_json(r->setting);
    point["state"] = c.empty() ? "ok" : c;
    grid_points.push_back(point);
  }
  return {{"model", family.name()},
          {"default", family.knobs_json(own)},
          {"grid", grid_points},
          {"boundaries", boundaries}};
}

}  // namespace granvv::app
