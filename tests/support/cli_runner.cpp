#include "support/cli_runner.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace granvv::testing {

CliResult run_cli(const std::string& args) {
  return run_shell(std::string(GRANVV_BINARY) + " " + args);
}

CliResult check_report_in_browser(const std::filesystem::path& dir) {
  return run_shell("/usr/bin/python3 " +
                   shell_quote(std::string(GRANVV_SOURCE_DIR) + "/scripts/check_report.py") + " " +
                   shell_quote(dir.string()) + " --timeout 90");
}

CliResult run_shell(const std::string& shell_command) {
  CliResult r;
  const std::string command = shell_command + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer{};
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) r.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::filesystem::path fresh_directory(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("granvv-test-" + name + "-" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (const char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

CliStreams run_cli_streams(const std::string& args, const std::filesystem::path& working_dir) {
  CliStreams r;
  std::string err_template =
      (std::filesystem::temp_directory_path() / "granvv-stderr-XXXXXX").string();
  const int fd = mkstemp(err_template.data());
  if (fd < 0) return r;
  close(fd);
  const std::filesystem::path err_file = err_template;
  std::string command;
  if (!working_dir.empty()) command = "cd " + shell_quote(working_dir.string()) + " && ";
  command += std::string(GRANVV_BINARY) + " " + args + " 2>" + shell_quote(err_file.string());
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe) {
    std::array<char, 4096> buffer{};
    size_t n;
    while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) r.out.append(buffer.data(), n);
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  r.err = read_text(err_file);
  std::error_code ec;
  std::filesystem::remove(err_file, ec);
  return r;
}

}  // namespace granvv::testing
