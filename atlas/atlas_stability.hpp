#pragma once
// The stability map of a family with knobs to push (docs/atlas.md, "Stability"): the state of
// each of its runs against its own finest run, and along each knob it declares
// (ModelFamily::stability_pushes) the boundary between the last setting that holds and the first
// that fails, found by pushing from the case's own setting and bisecting on a log scale.
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "atlas/atlas_analysis.hpp"
#include "atlas/atlas_runner.hpp"
#include "models/model_family.hpp"

namespace granvv::app {

// atlas.json's `stability` entry of the family; its probes are run by `runner` (and a signal
// marks the probes not made "interrupted").
nlohmann::json stability_map(const ModelFamily& family, const AtlasScene& scene,
                             const std::vector<AtlasRun>& runs,
                             const std::vector<ObservableErrors>& numerical, const AtlasRun& finest,
                             const std::vector<std::string>& observables, double tolerance,
                             AtlasRunner& runner);

}  // namespace granvv::app
