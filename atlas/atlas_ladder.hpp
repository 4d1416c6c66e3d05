#pragma once
// The ladder an atlas runs (docs/atlas.md): every family and why it does not apply, and its runs
// within the budget: the exact solutions once; each family with knobs at its pilot, then its
// grid, cheapest first, as far as its share of the budget goes.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "atlas/atlas_budget.hpp"
#include "atlas/atlas_runner.hpp"
#include "models/model_family.hpp"

namespace granvv::app {

struct LadderRung {
  std::string model;
  std::string skipped;  // why it does not apply (empty: it runs)
};

// Every family in the ladder's order, and why it does not apply; the Haff ODE runs on every
// scene, even where it cannot follow the fields, because it costs microseconds and the atlas
// shows how far it is.
std::vector<LadderRung> ladder_of(const AtlasScene& scene);

struct LadderRuns {
  std::vector<AtlasRun> runs;
  // The families with knobs that ran: those whose runs go on threads (the hydro), and the
  // others (the particles, which call MPI), richest first.
  std::vector<const ModelFamily*> threaded, in_turn;
  nlohmann::json skipped = nlohmann::json::array();  // settings left out for the budget
  BudgetShares budget{0.0, 1};  // what is left of --budget for the comparison power
};

// The ladder's runs within budget_seconds (--budget). A signal stops it after the run in
// flight (scene/interruption.hpp tells).
LadderRuns run_ladder(const AtlasScene& scene, const std::vector<LadderRung>& ladder,
                      AtlasRunner& runner, double budget_seconds);

}  // namespace granvv::app
