#pragma once
// summary.json: the contract other tools read (docs/outputs.md). Numbers are numbers; results
// a scene does not have are null.
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "scene/hydro_scene.hpp"

namespace granvv::app {

nlohmann::json hydro_summary(const HydroScene& scene, const HydroOutcome& outcome);
// hydro.validity: per monitor (hydro/validity_monitors.hpp) whether it applies, its threshold,
// its first crossing (value, time, place; null when never crossed) and its largest value.
nlohmann::json validity_json(const hydro::ValidityRecord& validity);

// The text of summary.json (or sweep.json): indented, with any byte that is not UTF-8
// replaced, so that writing a summary never throws.
std::string summary_text(const nlohmann::json& summary);

}  // namespace granvv::app
