#pragma once
// Provenance of a scene's initial state: the files its initial condition reads (a table, a
// previous run's results.h5), each with its SHA-256, for summary.json's "initial" block.
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "hydro/initial_conditions.hpp"

namespace granvv::app {

// One file a run read: {"path", "absolute_path", "bytes", "sha256"} (the SHA-256 of
// scene/input_fingerprint.hpp).
nlohmann::json file_provenance(const std::string& path);

// {"type": ..., "files": [file_provenance of each file, ...]}.
nlohmann::json initial_provenance(const hydro::InitialParameters& initial);

}  // namespace granvv::app
