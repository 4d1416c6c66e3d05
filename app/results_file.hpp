#pragma once
// results.h5: the resolved case as root attributes, and the hydro's group: its FieldSeries (on
// its cells), its native Lagrangian arrays, the whole-mesh time series, theory references and
// the convergence study. Layout in docs/outputs.md.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "scene/hydro_scene.hpp"

namespace granvv::app {

struct RunMetadata {
  std::string case_name, version, config_toml;
  std::vector<std::pair<std::string, std::string>> config;  // flattened resolved keys
};

// Creates (or truncates) the file with the root attributes; every model's group is added to it.
void create_results_file(const std::filesystem::path& file, const RunMetadata& meta);
// The hydro's group at `root`: /hydro, or /hydro_closures/<name> for a further closure of a
// comparison (compare.closures).
void write_hydro_results(const std::filesystem::path& file, const HydroScene& scene,
                         const HydroOutcome& outcome, const std::string& root = "/hydro");
// An empty group (a parent of per-closure groups).
void create_group(const std::filesystem::path& file, const std::string& path);

}  // namespace granvv::app
