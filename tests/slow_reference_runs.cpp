// Long runs (ctest -L slow): the default time-step control against a tight reference on the
// paper's single-mode scene, and every shipped case end to end through the real CLI.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "scene/case_catalog.hpp"
#include "scene/case_config.hpp"
#include "scene/hydro_scene.hpp"
#include "support/cli_runner.hpp"

namespace granvv::app {
namespace {

HydroOutcome run_single_mode(const std::vector<std::string>& sets) {
  auto all = sets;
  all.push_back("convergence.cells=[]");
  return run_hydro_scene(hydro_scene_from(CaseConfig::from_file(
                             std::string(GRANVV_SOURCE_DIR) + "/cases/single_mode.toml", all)),
                         {});
}

// The mesh test (2000 vs 4000 cells) cannot see a time-step error common to both meshes; this
// compares the default step control with a run whose steps are over ten times smaller (14 times
// in number for the shipped 500-cell default, on 16 times the cells).
TEST(SlowReference, DefaultStepsMatchTightStepsWithin1e4) {
  const HydroOutcome normal = run_single_mode({});
  const HydroOutcome tight = run_single_mode(
      {"hydro.cells=8000", "hydro.cfl=0.25", "hydro.dt_max=0.005", "hydro.max_compression=0.02"});
  ASSERT_TRUE(normal.blowup_time && tight.blowup_time);
  EXPECT_LT(std::abs(*normal.blowup_time / *tight.blowup_time - 1.0), 1e-4);
  for (double level : {10.0, 100.0, 1000.0, 1e6}) {
    EXPECT_LT(
        std::abs(normal.run.crossing_times.at(level) / tight.run.crossing_times.at(level) - 1.0),
        1e-4)
        << "crossing of n = " << level;
  }
  EXPECT_GT(tight.run.steps, 10 * normal.run.steps);
}

TEST(SlowReference, EveryShippedCaseRunsEndToEndWithItsReport) {
  for (const auto& scene : list_scenes()) {
    // A cluster scene (md.accept_long_run = true, e.g. md_paper_wide) is not run here; its
    // dry run is tested in test_cli.cpp.
    const auto dry = granvv::testing::run_cli("run " + scene.name + " --dry-run");
    if (dry.output.find("accept_long_run = true") != std::string::npos) continue;
    const auto dir = granvv::testing::fresh_directory("case-" + scene.name);
    const auto r = granvv::testing::run_cli("run " + scene.name + " --quiet --out " + dir.string());
    EXPECT_EQ(r.exit_code, 0) << scene.name << ":\n" << r.output;
    const auto summary = nlohmann::json::parse(granvv::testing::read_text(dir / "summary.json"));
    EXPECT_NE(summary["status"], "failed") << scene.name;
    EXPECT_TRUE(std::filesystem::exists(dir / "report.html")) << scene.name;
    // Every scene's report, opened in a real browser: loads, every figure shows, no errors.
    const auto browser = granvv::testing::check_report_in_browser(dir);
    EXPECT_EQ(browser.exit_code, 0) << scene.name << ":\n" << browser.output;
    if (summary["hydro"].is_object()) {  // a particle-only scene (hydro.enabled = false) has none
      EXPECT_LT(summary["hydro"]["energy_drift"].get<double>(), 1e-12) << scene.name;
    }
    std::filesystem::remove_all(dir);
  }
}

}  // namespace
}  // namespace granvv::app
