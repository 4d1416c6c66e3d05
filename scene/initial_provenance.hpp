#pragma once
// Provenance of a scene's initial state: the files its initial condition reads (a table, a
// previous run's results.h5), each with its SHA-256, for summary.json's "initial" block.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "hydro/initial_conditions.hpp"

namespace granvv::app {

// Lower-case hex SHA-256 of a file's bytes; throws std::runtime_error if it cannot be read.
std::string file_sha256(const std::filesystem::path& file);

// {"type": ..., "files": [{"path", "absolute_path", "bytes", "sha256"}, ...]}.
nlohmann::json initial_provenance(const hydro::InitialParameters& initial);

}  // namespace granvv::app
