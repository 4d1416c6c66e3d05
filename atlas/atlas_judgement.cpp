// How an atlas judges its runs (atlas/atlas_judgement.hpp).
#include "atlas/atlas_judgement.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "atlas/work_precision.hpp"
#include "scene/json_numbers.hpp"

namespace granvv::app {
using atlas::kNoValue;
using nlohmann::json;

namespace {

// A run is over-resolved when its numerical error is below this fraction of its model error:
// refining it further cannot bring it closer to the richest model.
constexpr double kOverResolved = 0.1;

// A family's finest finished run of the case's own scene.
const AtlasRun* finest_of(const ModelFamily& family, const std::vector<AtlasRun>& runs) {
  const AtlasRun* best = nullptr;
  for (const auto& r : runs) {
    if (r.setting.model != family.name() || r.status != "ok") continue;
    if (!family.may_be_reference(r.setting)) continue;
    if (!best || family.finer(r.setting, best->setting)) best = &r;
  }
  return best;
}

// The Pareto front of each observable over the runs (cost: wall seconds; error: model error).
std::map<std::string, std::vector<bool>> pareto_fronts(const std::vector<AtlasRun>& runs,
                                                       const AtlasErrors& errors,
                                                       const std::vector<std::string>& names) {
  std::map<std::string, std::vector<bool>> fronts;
  for (const auto& name : names) {
    std::vector<double> cost, error;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const auto it = errors.model[i].find(name);
      cost.push_back(runs[i].status == "ok" ? runs[i].cost.wall_seconds : kNoValue);
      error.push_back(it == errors.model[i].end() ? kNoValue : it->second.error);
    }
    fronts[name] = atlas::pareto_front(cost, error);
  }
  return fronts;
}

}  // namespace

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

AtlasReference find_reference(const std::vector<LadderRung>& ladder,
                              const std::vector<AtlasRun>& runs,
                              std::vector<std::string>& observables) {
  AtlasReference ref;
  for (const auto& rung : ladder) {
    const ModelFamily& family = model_family(rung.model);
    if (family.kind() == FamilyKind::exact) continue;
    if (const AtlasRun* f = finest_of(family, runs)) {
      ref.own[rung.model] = f, ref.run = f, ref.family = &family;
    }
  }
  if (!ref.run) return ref;
  // What the reference itself does not give (a density level the peak never reached, the
  // crossing times the particles do not report) cannot be judged: it is dropped from the
  // observables, and atlas.json says so.
  const std::vector<std::string> given = provided_observables(*ref.run, observables);
  for (const auto& name : observables) {
    if (std::find(given.begin(), given.end(), name) == given.end()) ref.not_judged.push_back(name);
  }
  observables = given;
  // The reference's own error: a discretised family's from its neighbours one step coarser in
  // each knob; an ensemble's is its standard error (the hard disks have no other knob).
  ref.statistical = statistical_errors(*ref.run, observables);
  if (ref.family->kind() == FamilyKind::ensemble) {
    ref.convergence = ref.statistical;
    return ref;
  }
  for (const auto& r : runs) {
    if (r.setting.model != ref.family->name() || r.status != "ok" || &r == ref.run) continue;
    if (!ref.family->coarser_neighbour(r.setting, ref.run->setting)) continue;
    for (const auto& [k, v] : observable_errors(r, *ref.run, observables)) {
      ref.convergence[k] = std::max(ref.convergence.count(k) ? ref.convergence[k] : 0.0, v.error);
    }
  }
  return ref;
}

AtlasErrors atlas_errors(const std::vector<AtlasRun>& runs, const AtlasReference& ref,
                         const std::vector<std::string>& observables) {
  AtlasErrors e;
  e.numerical.resize(runs.size());
  e.model.resize(runs.size());
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const AtlasRun& r = runs[i];
    if (r.status != "ok") continue;
    if (const auto own = ref.own.find(r.setting.model); own != ref.own.end()) {
      e.numerical[i] = observable_errors(r, *own->second, observables);
    }
    if (&r == ref.run) {
      for (const auto& [k, v] : ref.convergence) {
        e.model[i][k] = {v, ref.statistical.count(k) ? ref.statistical.at(k) : kNoValue};
      }
    } else {
      e.model[i] = observable_errors(r, *ref.run, observables);
    }
    e.candidates.push_back(
        {r.cost.wall_seconds, errors_of(e.model[i]), reference_errors_of(e.model[i])});
    e.candidate_run.push_back(i);
  }
  return e;
}

