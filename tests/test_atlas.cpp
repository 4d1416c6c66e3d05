// `granvv atlas` (docs/atlas.md): its pure pieces against known answers (the Pareto front, the
// cheapest adequate candidate, σ-aware adequacy, the bias of two measurements, the DEM work
// ratio, the log-scale boundary search, the flow-by-inertia crossing times), and the command
// through the real binary on the Haff and single-mode scenes with small grids and on a tiny
// particle ladder with both engines (real LAMMPS, the real event-driven engine).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "atlas/detectable_error.hpp"
#include "atlas/recommendation.hpp"
#include "atlas/relative_bias.hpp"
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
  c[0] = {0.1, {{"a", 0.5}}, {}};    // cheap, but wrong
  c[1] = {0.2, {{"a", 0.001}}, {}};  // right on a, silent on b: not adequate for b
  c[2] = {0.3, {{"a", 0.001}, {"b", 0.002}}, {}};
  EXPECT_EQ(atlas::cheapest_adequate(c, {"a"}, 0.01, 3.0), std::optional<std::size_t>(1));
  EXPECT_EQ(atlas::cheapest_adequate(c, {"a", "b"}, 0.01, 3.0), std::optional<std::size_t>(2));
  EXPECT_FALSE(atlas::cheapest_adequate(c, {"a", "b"}, 1e-4, 3.0).has_value());
}

TEST(AtlasPieces, SigmaAwareAdequacyAllowsTheReferencesOwnError) {
  // e <= tolerance + sigmas * s (docs/atlas.md): at tolerance 1e-2 and 3 sigma with s = 1e-3 the
  // threshold is 1.3e-2 exactly.
  EXPECT_TRUE(atlas::within_tolerance(0.012, 0.001, 0.01, 3.0));
  EXPECT_TRUE(atlas::within_tolerance(0.013, 0.001, 0.01, 3.0));
  EXPECT_FALSE(atlas::within_tolerance(0.0131, 0.001, 0.01, 3.0));
  // A deterministic reference (s = 0, or none: NaN) leaves the plain tolerance.
  EXPECT_FALSE(atlas::within_tolerance(0.012, 0.0, 0.01, 3.0));
  EXPECT_FALSE(atlas::within_tolerance(0.012, std::nan(""), 0.01, 3.0));
  EXPECT_TRUE(atlas::within_tolerance(0.01, std::nan(""), 0.01, 3.0));
  // No error (NaN) is never within; sigmas = 0 turns the allowance off.
  EXPECT_FALSE(atlas::within_tolerance(std::nan(""), 0.001, 0.01, 3.0));
  EXPECT_FALSE(atlas::within_tolerance(0.012, 0.001, 0.01, 0.0));
  // Per observable: a is within its allowance (0.02 <= 0.01 + 3 x 0.004), b is not (no error
  // given for b, so its threshold is 0.01).
  atlas::Candidate c{1.0, {{"a", 0.02}, {"b", 0.02}}, {{"a", 0.004}}};
  EXPECT_TRUE(atlas::adequate(c, {"a"}, 0.01, 3.0));
  EXPECT_FALSE(atlas::adequate(c, {"a", "b"}, 0.01, 3.0));
  c.reference_error["b"] = 0.004;
  EXPECT_TRUE(atlas::adequate(c, {"a", "b"}, 0.01, 3.0));
  EXPECT_FALSE(atlas::adequate(c, {"a", "b"}, 0.01, 2.0));  // 0.02 > 0.01 + 2 x 0.004
}

