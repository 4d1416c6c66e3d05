#pragma once
// Where scenes come from: a path, a scene name in cases/, or the embedded default
// (cases/quickstart.toml compiled into the binary).
#include <filesystem>
#include <string>
#include <vector>

namespace granvv::app {

struct CaseSource {
  std::string text;    // the TOML text
  std::string origin;  // shown in messages: the file path, or "embedded:cases/quickstart.toml"
};

std::filesystem::path cases_directory();
// Empty name: the embedded default scene. Throws ConfigError if nothing matches.
CaseSource locate_case(const std::string& name_or_path);

struct SceneListing {
  std::string name, description, reference;
};
std::vector<SceneListing> list_scenes();

}  // namespace granvv::app
