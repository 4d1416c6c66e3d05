// The validity monitors (hydro/validity_monitors.hpp, docs/physics.md §9): the kernel against
// hand-computed values on a known profile, and the monitors of a real single_mode run through
// the CLI firing where its density peak says they must.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "hydro/dilute_closure.hpp"
#include "hydro/enskog_closure.hpp"
#include "hydro/enskog_factors.hpp"
#include "hydro/validity_monitors.hpp"
#include "support/cli_runner.hpp"

namespace granvv::hydro {
namespace {

using granvv::testing::fresh_directory;
using granvv::testing::read_text;
using granvv::testing::run_cli_streams;
using granvv::testing::shell_quote;

constexpr int kArea = static_cast<int>(Monitor::area_fraction);
constexpr int kKnN = static_cast<int>(Monitor::knudsen_density);
constexpr int kKnV = static_cast<int>(Monitor::knudsen_velocity);
constexpr int kKnT = static_cast<int>(Monitor::knudsen_temperature);
constexpr int kFlow = static_cast<int>(Monitor::collision_flow);

// Four cells of width 1/4 (nodes at -1/2, -1/4, 0, 1/4) with n = 1, 2, 1, 1, T = 1, 1, 4, 1 and
// v = 0, 0.1, 0, 0 at the nodes: every gradient is known by hand.
LagrangianState known_profile() {
  LagrangianState s;
  s.node_x = {-0.5, -0.25, 0.0, 0.25};
  s.node_v = {0.0, 0.1, 0.0, 0.0};
  s.node_xi = s.node_x;
  s.cell_mass = {0.25, 0.5, 0.25, 0.25};
  s.cell_T = {1.0, 1.0, 4.0, 1.0};
  return s;
}

// Hand values, K = 0.01, l = (sqrt(2 pi)/8) K / n = 3.1332853e-3 / n (dilute, chi = 1):
//   |dv/dx| = 0.4 in cells 0 and 1; Kn_v = l |dv/dx| / sqrt(T) largest in cell 0 (x = -3/8):
//     3.1332853e-3 * 0.4 = 1.2533141e-3; tau |dv/dx| = K/(4 n sqrt(T)) 0.4 = 1e-3 there.
//   Kn_n at node 1 (x = -1/4, cells 0 and 1): l_node = (3.1332853e-3 + 1.5666427e-3)/2,
//     jump 2 |2 - 1| / 3, spacing 1/4: 6.2665707e-3 (node 2 ties; the first is kept).
//   Kn_T at node 3 (x = 1/4, cells 2 and 3): l = 3.1332853e-3, jump 2 * 3 / 5: 1.5039770e-2.
//   phi = phi0 n largest in cell 1 (x = -1/8): 0.05 * 2 = 0.1.
TEST(ValidityMonitors, KnownProfileDilute) {
  const LagrangianState s = known_profile();
  CellGeometry cells;
  measure_cells(s, cells);
  const DiluteClosure closure({0.01, 0.05}, CoolingRate::small_q, 0.05);
  const ValidityMeasures m = measure_validity(s, cells, closure.validity_scales());
  const double tol = 1e-12;  // a handful of roundings of O(1e-2) numbers
  EXPECT_NEAR(m[kKnV].value, 1.2533141373155e-3, tol);
  EXPECT_DOUBLE_EQ(m[kKnV].x, -0.375);
  EXPECT_NEAR(m[kFlow].value, 1e-3, tol);
  EXPECT_DOUBLE_EQ(m[kFlow].x, -0.375);
  EXPECT_NEAR(m[kKnN].value, 6.2665706865775e-3, tol);
  EXPECT_DOUBLE_EQ(m[kKnN].x, -0.25);
  EXPECT_NEAR(m[kKnT].value, 1.5039769647786e-2, tol);
  EXPECT_DOUBLE_EQ(m[kKnT].x, 0.25);
  EXPECT_NEAR(m[kArea].value, 0.1, tol);
  EXPECT_DOUBLE_EQ(m[kArea].x, -0.125);
}

// The Enskog closure's collisions are chi(phi0 n) times more frequent. phi0 = 0.2: cell 0 has
// phi = 0.2, chi = (1 - 0.0875)/0.64 = 1.42578125; cell 1 phi = 0.4, chi = 0.825/0.36.
// tau |dv/dx| = 0.01 * 0.4 / (4 n chi): 7.0136986e-4 in cell 0, 2.1818182e-4 in cell 1.
TEST(ValidityMonitors, KnownProfileEnskog) {
  const LagrangianState s = known_profile();
  CellGeometry cells;
  measure_cells(s, cells);
  const EnskogClosure closure({0.01, 0.05}, 0.2, CoolingRate::small_q);
  const ValidityScales scales = closure.validity_scales();
  const ValidityMeasures m = measure_validity(s, cells, scales);
  EXPECT_NEAR(m[kFlow].value, 0.004 / (4.0 * 1.42578125), 1e-15);
  EXPECT_DOUBLE_EQ(m[kFlow].x, -0.375);
  EXPECT_NEAR(m[kArea].value, 0.4, 1e-15);
  EXPECT_EQ(monitor_thresholds(scales)[kArea], enskog::kFreezingAreaFraction);
}

// The record keeps the first state at or past each threshold, and nothing for a monitor that
// does not apply (the area fraction without phi0).
TEST(ValidityMonitors, RecordKeepsTheFirstCrossing) {
  const DiluteClosure no_phi0({0.01, 0.05});
  ValidityRecord record(no_phi0.validity_scales());
  EXPECT_FALSE(record.applies[kArea]);
  EXPECT_EQ(record.threshold[kKnN], kKnudsenThreshold);
  EXPECT_EQ(record.threshold[kArea], kDiluteAreaFractionLimit);
  ValidityMeasures m{};
  m[kKnN] = {0.05, 0.1};
  m[kArea] = {0.5, 0.0};
  record.note(m, 1.0);
  m[kKnN] = {0.1, 0.2};  // reaches the threshold: this one is kept
  record.note(m, 2.0);
  m[kKnN] = {0.3, 0.3};
  record.note(m, 3.0);
  ASSERT_TRUE(record.first_crossing[kKnN]);
  EXPECT_EQ(record.first_crossing[kKnN]->time, 2.0);
  EXPECT_EQ(record.first_crossing[kKnN]->value, 0.1);
  EXPECT_EQ(record.first_crossing[kKnN]->x, 0.2);
  EXPECT_EQ(record.largest[kKnN], 0.3);
  EXPECT_FALSE(record.first_crossing[kArea]);
  EXPECT_FALSE(record.first_crossing[kKnV]);
}

// single_mode with phi0 = 0.01: the area fraction reaches the dilute threshold 0.1 exactly when
// the peak density reaches 10, so its first crossing is the first step at or after the n = 10
// crossing time, within one step (dt_max = 0.01), at the peak x = 0. As shipped (K = 4e-4, 500
// cells) the Knudsen numbers stay below 0.1 up to the singularity (measured largest 0.06 for
// the density): l = 1.25e-4 / n shrinks in the peak as fast as its gradients steepen.
TEST(ValidityMonitorsCli, SingleModeAreaFractionCrossesAtDensityTen) {
  const auto dir = fresh_directory("validity-single-mode");
  const auto r = run_cli_streams(
      "run single_mode --quiet --no-report --set 'convergence.cells=[]' "
      "--set physics.area_fraction=0.01 --out " +
      shell_quote((dir / "run").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto s = nlohmann::json::parse(read_text(dir / "run" / "summary.json"));
  const auto& h = s["hydro"];
  const auto& v = h["validity"];
  for (const char* key : {"area_fraction", "knudsen_density", "knudsen_velocity",
                          "knudsen_temperature", "collision_flow"}) {
    ASSERT_TRUE(v.contains(key)) << key;
    for (const char* field :
         {"applies", "threshold", "crossed", "value", "time", "place", "largest"}) {
      EXPECT_TRUE(v[key].contains(field)) << key << "." << field;
    }
  }
  const double t10 = h["peak_density_times"]["10"];
  const auto& phi = v["area_fraction"];
  ASSERT_TRUE(phi["crossed"].get<bool>()) << v.dump(2);
  EXPECT_EQ(phi["threshold"].get<double>(), 0.1);
  EXPECT_GE(phi["value"].get<double>(), 0.1);
  EXPECT_GE(phi["time"].get<double>(), t10);
  EXPECT_LE(phi["time"].get<double>(), t10 + 0.01);
  EXPECT_LE(std::abs(phi["place"].get<double>()), 0.01) << "the peak is at x = 0";
  EXPECT_NEAR(phi["largest"].get<double>(), 0.01 * 1e6, 0.01 * 1e6 * 0.05) << "n_max ~ 1e6";
  std::filesystem::remove_all(dir);
}

// A strong, coarse mode: K = 0.1, a = -0.6. At t = 0 (n = T = 1) the velocity Knudsen number is
// (sqrt(2 pi)/8) K |a| 2 pi |cos 2 pi x| = 0.1181 at x = 0, past 0.1, so it is crossed at t = 0
// next to x = 0; on 64 cells the cell's difference quotient is that times
// sin(pi/64)/(pi/64) = 0.99960 (bound 1e-3). tau |dv/dx| = K |a| 2 pi / 4 = 0.0942 is not.
TEST(ValidityMonitorsCli, StrongModeCrossesTheVelocityKnudsenNumberAtOnce) {
  const auto dir = fresh_directory("validity-strong-mode");
  const auto r = run_cli_streams(
      "run single_mode --quiet --no-report --set hydro.cells=64 --set 'convergence.cells=[]' "
      "--set physics.K=0.1 --set initial.velocity_amplitude=-0.6 --set hydro.t_end=0.01 "
      "--set 'hydro.output_times=[]' --out " +
      shell_quote((dir / "run").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto s = nlohmann::json::parse(read_text(dir / "run" / "summary.json"));
  const auto& v = s["hydro"]["validity"];
  const double pi = std::acos(-1.0);
  const double expected = std::sqrt(2 * pi) / 8 * 0.1 * 0.6 * 2 * pi;
  const auto& kn = v["knudsen_velocity"];
  ASSERT_TRUE(kn["crossed"].get<bool>()) << v.dump(2);
  EXPECT_EQ(kn["time"].get<double>(), 0.0);
  EXPECT_NEAR(kn["value"].get<double>(), expected, 1e-3 * expected);
  // |cos 2 pi x| peaks at x = 0 and at the period's ends x = +-1/2 alike: either is right.
  const double place = std::abs(kn["place"].get<double>());
  EXPECT_LE(std::min(place, 0.5 - place), 1.0 / 64) << place;
  EXPECT_FALSE(v["collision_flow"]["crossed"].get<bool>() &&
               v["collision_flow"]["time"].get<double>() == 0.0);
  std::filesystem::remove_all(dir);
}

// Without phi0 the dilute run's area fraction does not apply: no crossing, no column, no NaN.
TEST(ValidityMonitorsCli, NoAreaFractionMeansNotApplicable) {
  const auto dir = fresh_directory("validity-no-phi0");
  const auto r = run_cli_streams(
      "run single_mode --quiet --no-report --set hydro.cells=64 --set 'convergence.cells=[]' "
      "--set hydro.t_end=0.5 --set 'hydro.output_times=[0.25]' --out " +
      shell_quote((dir / "run").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto s = nlohmann::json::parse(read_text(dir / "run" / "summary.json"));
  const auto& phi = s["hydro"]["validity"]["area_fraction"];
  EXPECT_FALSE(phi["applies"].get<bool>());
  EXPECT_FALSE(phi["crossed"].get<bool>());
  EXPECT_TRUE(phi["largest"].is_null());
  EXPECT_TRUE(s["hydro"]["validity"]["knudsen_density"]["largest"].is_number());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace granvv::hydro
