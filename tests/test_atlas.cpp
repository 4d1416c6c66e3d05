// `granvv atlas` (docs/atlas.md): its pure pieces against known answers (the Pareto front, the
// cheapest adequate candidate, the log-scale boundary search, the flow-by-inertia crossing times),
// and the command through the real binary on the Haff and single-mode scenes with small grids.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "atlas/recommendation.hpp"
#include "atlas/stability_search.hpp"
#include "atlas/work_precision.hpp"
#include "hydro/inertia_crossing.hpp"
#include "support/cli_runner.hpp"

namespace granvv::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

TEST(AtlasPieces, ParetoFrontKeepsOnlyTheUndominated) {
  // (cost, error): (1, 1) and (2, 0.5) and (4, 0.1) are a front; (3, 0.6) is beaten by (2, 0.5);
  // (1, 2) by (1, 1); the NaN error is never on it.
  const std::vector<double> cost = {1, 2, 3, 4, 1, 5};
  const std::vector<double> error = {1, 0.5, 0.6, 0.1, 2, std::nan("")};
  const auto front = atlas::pareto_front(cost, error);
  EXPECT_EQ(front, (std::vector<bool>{true, true, false, true, false, false}));
}

TEST(AtlasPieces, RelativeErrors) {
  EXPECT_NEAR(atlas::relative_error(1.01, 1.0), 0.01, 1e-15);
  EXPECT_DOUBLE_EQ(atlas::relative_error(0.5, 0.0), 0.5);
  EXPECT_TRUE(std::isnan(atlas::relative_error(std::nan(""), 1.0)));
  EXPECT_NEAR(atlas::largest_relative_error({1.0, 2.2}, {1.0, 2.0}), 0.1, 1e-15);
  EXPECT_TRUE(std::isnan(atlas::largest_relative_error({1.0}, {1.0, 2.0})));
}

TEST(AtlasPieces, CheapestAdequateNeedsEveryObservable) {
  std::vector<atlas::Candidate> c(3);
  c[0] = {0.1, {{"a", 0.5}}};    // cheap, but wrong
  c[1] = {0.2, {{"a", 0.001}}};  // right on a, silent on b: not adequate for b
  c[2] = {0.3, {{"a", 0.001}, {"b", 0.002}}};
  EXPECT_EQ(atlas::cheapest_adequate(c, {"a"}, 0.01), std::optional<std::size_t>(1));
  EXPECT_EQ(atlas::cheapest_adequate(c, {"a", "b"}, 0.01), std::optional<std::size_t>(2));
  EXPECT_FALSE(atlas::cheapest_adequate(c, {"a", "b"}, 1e-4).has_value());
}

TEST(AtlasPieces, BoundarySearchBracketsAKnownThreshold) {
  // A method that fails above 5.3: pushed from 1 by factors of 2 it fails first at 8, and two
  // log-scale bisections leave a bracket of ratio 2^(1/4) around 5.3.
  int calls = 0;
  auto probe = [&](double k) {
    ++calls;
    return k > 5.3 ? std::string("unstable") : std::string();
  };
  const auto b = atlas::find_stability_boundary(1.0, 2.0, 6, 2, probe);
  EXPECT_EQ(b.failure, "unstable");
  EXPECT_LE(b.stable, 5.3);
  EXPECT_GT(b.failed, 5.3);
  EXPECT_NEAR(b.failed / b.stable, std::pow(2.0, 0.25), 1e-12);
  EXPECT_EQ(b.probes, calls);
  EXPECT_EQ(b.probes, 1 + 3 + 2);  // the start, 2, 4, 8, and two bisections
  // Nothing fails within the pushes: no boundary, the last value stable.
  const auto none = atlas::find_stability_boundary(1.0, 0.5, 3, 2, probe);
  EXPECT_TRUE(none.failure.empty());
  EXPECT_DOUBLE_EQ(none.stable, 0.125);
  EXPECT_THROW(atlas::find_stability_boundary(6.0, 2.0, 3, 2, probe), std::invalid_argument);
}

