#include "scene/case_catalog.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>

#include "embedded_cases.hpp"
#include "scene/case_config.hpp"
#include "scene/data_directory.hpp"

namespace granvv::app {
namespace fs = std::filesystem;

fs::path cases_directory() {
  if (const char* env = std::getenv("GRANVV_CASES_DIR")) return env;
  return data_directory() / "cases";
}

CaseSource locate_case(const std::string& name) {
  if (name.empty()) return {kQuickstartToml, "embedded:cases/quickstart.toml"};
  fs::path path = name;
  std::error_code ec;  // a name too long or unreadable is "not found", not an exception
  if (fs::is_directory(path, ec)) {
    throw ConfigError("case file '" + abbreviated(name) + "' is a directory, not a TOML file");
  }
  if (!fs::is_regular_file(path, ec)) {
    const fs::path in_catalog =
        cases_directory() / (path.extension() == ".toml" ? name : name + ".toml");
    if (fs::is_regular_file(in_catalog, ec)) {
      path = in_catalog;
    } else {
      throw ConfigError("case '" + abbreviated(name) +
                        "' not found: no such file, and no scene of that name in " +
                        cases_directory().string() + " (`granvv list` shows the scenes)");
    }
  }
  std::ifstream in(path);
  if (!in) throw ConfigError("case file " + path.string() + " cannot be read");
  std::ostringstream text;
  text << in.rdbuf();
  return {text.str(), path.string()};
}

std::vector<SceneListing> list_scenes() {
  std::vector<SceneListing> scenes;
  if (!fs::is_directory(cases_directory())) return scenes;
  for (const auto& entry : fs::directory_iterator(cases_directory())) {
    if (entry.path().extension() != ".toml") continue;
    SceneListing s{entry.path().stem().string(), "", ""};
    try {
      const auto table = toml::parse_file(entry.path().string());
      s.description = table["case"]["description"].value_or(std::string());
      s.reference = table["case"]["reference"].value_or(std::string());
    } catch (const toml::parse_error& e) {
      s.description = std::string("(unreadable: ") + std::string(e.description()) + ")";
    }
    scenes.push_back(s);
  }
  std::sort(scenes.begin(), scenes.end(),
            [](const auto& a, const auto& b) { return a.name < b.name; });
  return scenes;
}

}  // namespace granvv::app
