#pragma once
// How an atlas judges its runs (docs/atlas.md, "What it measures"): the references (each
// family's finest run, the richest family's for the model errors), every run's numerical and
// model errors, the Pareto fronts, the recommendation with its next rung, the ladder timeline,
// and the atlas.json row of each run.
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "atlas/atlas_analysis.hpp"
#include "atlas/atlas_ladder.hpp"
#include "atlas/recommendation.hpp"

namespace granvv::app {

struct AtlasReference {
  std::map<std::string, const AtlasRun*> own;  // each family's finest finished run
  const AtlasRun* run = nullptr;               // the richest family's: the reference
  const ModelFamily* family = nullptr;
  std::vector<std::string> not_judged;  // observables the reference does not give
  // The reference's own error per observable: its statistical error (an ensemble's standard
  // error), and its convergence (a discretised family's largest difference to its neighbours one
  // step coarser; an ensemble's statistical error again).
  std::map<std::string, double> statistical, convergence;
};

// The references of the ladder's runs; run is null when no family with knobs finished. The
// observables the reference does not give are moved from `observables` to not_judged.
AtlasReference find_reference(const std::vector<LadderRung>& ladder,
                              const std::vector<AtlasRun>& runs,
                              std::vector<std::string>& observables);

struct AtlasErrors {
  std::vector<ObservableErrors> numerical, model;  // per run
  std::vector<atlas::Candidate> candidates;        // the finished runs
  std::vector<std::size_t> candidate_run;          // their index in the runs
};
AtlasErrors atlas_errors(const std::vector<AtlasRun>& runs, const AtlasReference& reference,
                         const std::vector<std::string>& observables);

// atlas.json `recommendation`: the cheapest adequate run at the tolerance and its next rung up;
// best is its index in the runs.
nlohmann::json recommendation_json(const std::vector<AtlasRun>& runs, const AtlasErrors& errors,
                                   const std::vector<std::string>& observables, double tolerance,
                                   double sigmas, std::optional<std::size_t>& best);

// atlas.json `timeline`: how long each family's best run stays within the tolerance.
nlohmann::json ladder_timeline(const std::vector<LadderRung>& ladder,
                               const std::vector<AtlasRun>& runs, const AtlasReference& reference,
                               const std::vector<std::string>& observables, double tolerance,
                               double sigmas);

// atlas.json `runs`: each run's setting, status, cost, errors, Pareto membership, whether it is
// over-resolved and, for an ensemble, its scalars with their errors.
nlohmann::json run_rows(const std::vector<AtlasRun>& runs, const AtlasErrors& errors,
                        const AtlasReference& reference,
                        const std::vector<std::string>& observables);

// Per observable name.
nlohmann::json errors_json(const std::map<std::string, double>& errors);
// The largest, NaN for none.
double largest(const std::map<std::string, double>& errors);

}  // namespace granvv::app
