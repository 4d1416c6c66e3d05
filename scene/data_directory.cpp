#include "scene/data_directory.hpp"

#include <cstdlib>
#include <string>
#include <system_error>
#include <vector>

#include "scene/case_config.hpp"

namespace granvv::app {
namespace fs = std::filesystem;

namespace {

bool holds_data(const fs::path& dir) {
  std::error_code ec;
  return fs::is_directory(dir / "cases", ec) &&
         fs::is_regular_file(dir / "scripts" / "report.py", ec);
}

// The folder of the running executable (Linux: /proc/self/exe).
fs::path executable_directory() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

}  // namespace

fs::path data_directory() {
  if (const char* env = std::getenv("GRANVV_DATA_DIR")) {
    if (!holds_data(env)) {
      throw ConfigError(std::string("GRANVV_DATA_DIR = '") + env +
                        "' holds no cases/ and scripts/report.py; point it at an installed "
                        "share/granvv folder or a source checkout");
    }
    return env;
  }
  const fs::path bin = executable_directory();
  // GRANVV_INSTALLED_DATA_DIR: the install's data folder relative to its bin folder.
  const std::vector<fs::path> candidates = {bin / GRANVV_INSTALLED_DATA_DIR,
                                            bin / "share" / "granvv"};
  for (const auto& c : candidates) {
    if (holds_data(c)) return fs::weakly_canonical(c);
  }
  std::string searched;
  for (const auto& c : candidates) searched += (searched.empty() ? "" : ", ") + c.string();
  throw ConfigError("granvv's data folder (cases/, scripts/) was not found in " + searched +
                    "; install with `cmake --install build --prefix P`, or set GRANVV_DATA_DIR");
}

}  // namespace granvv::app
