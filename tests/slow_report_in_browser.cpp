// Long runs (ctest -L slow): the HTML reports of the default scene and of a sweep, opened in a
// real headless Chromium by scripts/check_report.py (chromedriver, W3C WebDriver). A report must
// have a title and headings, every figure must load, and the browser console must show no SEVERE
// message; a report with a figure deleted must fail the same check. (Every shipped scene's
// report is checked the same way in slow_reference_runs.cpp.)
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/cli_runner.hpp"

namespace granvv::app {
namespace {

namespace fs = std::filesystem;

// A run into a fresh folder; the test fails (with the run's output) unless it made a report.
fs::path run_with_report(const std::string& name, const std::string& args) {
  const fs::path dir = granvv::testing::fresh_directory(name);
  const auto r = granvv::testing::run_cli(args + " --out " + granvv::testing::shell_quote(dir));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "report.html")) << r.output;
  return dir;
}

TEST(BrowserReport, DefaultSceneReportRendersInChromium) {
  const fs::path dir = run_with_report("browser-default", "run --quiet");
  const auto r = granvv::testing::check_report_in_browser(dir);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("check_report: PASS"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

TEST(BrowserReport, SweepReportRendersInChromium) {
  const fs::path dir = run_with_report(
      "browser-sweep",
      "sweep md_cooling_sweep --quiet --set md.restitution=0.7,0.9 --set md.ensemble=2 "
      "--set md.t_end=0.3");
  const auto r = granvv::testing::check_report_in_browser(dir);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  fs::remove_all(dir);
}

TEST(BrowserReport, ReportWithAMissingFigureFails) {
  const fs::path dir =
      run_with_report("browser-broken",
                      "run single_mode --quiet --set hydro.cells=64 --set 'convergence.cells=[]' "
                      "--set hydro.t_end=0.5 --set 'hydro.output_times=[0.25]'");
  fs::path figure;
  for (const auto& entry : fs::directory_iterator(dir / "figures")) {
    if (entry.path().extension() == ".png" && (figure.empty() || entry.path() < figure)) {
      figure = entry.path();
    }
  }
  ASSERT_FALSE(figure.empty()) << "no figures/*.png in " << dir;
  ASSERT_EQ(granvv::testing::check_report_in_browser(dir).exit_code, 0) << "intact report";
  fs::remove(figure);

  const auto r = granvv::testing::check_report_in_browser(dir);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("broken image: figures/" + figure.filename().string()), std::string::npos)
      << r.output;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace granvv::app
