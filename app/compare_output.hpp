#pragma once
// A comparison's outputs: the `compare` block of summary.json and the /compare group of
// results.h5 (read by scripts/report.py).
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "models/compare_scene.hpp"

namespace granvv::app {

nlohmann::json compare_summary(const CompareScene& scene, const HydroScene& hydro,
                               const HydroOutcome& hydro_out, const MdScene& md,
                               const MdOutcome& md_out, const CompareOutcome& out);

// One closure's entry of compare.closures (compare.closures = [...]): its compare block as above
// and its own hydro block (hydro_summary, with its validity monitors).
nlohmann::json closure_comparison_summary(const CompareScene& scene, const HydroScene& hydro,
                                          const HydroOutcome& hydro_out, const MdScene& md,
                                          const MdOutcome& md_out, const CompareOutcome& out);

// Adds the group `root` (/compare, or /compare/closures/<name> of one closure) to an existing
// results.h5.
void write_compare_results(const std::filesystem::path& file, const CompareScene& scene,
                           const MdScene& md, const CompareOutcome& out,
                           const std::string& root = "/compare");

}  // namespace granvv::app