TEST(AtlasPieces, RelativeBiasAndItsError) {
  // 1.03 +- 0.01 against 1.00 +- 0.02: +3 %, error sqrt(0.01^2 + (1.03 x 0.02)^2).
  const auto b = atlas::relative_bias(1.03, 0.01, 1.0, 0.02);
  EXPECT_NEAR(b.value, 0.03, 1e-14);
  EXPECT_NEAR(b.error, std::hypot(0.01, 1.03 * 0.02), 1e-14);
  // Errors that are NaN count as 0; a reference of 0 has no relative bias.
  EXPECT_NEAR(atlas::relative_bias(2.0, std::nan(""), 4.0, 0.4).error, 2.0 * 0.4 / 16.0, 1e-15);
  EXPECT_TRUE(std::isnan(atlas::relative_bias(1.0, 0.1, 0.0, 0.1).value));
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

TEST(AtlasPieces, SmallestDetectableErrorIsWhereCatchingStaysOn) {
  const std::vector<double> eps = {0.01, 0.02, 0.04, 0.08, 0.16};
  const std::vector<bool> all(5, true);
  // Caught from 0.04 up; a lone catch at 0.01 (noise) does not count, since 0.02 is missed.
  EXPECT_EQ(atlas::smallest_detectable(eps, {true, false, true, true, true}, all), 0.04);
  // A run that did not finish is passed over: 0.08 failed, 0.04 and 0.16 caught.
  EXPECT_EQ(atlas::smallest_detectable(eps, {false, false, true, false, true},
                                       {true, true, true, false, true}),
            0.04);
  // The largest finished eps missed: nothing is detectable on this grid.
  EXPECT_FALSE(atlas::smallest_detectable(eps, {true, true, true, true, false}, all));
  EXPECT_THROW(atlas::smallest_detectable({0.1, 0.05}, {true, true}, {true, true}),
               std::invalid_argument);
  const auto grid = atlas::default_injected_errors();
  EXPECT_EQ(grid.size(), 17u);
  EXPECT_NEAR(grid.back(), 2.56, 1e-12);
}

TEST(AtlasPieces, AnInjectedErrorIsCaughtOnlyBeyondTheUnperturbedDisagreement) {
  const atlas::JudgedHydro agrees{true, false, true, 3.0};
  const atlas::JudgedHydro parts_at_2{true, true, false, 2.0};
  const atlas::JudgedHydro parts_at_1{true, true, false, 1.0};
  const atlas::JudgedHydro noise_at_1{true, false, false, 1.0};
  const atlas::JudgedHydro failed{};
  EXPECT_TRUE(atlas::catches_injected_error(parts_at_2, agrees));
  EXPECT_FALSE(atlas::catches_injected_error(noise_at_1, agrees));     // noise is not a model error
  EXPECT_TRUE(atlas::catches_injected_error(parts_at_1, parts_at_2));  // it parts earlier
  EXPECT_FALSE(atlas::catches_injected_error(parts_at_2, parts_at_2));  // no earlier than without
  EXPECT_FALSE(atlas::catches_injected_error(failed, agrees));
  EXPECT_FALSE(atlas::catches_injected_error(parts_at_1, failed));
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
  // The homogeneous cooling state is judged on its thermal energy. The reference is the richest
  // hydro that ran, the garzo_dufty closure, whose cooling carries the Sonine factor 1 + 3 a2/16
  // (a2 = -0.0089 at r = 0.98: -0.17 %, so T late in Haff's law, ~ rate^-2, is 0.33 % higher):
  // the exact Haff ODE of the paper's cooling is 0.33 % off it. Every hydro rung above the ODE
  // is adequate; the cheapest run of either is the next rung.
  EXPECT_EQ(a["observables"], json::array({"thermal_energy"}));
  EXPECT_LT(a["recommendation"]["error"]["thermal_energy"].get<double>(), 1e-2);
  EXPECT_GT(a["recommendation"]["error"]["thermal_energy"].get<double>(), 1e-3);
  EXPECT_EQ(a["recommendation"]["next_rung"]["model"].get<std::string>().rfind("hydro/", 0), 0u);
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
  // A hydro family: dilute and garzo_dufty cost the same cell-steps and are both adequate here,
  // so which of them is cheapest depends on their measured wall times.
  EXPECT_EQ(a["recommendation"]["model"].get<std::string>().rfind("hydro/", 0), 0u);
  bool inertia_ran = false;
  for (const auto& run : a["runs"]) {
    if (run["model"] != "flow_by_inertia") continue;
    inertia_ran = true;
    EXPECT_TRUE(run["model_error"].contains("crossing_time_n100"));
    EXPECT_FALSE(run["model_error"].contains("field_T"));
  }
  EXPECT_TRUE(inertia_ran);
  // The stability maps of the two hydro families that run without physics.area_fraction
  // (dilute, garzo_dufty).
  ASSERT_EQ(a["stability"].size(), 2u);
  EXPECT_EQ(a["stability"][0]["boundaries"].size(), 2u);
  EXPECT_EQ(a["stability"][1]["boundaries"].size(), 2u);
  // The hydro's timeline carries its validity monitors (none reaches its threshold in this
  // dilute, small-K scene; a crossing would lie within the run, t <= 3.225).
  bool hydro_row = false;
  for (const auto& row : a["timeline"]) {
    if (row["model"] != "hydro/dilute") continue;
    hydro_row = true;
    ASSERT_TRUE(row["monitors"].is_object()) << row.dump();
    for (const auto& [name, t] : row["monitors"].items()) {
      EXPECT_GE(t.get<double>(), 0.0) << name;
      EXPECT_LE(t.get<double>(), 3.3) << name;
    }
  }
  EXPECT_TRUE(hydro_row);
  EXPECT_TRUE(fs::is_regular_file(dir / "atlas.html"));
  // `granvv report DIR` rebuilds the page.
  fs::remove(dir / "atlas.html");
  const auto page = run_cli("report " + shell_quote(dir.string()));
  EXPECT_EQ(page.exit_code, 0) << page.output;
  EXPECT_TRUE(fs::is_regular_file(dir / "atlas.html"));
}

TEST(AtlasCli, TinyParticleLadderWithBothEngines) {
  // 300 disks to t = 10 (MD units): the event-driven engine at 2 and 8 members (the hard-disk
  // reference), LAMMPS at the case's contact (its pilot, one member) and at max_overlap 0.05
  // with 15 steps per contact and with adaptive stiffness off. A few seconds.
  const fs::path dir = fresh_directory("atlas_particles");
  const std::string args =
      "atlas md_haff --quiet --no-report --out " + shell_quote(dir.string()) +
      " --set md.particles=300 --set md.box_width=68 --set md.t_end=10 --set md.sample_interval=1"
      " --set 'md.output_times=[0,5,10]' --set md.ensemble=1 --set 'atlas.ensembles=[2,8]'"
      " --set 'atlas.max_overlaps=[0.05]' --set 'atlas.steps_per_contacts=[15]'"
      " --set 'atlas.cells=[16,32]' --set 'atlas.step_factors=[1]'"
      " --set 'atlas.particle_factors=[0.5]'";
  const auto r = run_cli(args);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json a = read_json(dir / "atlas.json");
  // The hard disks at their largest ensemble are the reference, with a statistical error.
  EXPECT_EQ(a["reference"]["setting"]["model"], "particles/event_driven");
  EXPECT_EQ(a["reference"]["setting"]["ensemble"], 8);
  EXPECT_EQ(a["observables"], json::array({"thermal_energy", "haff_t0"}));
  EXPECT_GT(a["reference"]["statistical_error"]["haff_t0"].get<double>(), 0.0);
  EXPECT_GT(a["reference"]["statistical_error"]["thermal_energy"].get<double>(), 0.0);
  int lammps = 0, event_driven = 0;
  double half_work = 0.0, full_work = 0.0;  // one member, 150 and 300 disks
  for (const auto& run : a["runs"]) {
    if (run["model"] == "particles/lammps") {
      ++lammps;
      EXPECT_EQ(run["status"], "ok") << run.dump();
      EXPECT_EQ(run["work_unit"], "atom_steps");
      // Every compared time was reached: the soft contacts' snapshots stand for them.
      EXPECT_TRUE(run["model_error"].contains("thermal_energy")) << run.dump();
    }
    if (run["model"] == "particles/event_driven") {
      ++event_driven;
      EXPECT_EQ(run["work_unit"], "collisions");
      EXPECT_GT(run["work"].get<double>(), 0.0);
      if (run["ensemble"] == 1) {
        (run["particle_factor"] == 0.5 ? half_work : full_work) = run["work"].get<double>();
      }
    }
  }
  EXPECT_EQ(lammps, 3);
  EXPECT_EQ(event_driven, 4);  // its pilot (one member), 2 and 8, and half the disks
  // Half the disks in half the channel width make half the collisions (to the scatter of one
  // member's ~370 collisions, a few per cent); the reference stays at the case's count.
  EXPECT_NEAR(half_work / full_work, 0.5, 0.1) << half_work << " " << full_work;
  EXPECT_EQ(a["reference"]["setting"]["particle_factor"], 1.0);
  // The DEM map: three contact settings, each with its t0 and P/(nT) bias and their errors.
  const json& dem = a["dem_map"];
  ASSERT_EQ(dem["points"].size(), 3u);
  for (const auto& p : dem["points"]) {
    EXPECT_TRUE(p["t0_bias"].is_number()) << p.dump();
    EXPECT_GT(p["t0_bias_error"].get<double>(), 0.0) << p.dump();
    EXPECT_TRUE(p["compressibility_bias"].is_number()) << p.dump();
  }
  EXPECT_EQ(dem["against"]["setting"], "particles/event_driven ensemble=8");
  // The hard disks' P/(nT) from their collision virial is near Enskog's 1 + 2 phi chi = 1.10
  // at phi = 0.05 (its statistical error at 8 x 300 disks is below 1 %; 3 % allows 3 sigma).
  EXPECT_NEAR(dem["against"]["compressibility"].get<double>(), 1.10, 0.03);
  // Comparison power: a uniform gas has no gradients, so the hydro's viscosity and conductivity
  // can be wrong by any factor without a trace, while its cooling rate shows in T. Each of the
  // three event-driven runs (1, 2 and 8 members) is a particle cost.
  const json& power = a["comparison_power"];
  ASSERT_TRUE(power.is_object()) << a.dump();
  ASSERT_EQ(power["particles"].size(), 3u) << power.dump();
  for (const auto& row : power["particles"]) {
    for (const char* key : {"viscosity_factor", "conductivity_factor"}) {
      for (const char* d : {"up", "down"}) {
        EXPECT_TRUE(row["detectable"][key][d].is_null()) << key << " " << d << row.dump();
      }
    }
  }
  // 8 members x 300 disks measure T to about 1 %; the cooling over t = 10 of t0 = 86 moves T by
  // 0.23 eps, so an eps of order 0.1 to 1 is caught, and within the grid (to 2.56) both ways.
  const json& largest = power["particles"].back();
  EXPECT_EQ(largest["setting"]["ensemble"], 8);
  for (const char* d : {"up", "down"}) {
    ASSERT_TRUE(largest["detectable"]["cooling_factor"][d].is_number()) << largest.dump();
    EXPECT_LT(largest["detectable"]["cooling_factor"][d].get<double>(), 2.56);
  }
  // A second atlas takes every run from the cache.
  const auto again = run_cli(args);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(read_json(dir / "atlas.json")["runs_made"], 0);
  // A run does not depend on the [atlas] table: a smaller grid finds all its runs there too.
  std::string smaller = args;
  smaller.replace(smaller.find("[2,8]"), 5, "[2]");
  const auto subset = run_cli(smaller);
  ASSERT_EQ(subset.exit_code, 0) << subset.output;
  EXPECT_EQ(read_json(dir / "atlas.json")["runs_made"], 0);
  // Collapse-rule activity as a failure mode: with the Bizon rule up to impact speed 1 (about
  // the thermal speed) a quarter of the impacts are changed, above a limit of 5 %; the hard
  // disks then fail as collapse_rule_active and the reference falls to LAMMPS.
  const auto ruled =
      run_cli(args + " --set md.collapse_speed=1 --set atlas.collapse_rule_limit=0.05");
  ASSERT_EQ(ruled.exit_code, 0) << ruled.output;
  const json b = read_json(dir / "atlas.json");
  int active = 0;
  for (const auto& run : b["runs"]) {
    if (run["model"] != "particles/event_driven") continue;
    EXPECT_EQ(run["status"], "collapse_rule_active") << run.dump();
    active += run["status"] == "collapse_rule_active";
  }
  EXPECT_EQ(active, 4);
  EXPECT_EQ(b["reference"]["setting"]["model"], "particles/lammps");
}

TEST(AtlasCli, BadInputIsOneLineAndExitTwo) {
  const fs::path dir = fresh_directory("atlas_bad");
  const std::string out = " --out " + shell_quote((dir / "x").string());
  for (const std::string& args :
       {std::string("atlas haff --tolerance -1"), std::string("atlas haff --budget 0"),
        std::string("atlas haff --jobs -2"),
        std::string("atlas haff --set atlas.observables='\"bogus\"'"),
        std::string("atlas md_haff --set atlas.bins=30"),
        std::string("atlas md_haff --set 'atlas.max_overlaps=[0.5]'"),
        std::string("atlas no_such_scene")}) {
    const auto r = run_cli_streams(args + out);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir / "x" / "atlas.json")) << args;
  }
}

}  // namespace
}  // namespace granvv::testing
