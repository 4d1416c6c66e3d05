// An atlas from its set-up to its document (atlas/atlas_weigh.hpp).
#include "atlas/atlas_weigh.hpp"

#include "atlas/atlas_power.hpp"
#include "atlas/atlas_stability.hpp"
#include "atlas/dem_map.hpp"
#include "scene/interruption.hpp"

namespace granvv::app {
using nlohmann::json;

namespace {

json ladder_rows(const std::vector<LadderRung>& ladder) {
  json rows = json::array();
  for (const auto& rung : ladder) {
    const ModelStyle style = model_family(rung.model).style();
    rows.push_back({{"model", rung.model},
                    {"runs", rung.skipped.empty()},
                    {"reason", rung.skipped.empty() ? json(nullptr) : json(rung.skipped)},
                    {"style", {{"color", style.color}, {"marker", style.marker}}}});
  }
  return rows;
}

// The reference as atlas.json gives it. Converged only where its own error was measured and is
// within the tolerance: an error nobody measured (no neighbour ran) does not count as small.
// Unmeasured, converged_to_tolerance is null and converged_reason says why.
json reference_json(const AtlasReference& ref, double tolerance) {
  bool converged = !ref.convergence.empty();
  for (const auto& [k, v] : ref.convergence) converged &= v <= tolerance;
  const bool ensemble = ref.family->kind() == FamilyKind::ensemble;
  const bool measured = !ref.convergence.empty();
  return {{"setting", setting_json(ref.run->setting)},
          {"convergence", errors_json(ref.convergence)},
          {"statistical_error", errors_json(ref.statistical)},
          {"converged_to_tolerance", measured ? json(converged) : json(nullptr)},
          {"converged_reason",
           measured ? json(nullptr)
                    : json("not measured: no neighbour of the reference one step coarser ran "
                           "within the budget, so its own error is unknown")},
          {"how", ensemble ? "the reference's ensemble standard error (relative; a "
                             "particle ensemble has no discretisation knob)"
                           : "largest difference to its neighbours one step coarser in "
                             "each knob: an upper bound of its own error"}};
}

}  // namespace

std::optional<WeighedLadder> weigh_ladder(const AtlasSetup& setup, const AtlasRequest& request,
                                          AtlasRunner& runner) {
  const AtlasScene& scene = setup.scene;
  const std::vector<LadderRung> ladder = ladder_of(scene);
  LadderRuns ran = run_ladder(scene, ladder, runner, request.budget);
  if (interruption_signal()) return std::nullopt;
  WeighedLadder out;
  out.observables = setup.observables;
  const AtlasReference ref = find_reference(ladder, ran.runs, out.observables);
  if (!ref.run) {
    throw std::runtime_error(
        "no hydro or particle run finished, so there is no reference to measure errors against");
  }
  // The comparison power: the case's own hydro with injected model errors, judged side by side
  // against every run of the reference engine (its ensemble sizes are the particle cost axis).
  json power = nullptr;
  if (ref.family->kind() == FamilyKind::ensemble) {
    power = comparison_power_within_budget(scene, ran.runs, *ref.family, setup.injected_errors,
                                           ran.budget, runner.jobs(), runner, request.budget);
    if (interruption_signal()) return std::nullopt;
  }
  out.errors = atlas_errors(ran.runs, ref, out.observables);
  const json recommendation = recommendation_json(ran.runs, out.errors, out.observables,
                                                  request.tolerance, scene.sigmas, out.best);
  json stability = json::array();
  for (const ModelFamily* family : ran.threaded) {
    const auto finest = ref.own.find(family->name());
    if (family->stability_pushes().empty() || finest == ref.own.end()) continue;
    stability.push_back(stability_map(*family, scene, ran.runs, out.errors.numerical,
                                      *finest->second, out.observables, request.tolerance, runner));
  }
  // The DEM's stability and bias map of each family with contact knobs, against the richest
  // ensemble family without them (the hard disks).
  json dem = nullptr;
  for (const ModelFamily* family : ran.in_turn) {
    if (!family->has_contact_map()) continue;
    const AtlasRun* hard = nullptr;
    for (const ModelFamily* other : ran.in_turn) {  // richest first
      const auto own = ref.own.find(other->name());
      if (!hard && !other->has_contact_map() && own != ref.own.end()) hard = own->second;
    }
    dem = dem_map(*family, scene, ran.runs, out.errors.model, out.observables, hard,
                  scene.t0_theory, request.tolerance, scene.sigmas);
  }
  out.document = {{"recommendation", recommendation},
                  {"case", scene.name},
                  {"granvv_version", GRANVV_VERSION},
                  {"status", "ok"},
                  {"tolerance", request.tolerance},
                  {"sigmas", scene.sigmas},
                  {"budget_seconds", request.budget},
                  {"jobs", runner.jobs()},
                  {"observables", out.observables},
                  {"observables_not_judged",
                   {{"names", ref.not_judged},
                    {"why",
                     "the reference run does not give them (a crossing level its peak "
                     "density never reached, or a crossing time of the particles)"}}},
                  {"times", scene.times},
                  {"ladder", ladder_rows(ladder)},
                  {"reference", reference_json(ref, request.tolerance)},
                  {"runs", run_rows(ran.runs, out.errors, ref, out.observables)},
                  {"stability", stability},
                  {"dem_map", dem},
                  {"timeline", ladder_timeline(ladder, ran.runs, ref, out.observables,
                                               request.tolerance, scene.sigmas)},
                  {"comparison_power", power},
                  {"skipped", ran.skipped},
                  {"runs_made", runner.made()},
                  {"run_seconds", runner.spent()}};
  out.runs = std::move(ran.runs);
  return out;
}

}  // namespace granvv::app
