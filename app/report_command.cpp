#include "app/report_command.hpp"

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "app/output_folder.hpp"
#include "scene/case_config.hpp"
#include "scene/data_directory.hpp"

namespace granvv::app {

namespace {
std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
}  // namespace

int run_python_script(const std::string& script_name, const std::vector<std::string>& args) {
  const char* env = std::getenv("GRANVV_PYTHON");
  const std::string python = env ? env : "/usr/bin/python3";
  std::string script;
  try {
    script = (data_directory() / "scripts" / script_name).string();
  } catch (const ConfigError& e) {
    std::cerr << "granvv: error: " << e.what() << "\n";
    return 2;
  }
  std::string command = shell_quote(python) + " " + shell_quote(script);
  for (const auto& a : args) command += " " + shell_quote(a);
  const int status = std::system(command.c_str());
  if (status == -1) return 127;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

int build_report(const std::filesystem::path& dir) {
  return run_python_script("report.py", {dir.string()});
}

int report_command(const std::filesystem::path& dir) {
  for (const auto& note : finish_interrupted_commits(dir)) std::cerr << "granvv: " << note << "\n";
  if (!std::filesystem::is_regular_file(dir / "results.h5") &&
      !std::filesystem::is_regular_file(dir / "sweep.json") &&
      !std::filesystem::is_regular_file(dir / "atlas.json")) {
    std::cerr << "granvv: error: none of results.h5, sweep.json, atlas.json found in "
              << dir.string()
              << "; `granvv report DIR` needs the folder of a run, a sweep or an "
                 "atlas\n";
    return 2;
  }
  return build_report(dir);
}

}  // namespace granvv::app
