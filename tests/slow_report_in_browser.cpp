// Long run (ctest -L slow): the HTML report of the default scene, opened in a real headless
// Chromium by scripts/check_report.py (chromedriver, W3C WebDriver). The report must have a title
// and headings, every figure must load, and the browser console must show no SEVERE message; a
// report with a figure deleted must fail the same check.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include "support/cli_runner.hpp"

namespace granvv::app {
namespace {

namespace fs = std::filesystem;

// scripts/check_report.py on dir, with stdout and stderr together.
granvv::testing::CliResult check_report(const fs::path& dir) {
  granvv::testing::CliResult r;
  const std::string command =
      "/usr/bin/python3 " +
      granvv::testing::shell_quote(std::string(GRANVV_SOURCE_DIR) + "/scripts/check_report.py") +
      " " + granvv::testing::shell_quote(dir.string()) + " --timeout 90 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer{};
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) r.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

class BrowserReport : public ::testing::Test {
 protected:
  // One real run of the default scene per test process (ctest runs each test in its own).
  static void SetUpTestSuite() {
    dir_ = new fs::path(granvv::testing::fresh_directory("browser-report"));
    const auto r = granvv::testing::run_cli("run --quiet --out " +
                                            granvv::testing::shell_quote(dir_->string()));
    run_output_ = new std::string(r.output);
    run_exit_code_ = r.exit_code;
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(*dir_, ec);
    delete dir_;
    delete run_output_;
  }
  void SetUp() override {
    ASSERT_EQ(run_exit_code_, 0) << *run_output_;
    ASSERT_TRUE(fs::exists(*dir_ / "report.html")) << *run_output_;
  }

  static fs::path* dir_;
  static std::string* run_output_;
  static int run_exit_code_;
};

fs::path* BrowserReport::dir_ = nullptr;
std::string* BrowserReport::run_output_ = nullptr;
int BrowserReport::run_exit_code_ = -1;

TEST_F(BrowserReport, DefaultSceneReportRendersInChromium) {
  const auto r = check_report(*dir_);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("check_report: PASS"), std::string::npos) << r.output;
}

TEST_F(BrowserReport, ReportWithAMissingFigureFails) {
  const auto broken = granvv::testing::fresh_directory("browser-report-broken");
  fs::copy(*dir_, broken, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  fs::path figure;
  for (const auto& entry : fs::directory_iterator(broken / "figures")) {
    if (entry.path().extension() == ".png" && (figure.empty() || entry.path() < figure)) {
      figure = entry.path();
    }
  }
  ASSERT_FALSE(figure.empty()) << "no figures/*.png in " << broken;
  fs::remove(figure);

  const auto r = check_report(broken);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("broken image: figures/" + figure.filename().string()), std::string::npos)
      << r.output;
  std::error_code ec;
  fs::remove_all(broken, ec);
}

}  // namespace
}  // namespace granvv::app
