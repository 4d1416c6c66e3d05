// The ladder's runs within the budget (atlas/atlas_ladder.hpp).
#include "atlas/atlas_ladder.hpp"

#include <algorithm>

#include "scene/case_schema.hpp"
#include "scene/interruption.hpp"

namespace granvv::app {
using nlohmann::json;

namespace {

// A family's grid within its share: the pilot first (its cost calibrates the estimates), then
// what the family plans first (its reference, its own contact), then the cheapest. Runs on
// threads share the wall time over the `parallel` jobs.
void plan(const AtlasScene& scene, const ModelFamily& family, const AtlasRun& pilot, double share,
          int parallel, double budget_seconds, LadderRuns& out, std::vector<AtlasSetting>& settings,
          std::vector<double>& estimates) {
  double planned_seconds = pilot.cost.wall_seconds;
  struct Planned {
    AtlasSetting setting;
    bool first;
    double estimate;
  };
  std::vector<Planned> grid;
  const ModelFamily::CostEstimate estimate = family.estimate(pilot, scene);
  for (auto& s : family.grid(scene)) {
    const bool first = family.plan_first(s, scene);
    const double e = estimate(s);
    grid.push_back({std::move(s), first, e});
  }
  std::stable_sort(grid.begin(), grid.end(), [](const Planned& a, const Planned& b) {
    if (a.first != b.first) return a.first;
    return a.estimate < b.estimate;
  });
  for (const Planned& p : grid) {
    if (p.setting == pilot.setting) continue;
    if ((planned_seconds + p.estimate) / parallel > share) {
      out.skipped.push_back(skipped_for_budget(p.setting, p.estimate, share, budget_seconds));
      continue;
    }
    planned_seconds += p.estimate;
    settings.push_back(p.setting);
    estimates.push_back(p.estimate);
  }
  out.budget.spend(planned_seconds / parallel);
  out.budget.done();
}

}  // namespace

json skipped_for_budget(const AtlasSetting& s, double estimate, double share, double budget) {
  return {{"setting", setting_json(s)},
          {"estimate_seconds", estimate},
          {"reason", "its estimated " + format_real(estimate) + " s would pass the share of " +
                         s.model + " in the budget (" + format_real(share) + " s of --budget " +
                         format_real(budget) + ")"}};
}

std::vector<LadderRung> ladder_of(const AtlasScene& scene) {
  std::vector<LadderRung> rungs;
  for (const ModelFamily* family : model_families()) {
    rungs.push_back({family->name(), family->not_applicable(scene).value_or("")});
  }
  return rungs;
}

LadderRuns run_ladder(const AtlasScene& scene, const std::vector<LadderRung>& ladder,
                      AtlasRunner& runner, double budget_seconds) {
  LadderRuns out;
  for (const auto& rung : ladder) {
    if (!rung.skipped.empty()) continue;
    const ModelFamily& family = model_family(rung.model);
    if (family.kind() == FamilyKind::exact) {
      out.runs.push_back(runner.run_one(family.pilot(scene)));
    } else if (family.runs_on_threads()) {
      out.threaded.push_back(&family);
    } else {
      out.in_turn.insert(out.in_turn.begin(), &family);
    }
  }
  // The families that share the budget: each of those, and in a particle scene the comparison
  // power.
  out.budget = BudgetShares(budget_seconds, int(out.threaded.size() + out.in_turn.size() +
                                                (out.in_turn.empty() ? 0 : 1)));
  // The families on threads: each pilot, then their grids planned together and run together.
  {
    std::vector<AtlasSetting> planned;
    std::vector<double> estimates;
    for (const ModelFamily* family : out.threaded) {
      const double share = out.budget.share();
      out.runs.push_back(runner.run_one(family->pilot(scene)));
      plan(scene, *family, out.runs.back(), share, runner.jobs(), budget_seconds, out, planned,
           estimates);
    }
    auto more = runner.run(planned, estimates);
    out.runs.insert(out.runs.end(), more.begin(), more.end());
  }
  if (interruption_signal()) return out;
  // The others one family at a time: its pilot, then its grid.
  for (const ModelFamily* family : out.in_turn) {
    const double share = out.budget.share();
    const AtlasRun pilot = runner.run_one(family->pilot(scene));
    out.runs.push_back(pilot);
    if (interruption_signal()) return out;
    if (pilot.status == "refused") {  // the scene is not one this family takes: no grid
      out.skipped.push_back(
          {{"setting", setting_json(pilot.setting)},
           {"reason", "the pilot was refused, so is every setting: " + pilot.reason}});
      out.budget.done();
      continue;
    }
    std::vector<AtlasSetting> planned;
    std::vector<double> estimates;
    plan(scene, *family, pilot, share, 1, budget_seconds, out, planned, estimates);
    auto more = runner.run(planned, estimates);
    out.runs.insert(out.runs.end(), more.begin(), more.end());
    if (interruption_signal()) return out;
  }
  return out;
}

}  // namespace granvv::app
