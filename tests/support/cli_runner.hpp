#pragma once
// Runs the real granvv binary (built by CMake) in a shell and captures its output.
#include <filesystem>
#include <string>

namespace granvv::testing {

struct CliResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// args are appended to the binary path as given (quote them yourself).
CliResult run_cli(const std::string& args);
// A fresh empty folder under the system temp directory.
std::filesystem::path fresh_directory(const std::string& name);
std::string read_text(const std::filesystem::path& file);

}  // namespace granvv::testing
