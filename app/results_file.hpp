#pragma once
// results.h5: the FieldSeries of the hydro run (snapshots at cell centres), its native
// Lagrangian arrays, the whole-mesh time series, theory references and the convergence
// study, with the resolved case as root attributes. Layout documented in README.md.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "app/hydro_scene.hpp"

namespace granvv::app {

struct RunMetadata {
  std::string case_name, version, config_toml;
  std::vector<std::pair<std::string, std::string>> config;  // flattened resolved keys
};

void write_results_file(const std::filesystem::path& file, const RunMetadata& meta,
                        const HydroScene& scene, const HydroOutcome& outcome);

}  // namespace granvv::app
