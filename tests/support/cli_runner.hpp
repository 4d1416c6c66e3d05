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
// Any shell command, stdout and stderr together.
CliResult run_shell(const std::string& command);
// scripts/check_report.py on a run or sweep folder: its report.html opened in headless Chromium
// (exit 0: the page loads, every figure shows, no console errors; 1: a check failed).
CliResult check_report_in_browser(const std::filesystem::path& dir);
// A fresh empty folder under the system temp directory.
std::filesystem::path fresh_directory(const std::string& name);
std::string read_text(const std::filesystem::path& file);

struct CliStreams {
  int exit_code = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

// Like run_cli, but stdout and stderr are captured separately; with a non-empty working_dir the
// binary runs there (`cd working_dir && granvv args`).
CliStreams run_cli_streams(const std::string& args, const std::filesystem::path& working_dir = {});
// A string as one single-quoted shell word.
std::string shell_quote(const std::string& s);

}  // namespace granvv::testing