TEST(AtlasPieces, InertiaCrossingTimeOfTheSingleModeIsExact) {
  // n0 = 1, v0 = a sin(2 pi x): the peak is at xi* = 0, n = 1/(1 - t/tau), so the level L is
  // reached at tau (1 - 1/L) (paper Eq. 5); bisection to round-off.
  const auto flow = hydro::FlowByInertia::single_mode(-0.05);
  const double tau = flow.singularity_time();
  for (double level : {10.0, 100.0, 1000.0}) {
    EXPECT_NEAR(hydro::inertia_crossing_time(flow, level), tau * (1.0 - 1.0 / level), 1e-13)
        << level;
  }
  EXPECT_EQ(hydro::inertia_crossing_time(flow, 0.5), 0.0);  // the initial peak is above 0.5
}

json read_json(const fs::path& file) {
  return json::parse(read_text(file));
}

TEST(AtlasCli, HaffSceneRecommendsTheHaffOde) {
  const fs::path dir = fresh_directory("atlas_haff");
  const auto r = run_cli("atlas haff --quiet --no-report --out " + shell_quote(dir.string()) +
                         " --set 'atlas.cells=[16,32,64]' --set 'atlas.step_factors=[0.5,1]'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json a = read_json(dir / "atlas.json");
  EXPECT_EQ(a["recommendation"]["model"], "haff_ode");
  // The homogeneous cooling state is judged on its thermal energy; the Haff ODE is exact, and the
  // hydro's cooling step is exact too, so both agree with the reference to round-off (1e-12).
  EXPECT_EQ(a["observables"], json::array({"thermal_energy"}));
  EXPECT_LT(a["recommendation"]["error"]["thermal_energy"].get<double>(), 1e-12);
  EXPECT_EQ(a["recommendation"]["next_rung"]["model"], "hydro/dilute");
  EXPECT_TRUE(fs::is_regular_file(dir / "atlas.h5"));
  // A second atlas of the same scene takes every run from the cache.
  const auto again = run_cli("atlas haff --quiet --no-report --out " + shell_quote(dir.string()) +
                             " --set 'atlas.cells=[16,32,64]' --set 'atlas.step_factors=[0.5,1]'");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(read_json(dir / "atlas.json")["runs_made"], 0);
}

TEST(AtlasCli, SingleModeLadderAndItsPage) {
  const fs::path dir = fresh_directory("atlas_single_mode");
  const auto r = run_cli("atlas single_mode --quiet --out " + shell_quote(dir.string()) +
                         " --set 'atlas.cells=[64,128,256]' --set 'atlas.step_factors=[0.5,1,2]'"
                         " --set hydro.cells=128");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json a = read_json(dir / "atlas.json");
  // The hydro's own reference (256 cells, factor 0.5) is converged far below 1e-2 on this grid.
  EXPECT_EQ(a["reference"]["setting"]["cells"], 256);
  EXPECT_TRUE(a["reference"]["converged_to_tolerance"].get<bool>());
  // Flow by inertia has crossing times but no temperature; the Haff ODE cannot follow the mode.
  ASSERT_TRUE(a["recommendation"]["model"].is_string());
  EXPECT_EQ(a["recommendation"]["model"], "hydro/dilute");
  bool inertia_ran = false;
  for (const auto& run : a["runs"]) {
    if (run["model"] != "flow_by_inertia") continue;
    inertia_ran = true;
    EXPECT_TRUE(run["model_error"].contains("crossing_time_n100"));
    EXPECT_FALSE(run["model_error"].contains("field_T"));
  }
  EXPECT_TRUE(inertia_ran);
  ASSERT_EQ(a["stability"].size(), 1u);
  EXPECT_EQ(a["stability"][0]["boundaries"].size(), 2u);
  EXPECT_TRUE(fs::is_regular_file(dir / "atlas.html"));
  // `granvv report DIR` rebuilds the page.
  fs::remove(dir / "atlas.html");
  const auto page = run_cli("report " + shell_quote(dir.string()));
  EXPECT_EQ(page.exit_code, 0) << page.output;
  EXPECT_TRUE(fs::is_regular_file(dir / "atlas.html"));
}

TEST(AtlasCli, BadInputIsOneLineAndExitTwo) {
  const fs::path dir = fresh_directory("atlas_bad");
  const std::string out = " --out " + shell_quote((dir / "x").string());
  for (const std::string& args :
       {std::string("atlas haff --tolerance -1"), std::string("atlas haff --budget 0"),
        std::string("atlas haff --jobs -2"),
        std::string("atlas haff --set atlas.observables='\"bogus\"'"),
        std::string("atlas no_such_scene")}) {
    const auto r = run_cli_streams(args + out);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir / "x" / "atlas.json")) << args;
  }
}

}  // namespace
}  // namespace granvv::testing
