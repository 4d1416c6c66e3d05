#pragma once
// summary.json: the contract other tools read (docs/outputs.md). Numbers are numbers; results
// a scene does not have are null.
#include <nlohmann/json.hpp>

#include "app/hydro_scene.hpp"

namespace granvv::app {

nlohmann::json hydro_summary(const HydroScene& scene, const HydroOutcome& outcome);

}  // namespace granvv::app
