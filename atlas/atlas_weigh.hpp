#pragma once
// An atlas from its set-up to its document (docs/atlas.md): the ladder run within the budget,
// the references, the comparison power, every run's errors, the recommendation, the stability
// and DEM maps and the ladder timeline, as atlas.json holds them.
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "atlas/atlas_judgement.hpp"
#include "atlas/atlas_runner.hpp"
#include "atlas/atlas_setup.hpp"

namespace granvv::app {

struct AtlasRequest {
  double tolerance = 1e-2;  // relative
  double budget = 300.0;    // wall seconds for the runs
};

struct WeighedLadder {
  nlohmann::json document;  // atlas.json, but for the wall time of the whole command
  std::vector<AtlasRun> runs;
  AtlasErrors errors;
  std::vector<std::string> observables;  // the judged ones
  std::optional<std::size_t> best;       // the recommended run
};

// nullopt when a signal stopped it (the runs made stay in the runner's cache). Throws
// std::runtime_error when no family with knobs finished a run: there is no reference.
std::optional<WeighedLadder> weigh_ladder(const AtlasSetup& setup, const AtlasRequest& request,
                                          AtlasRunner& runner);

}  // namespace granvv::app