json recommendation_json(const std::vector<AtlasRun>& runs, const AtlasErrors& errors,
                         const std::vector<std::string>& observables, double tolerance,
                         double sigmas, std::optional<std::size_t>& best_run) {
  const auto& candidates = errors.candidates;
  const std::optional<std::size_t> best =
      atlas::cheapest_adequate(candidates, observables, tolerance, sigmas);
  best_run.reset();
  if (!best) {
    return {{"tolerance", tolerance},
            {"sigmas", sigmas},
            {"model", nullptr},
            {"reason", "no run meets the tolerance on every observable"}};
  }
  best_run = errors.candidate_run[*best];
  const AtlasRun& r = runs[*best_run];
  json recommendation = {
      {"tolerance", tolerance},
      {"sigmas", sigmas},
      {"model", r.setting.model},
      {"setting", setting_json(r.setting)},
      {"cost",
       {{"wall_seconds", r.cost.wall_seconds},
        {"work", r.cost.work},
        {"work_unit", r.cost.work_unit}}},
      {"error", errors_json(errors_of(errors.model[*best_run]))},
      {"reference_statistical_error", errors_json(reference_errors_of(errors.model[*best_run]))}};
  // The next rung up: the cheapest adequate run of a richer model, else the cheapest of the
  // next richer model that ran.
  json next = nullptr;
  for (int pass = 0; pass < 2 && next.is_null(); ++pass) {
    const AtlasRun* pick = nullptr;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      const AtlasRun& c = runs[errors.candidate_run[k]];
      if (ladder_rank(c.setting.model) <= ladder_rank(r.setting.model)) continue;
      if (pass == 0 && !atlas::adequate(candidates[k], observables, tolerance, sigmas)) continue;
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
  return recommendation;
}

json ladder_timeline(const std::vector<LadderRung>& ladder, const std::vector<AtlasRun>& runs,
                     const AtlasReference& ref, const std::vector<std::string>& observables,
                     double tolerance, double sigmas) {
  json timeline = json::array();
  for (const auto& rung : ladder) {
    if (!rung.skipped.empty()) continue;
    const auto own = ref.own.find(rung.model);
    const AtlasRun* best_run = own != ref.own.end() ? own->second : nullptr;
    for (const auto& r : runs) {
      if (!best_run && r.setting.model == rung.model && r.status == "ok") best_run = &r;
    }
    if (!best_run) continue;
    const std::vector<std::string> judged = provided_observables(*best_run, observables);
    const std::vector<ObservableError> e = error_over_time(*best_run, *ref.run, judged, sigmas);
    json until = nullptr, exceeded = nullptr;
    for (std::size_t i = 0; i < e.size(); ++i) {
      if (!atlas::within_tolerance(e[i].error, e[i].reference_error, tolerance, sigmas)) {
        exceeded = ref.run->times[i];
        break;
      }
      until = ref.run->times[i];
    }
    json errs = json::array(), reference_errs = json::array();
    for (const auto& x : e) {
      errs.push_back(number_or_null(x.error));
      reference_errs.push_back(number_or_null(x.reference_error));
    }
    timeline.push_back({{"model", rung.model},
                        {"setting", setting_json(best_run->setting)},
                        {"judged", judged},
                        {"times", ref.run->times},
                        {"error", errs},
                        {"reference_statistical_error", reference_errs},
                        {"adequate_until", until},
                        {"exceeded_at", exceeded},
                        {"monitors", best_run->monitor_crossings}});
  }
  return timeline;
}

json run_rows(const std::vector<AtlasRun>& runs, const AtlasErrors& errors,
              const AtlasReference& ref, const std::vector<std::string>& observables) {
  auto fronts = pareto_fronts(runs, errors, observables);
  json rows = json::array();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const AtlasRun& r = runs[i];
    json pareto = json::array();
    for (const auto& name : observables) {
      if (fronts[name][i]) pareto.push_back(name);
    }
    const double num = largest(errors_of(errors.numerical[i]));
    const double mod = largest(errors_of(errors.model[i]));
    json row = setting_json(r.setting);
    row.update({{"status", r.status},
                {"reason", r.reason},
                {"wall_seconds", r.cost.wall_seconds},
                {"work", r.cost.work},
                {"work_unit", r.cost.work_unit},
                {"rejected_steps", r.rejected_steps},
                {"cached", r.cached},
                {"numerical_error", errors_json(errors_of(errors.numerical[i]))},
                {"model_error", errors_json(errors_of(errors.model[i]))},
                {"reference_statistical_error", errors_json(reference_errors_of(errors.model[i]))},
                {"over_resolved", r.setting.model != ref.family->name() && std::isfinite(num) &&
                                      std::isfinite(mod) && num < kOverResolved * mod},
                {"pareto", pareto}});
    if (model_family(r.setting.model).kind() == FamilyKind::ensemble && r.status == "ok") {
      json sc = json::object();
      for (const auto& [k, v] : r.scalars) {
        const auto e = r.scalar_errors.find(k);
        sc[k] = {{"value", number_or_null(v)},
                 {"error", number_or_null(e == r.scalar_errors.end() ? kNoValue : e->second)}};
      }
      row["scalars"] = sc;
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace granvv::app
