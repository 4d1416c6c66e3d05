#include "scene/initial_provenance.hpp"

#include <nlohmann/json.hpp>

#include "scene/input_fingerprint.hpp"

namespace granvv::app {

nlohmann::json file_provenance(const std::string& path) {
  std::error_code ec;
  const auto absolute = std::filesystem::absolute(path, ec);
  return {{"path", path},
          {"absolute_path", ec ? path : absolute.lexically_normal().string()},
          {"bytes", std::filesystem::file_size(path)},
          {"sha256", file_sha256(path)}};
}

nlohmann::json initial_provenance(const hydro::InitialParameters& initial) {
  nlohmann::json files = nlohmann::json::array();
  for (const auto& path : hydro::initial_files(initial)) files.push_back(file_provenance(path));
  return {{"type", initial.type}, {"files", files}};
}

}  // namespace granvv::app
