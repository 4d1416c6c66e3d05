// The atlas's comparison power judged by the transport fit (docs/atlas.md, "Comparison power"):
// the catch rule on synthetic fit results, the factor an injection moves the fitted coefficient
// by, and `granvv atlas` on a tiny shear wave of event-driven disks (real engine, real CLI): the
// new atlas.json keys, their verdicts against the rule, and a cache entry without its fit run
// again.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "atlas/detectable_error.hpp"
#include "models/transport_measurement.hpp"
#include "scene/case_config.hpp"
#include "scene/hydro_scene.hpp"
#include "support/cli_runner.hpp"
#include "support/small_shear_wave.hpp"

namespace granvv::testing {
namespace {

namespace fs = std::filesystem;
using app::CaseConfig;
using app::HydroScene;
using app::injected_coefficient_factor;
using nlohmann::json;

TEST(AtlasTransportPower, CatchRuleOnSyntheticFits) {
  // F = 1.02 +- 0.01 at 3 sigma: the window of agreement is [0.99, 1.05]. The closure (1) is in
  // it; a hydro at 1.06 or 0.98 is out (caught), at 1.04 or 0.995 in (missed).
  EXPECT_FALSE(atlas::off_by_transport_fit(1.02, 0.01, 1.0, 3.0));
  EXPECT_TRUE(atlas::catches_by_transport_fit(1.02, 0.01, 1.06, 3.0));
  EXPECT_TRUE(atlas::catches_by_transport_fit(1.02, 0.01, 0.98, 3.0));
  EXPECT_FALSE(atlas::catches_by_transport_fit(1.02, 0.01, 1.04, 3.0));
  EXPECT_FALSE(atlas::catches_by_transport_fit(1.02, 0.01, 0.995, 3.0));
  // The closure itself off (F = 1.1 +- 0.01): it is, and then nothing is caught, however far.
  EXPECT_TRUE(atlas::off_by_transport_fit(1.1, 0.01, 1.0, 3.0));
  EXPECT_FALSE(atlas::catches_by_transport_fit(1.1, 0.01, 2.0, 3.0));
  // No fit (a NaN factor, a zero or NaN error): nothing off, nothing caught.
  EXPECT_FALSE(atlas::catches_by_transport_fit(std::nan(""), 0.01, 2.0, 3.0));
  EXPECT_FALSE(atlas::catches_by_transport_fit(1.0, 0.0, 2.0, 3.0));
  EXPECT_FALSE(atlas::off_by_transport_fit(1.0, std::nan(""), 2.0, 3.0));
}

HydroScene garzo_dufty_scene() {
  const std::string text =
      "[case]\nname = \"x\"\n[physics]\nK = 0.08\nq = 0.05\n[initial]\ntype = \"uniform\"\n"
      "[hydro]\nclosure = \"garzo_dufty\"\n";
  return app::hydro_scene_from(CaseConfig::from_string(text, "x.toml", {}));
}

TEST(AtlasTransportPower, InjectedFactorOnTheFittedCoefficient) {
  const HydroScene scene = garzo_dufty_scene();
  // eta alone scales with its own factor; the cooling does not move it.
  EXPECT_NEAR(injected_coefficient_factor("shear_viscosity", scene, "hydro.viscosity_factor", 1.05),
              1.05, 1e-14);
  EXPECT_EQ(injected_coefficient_factor("shear_viscosity", scene, "hydro.cooling_factor", 1.05),
            1.0);
  // kappa - mu n/T: kappa times f moves it by (f - 1) kappa/(kappa - mu n/T), mu times f by
  // -(f - 1) mu n/T/(kappa - mu n/T); the two moves add to f - 1 (both times f is the fit's F),
  // and garzo_dufty's mu > 0 at r = 0.9 makes the conductivity's the larger, the mu's negative.
  const double f = 1.05;
  const double by_kappa =
      injected_coefficient_factor("effective_conductivity", scene, "hydro.conductivity_factor", f);
  const double by_mu =
      injected_coefficient_factor("effective_conductivity", scene, "hydro.mu_factor", f);
  EXPECT_NEAR((by_kappa - 1.0) + (by_mu - 1.0), f - 1.0, 1e-12);
  EXPECT_GT(by_kappa, f);
  EXPECT_LT(by_mu, 1.0);
  EXPECT_EQ(
      injected_coefficient_factor("effective_conductivity", scene, "hydro.viscosity_factor", f),
      1.0);
}

TEST(AtlasTransportPower, AtlasJudgesInjectedErrorsByTheFit) {
  const fs::path dir = fresh_directory("atlas_transport_power");
  const fs::path file = dir / "tiny_shear_wave.toml";
  std::ofstream(file) << kSmallShearWave;
  // eps = 1e-4 moves eta by far less than the fit's error; eps = 20 (eta times 21) by dozens.
  const std::string args =
      "atlas " + shell_quote(file.string()) + " --quiet --no-report --jobs 1 --out " +
      shell_quote((dir / "atlas").string()) +
      // The small scene with 2 members on 50 cells, and the LAMMPS ladder's soft contacts, which
      // the atlas runs beside, at their cheapest (a few seconds in all).
      " --set md.ensemble=2 --set hydro.cells=50 --set md.max_overlap=0.1"
      " --set md.steps_per_contact=10 --set 'compare.closures=[\"dilute\"]'"
      " --set 'atlas.ensembles=[2,8]' --set 'atlas.injected_errors=[0.0001,20]'"
      " --set 'atlas.cells=[50]' --set 'atlas.step_factors=[1]'"
      " --set 'atlas.max_overlaps=[0.1]' --set 'atlas.steps_per_contacts=[10]' --budget 300";
  const auto r = run_cli(args);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json a = json::parse(read_text(dir / "atlas" / "atlas.json"));
  const json& power = a["comparison_power"];
  ASSERT_TRUE(power.contains("transport_fit")) << power.dump();
  const json& how = power["transport_fit"];
  EXPECT_EQ(how["coefficient"], "shear_viscosity");
  EXPECT_EQ(how["keys_judged"], json::array({"viscosity_factor"}));
  EXPECT_DOUBLE_EQ(how["injected_factors"]["viscosity_factor"]["up"][1].get<double>(), 21.0);
  bool eight = false;
  for (const auto& row : power["particles"]) {
    const json& fit = row["transport_fit"];
    ASSERT_TRUE(fit.is_object()) << row.dump();
    // A fit at the end of its factor grid does not bracket F: it judges nothing.
    if (fit["at_grid_edge"] == true) {
      EXPECT_EQ(fit["verdicts"]["viscosity_factor"]["up"], json::array({"no_fit", "no_fit"}));
    }
    if (row["setting"]["ensemble"] != 8) continue;
    ASSERT_EQ(fit["at_grid_edge"], false) << fit.dump();
    eight = true;
    ASSERT_TRUE(fit["factor"].is_number()) << fit.dump();
    EXPECT_GT(fit["error"].get<double>(), 0.0);
    EXPECT_GT(fit["wall_seconds"].get<double>(), 0.0);
    // The dilute closure's eta is within a few tens of per cent of the particles' at r = 0.9,
    // inside 3 errors of 8 small members (F to some 50 %); then the tiny eps is missed and eta
    // times 21 caught.
    ASSERT_EQ(fit["unperturbed_off"], false) << fit.dump();
    EXPECT_EQ(fit["verdicts"]["viscosity_factor"]["up"], json::array({"missed", "caught"}));
    EXPECT_EQ(fit["detectable"]["viscosity_factor"]["up"], 20.0);
    EXPECT_EQ(fit["verdicts"]["viscosity_factor"]["down"][0], "missed");
    // Every verdict is the rule's on the row's own F, its error and the injected factor.
    const double F = fit["factor"].get<double>(), error = fit["error"].get<double>();
    for (const char* d : {"up", "down"}) {
      for (int i = 0; i < 2; ++i) {
        const double f = how["injected_factors"]["viscosity_factor"][d][i].get<double>();
        EXPECT_EQ(fit["verdicts"]["viscosity_factor"][d][i],
                  std::abs(f - F) > a["sigmas"].get<double>() * error ? "caught" : "missed");
      }
      // The cooling does not move eta: it is not judged by the fit.
      EXPECT_EQ(fit["verdicts"]["cooling_factor"][d], json::array({"not_judged", "not_judged"}));
      EXPECT_TRUE(fit["detectable"]["cooling_factor"][d].is_null());
    }
  }
  EXPECT_TRUE(eight) << power.dump();
  // A particle run cached without its fit (as before fits were kept) is run again, and only it.
  int stripped = 0;
  for (const auto& entry : fs::directory_iterator(dir / "atlas" / "runs")) {
    json run = json::parse(read_text(entry.path()));
    if (stripped == 0 && run["transport"].is_object()) {
      run.erase("transport");
      std::ofstream(entry.path()) << run.dump();
      ++stripped;
    }
  }
  ASSERT_EQ(stripped, 1);
  const auto again = run_cli(args);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("cached without its transport fit"), std::string::npos)
      << again.output;
  EXPECT_EQ(json::parse(read_text(dir / "atlas" / "atlas.json"))["runs_made"], 1);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace granvv::testing
