// Scenes of the user's own (initial.type = "expression", "table", "snapshot"): known answers of
// the interpolation and the formulas, the expression form of single_mode against the built-in
// one, a table round trip, a snapshot continuation, and every refusal through the real CLI.
#include <H5Cpp.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fields/constants.hpp"
#include "fields/field_series_file.hpp"
#include "hydro/formula.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "hydro/periodic_interpolation.hpp"
#include "hydro/profile_table.hpp"
#include "scene/case_config.hpp"
#include "scene/hydro_scene.hpp"
#include "support/cli_runner.hpp"

namespace granvv {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Known answers.
// ---------------------------------------------------------------------------------------------

TEST(PeriodicInterpolation, LinearIsExactOnLinesAndClosesThePeriod) {
  const std::vector<double> x = {-0.4, -0.1, 0.2, 0.3}, y = {1.0, 2.5, 4.0, 3.0};
  const auto f = hydro::periodic_interpolant(x, y, hydro::Interpolation::linear);
  EXPECT_DOUBLE_EQ(f(-0.25), 1.75);
  EXPECT_DOUBLE_EQ(f(0.2), 4.0);
  // Across x = 1/2: from (0.3, 3) to (0.6, 1), i.e. x = -0.4 one period on.
  EXPECT_NEAR(f(0.45), 2.0, 1e-14);
  EXPECT_NEAR(f(-0.55), 2.0, 1e-14);
  EXPECT_NEAR(f(1.2), 4.0, 1e-14);
}

TEST(PeriodicInterpolation, MonotoneCubicStaysWithinItsNeighboursAndIsAccurate) {
  // A step: the cubic must not overshoot (n, T stay positive).
  const std::vector<double> x = {-0.5, -0.25, 0.0, 0.25}, y = {1.0, 1.0, 1e-3, 1e-3};
  const auto f = hydro::periodic_interpolant(x, y, hydro::Interpolation::monotone_cubic);
  for (double z = -0.5; z < 0.5; z += 1e-3) {
    EXPECT_GE(f(z), 1e-3 - 1e-15) << z;
    EXPECT_LE(f(z), 1.0 + 1e-15) << z;
  }
  // A smooth periodic profile on 64 rows: the cubic's mean error is well below the linear one's;
  // its largest, at the extrema where the monotone slopes are set to 0, is the linear one's
  // bound h^2/8 max|f''| = 1.2e-3.
  std::vector<double> xs, ys;
  for (int i = 0; i < 64; ++i) {
    xs.push_back(-0.5 + (i + 0.5) / 64);
    ys.push_back(2.0 + std::sin(2 * kPi * xs.back()));
  }
  const auto cubic = hydro::periodic_interpolant(xs, ys, hydro::Interpolation::monotone_cubic);
  const auto linear = hydro::periodic_interpolant(xs, ys, hydro::Interpolation::linear);
  double worst = 0.0, mean_cubic = 0.0, mean_linear = 0.0;
  const int points = 10000;
  for (int i = 0; i < points; ++i) {
    const double z = -0.5 + (i + 0.5) / points, exact = 2.0 + std::sin(2 * kPi * z);
    worst = std::max(worst, std::abs(cubic(z) - exact));
    mean_cubic += std::abs(cubic(z) - exact) / points;
    mean_linear += std::abs(linear(z) - exact) / points;
  }
  EXPECT_LT(worst, 1.25e-3);
  EXPECT_LT(mean_cubic, 0.25 * mean_linear) << mean_cubic << " " << mean_linear;
}

TEST(Formula, EvaluatesWithPiAndConstantsAndReportsTheErrorPosition) {
  const hydro::Formula f("a*sin(2*pi*x) + b", {{"a", -0.05}, {"b", 1.0}});
  EXPECT_EQ(f(0.25), -0.05 * std::sin(2 * kPi * 0.25) + 1.0);
  try {
    hydro::Formula("1 + * x", {});
    FAIL() << "no syntax error";
  } catch (const hydro::FormulaError& e) {
    EXPECT_NE(std::string(e.what()).find("position 4"), std::string::npos) << e.what();
    EXPECT_FALSE(e.constant);
  }
  EXPECT_THROW(hydro::Formula("x", {{"pi", 3.0}}), hydro::FormulaError);
}

// A table's mass on the mesh is the integral of its interpolant (the trapezoid sum for the
// linear one) to the quadrature's accuracy.
TEST(ProfileTable, MassOnTheMeshIsTheInterpolantsIntegral) {
  hydro::ProfileTable t;
  for (int i = 0; i < 10; ++i) {
    const double x = -0.5 + 0.1 * i + 0.01 * (i % 3);
    t.x.push_back(x);
    t.n.push_back(1.0 + 0.5 * std::cos(2 * kPi * x) + 0.1 * (i % 2));
    t.v_x.push_back(0.0);
    t.T.push_back(1.0);
  }
  ASSERT_FALSE(hydro::profile_table_problem(t));
  double trapezoid = 0.0;
  for (std::size_t i = 0; i < t.x.size(); ++i) {
    const std::size_t j = (i + 1) % t.x.size();
    const double h = (j == 0 ? t.x[0] + 1.0 : t.x[j]) - t.x[i];
    trapezoid += 0.5 * h * (t.n[i] + t.n[j]);
  }
  const auto state =
      hydro::discretize(hydro::profile_fields(t, hydro::Interpolation::linear), 4000, 0.5, false);
  double mass = 0.0;
  for (const double m : state.cell_mass) mass += m;
  // Only the cells holding a row's kink are not integrated exactly: 10 cells, each off by
  // at most h^2 |jump of n'| / 8 ~ 1e-8.
  EXPECT_NEAR(mass, trapezoid, 1e-9);
}

// ---------------------------------------------------------------------------------------------
// Runs through the library (the same functions `granvv run` calls).
// ---------------------------------------------------------------------------------------------

std::string small_single_mode(const std::string& initial, const std::string& hydro_extra) {
  return "[physics]\nK = 4e-4\nq = 0.01\n[initial]\n" + initial +
         "\n[hydro]\ncells = 200\ndt_max = 0.01\ncfl = 0.5\n" + hydro_extra + "\n";
}

app::HydroOutcome run_case(const std::string& toml) {
  return app::run_hydro_scene(
      app::hydro_scene_from(app::CaseConfig::from_string(toml, "user_scenes.toml")), {});
}

double largest_difference(const fields::FieldSnapshot& a, const fields::FieldSnapshot& b) {
  double worst = 0.0;
  for (const auto& column : fields::field_columns()) {
    const auto& u = a.*(column.values);
    const auto& v = b.*(column.values);
    EXPECT_EQ(u.size(), v.size()) << column.name;
    for (std::size_t i = 0; i < std::min(u.size(), v.size()); ++i) {
      worst = std::max(worst, std::abs(u[i] - v[i]));
    }
  }
  return worst;
}

// The expression form of single_mode gives the built-in run: same formula, same evaluation
// (muparser folds 2*pi*k into one constant as the built-in does), so the same bits.
TEST(UserScenes, SingleModeAsAnExpressionGivesTheBuiltInRunToRoundOff) {
  const std::string hydro = "t_end = 2.0\noutput_times = [1.0, 2.0]";
  const auto built_in =
      run_case(small_single_mode("type = \"single_mode\"\nvelocity_amplitude = -0.05", hydro));
  const auto expression = run_case(small_single_mode(
      "type = \"expression\"\nvelocity = \"a*sin(2*pi*x)\"\nconstants = { a = -0.05 }", hydro));
  ASSERT_EQ(built_in.cell_fields.snapshots.size(), expression.cell_fields.snapshots.size());
  double worst = 0.0;
  for (std::size_t s = 0; s < built_in.cell_fields.snapshots.size(); ++s) {
    worst = std::max(worst, largest_difference(built_in.cell_fields.snapshots[s],
                                               expression.cell_fields.snapshots[s]));
  }
  std::printf("expression single_mode against the built-in: largest difference %.3g\n", worst);
  EXPECT_LE(worst, 1e-13);
  // Its flow-by-inertia reference (from the formula, slope by differences) has the exact tau.
  ASSERT_TRUE(expression.inertia_tau);
  EXPECT_NEAR(*expression.inertia_tau, 1.0 / (2 * kPi * 0.05), 1e-10);
}

struct Scratch {
  explicit Scratch(const std::string& name) : path(testing::fresh_directory(name)) {}
  ~Scratch() {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    std::error_code ec;
    if (test && !test->result()->Failed()) fs::remove_all(path, ec);
  }
  fs::path path;
};

// Export a run's t = 0 fields as a CSV table and start from it: the difference at the first
// step is the interpolation through the cell centres (cubic: O(h^4) for n and T, which are
// uniform here, and the v_x of the table being the mean of the two node velocities).
TEST(UserScenes, TableRoundTripOfARunsFields) {
  Scratch scratch("table-round-trip");
  const std::string hydro = "t_end = 0.5\noutput_times = [0.5]";
  const auto first =
      run_case(small_single_mode("type = \"single_mode\"\nvelocity_amplitude = -0.05", hydro));
  const auto& start = first.cell_fields.snapshots.front();
  // The export: the rows by x in [-1/2, 1/2) (the last cell centre sits at 1/2), as a CSV.
  hydro::ProfileTable exported;
  exported.x = start.x, exported.n = start.n, exported.v_x = start.v_x, exported.T = start.T;
  exported = hydro::wrapped_into_period(exported);
  const fs::path csv = scratch.path / "fields.csv";
  {
    std::ofstream out(csv);
    out << "# a run's /hydro/fields at t = 0\nx, n, v_x, T\n";
    char line[160];
    for (std::size_t i = 0; i < exported.x.size(); ++i) {
      std::snprintf(line, sizeof line, "%.17g, %.17g, %.17g, %.17g\n", exported.x[i], exported.n[i],
                    exported.v_x[i], exported.T[i]);
      out << line;
    }
  }
  const auto second = run_case(small_single_mode(
      "type = \"table\"\nfrom = \"" + csv.string() + "\"\ninterpolation = \"cubic\"", hydro));
  const double at_start = largest_difference(start, second.cell_fields.snapshots.front());
  const double at_end =
      largest_difference(first.cell_fields.snapshots.back(), second.cell_fields.snapshots.back());
  std::printf("table round trip: largest difference %.3g at t = 0, %.3g at t = 0.5\n", at_start,
              at_end);
  // v_x of the table is the node mean a sin(2 pi x) cos(pi h), off by (pi h)^2/2 |a| = 6e-6,
  // and the new nodes take it interpolated half a cell away; the difference then grows with the
  // flow (measured 7.7e-6 and 2.7e-5).
  EXPECT_LT(at_start, 1e-5);
  EXPECT_LT(at_end, 4e-5);
  EXPECT_GT(at_start, 0.0);  // the export is not the state itself
}

// A hydro of 2 + 2 time units, continued from the first run's results.h5, against a straight
// run of 4 (a = -0.02: the flow-by-inertia singularity is at 7.96).
TEST(UserScenes, SnapshotContinuationMatchesTheStraightRun) {
  Scratch scratch("snapshot-continuation");
  const std::string single = "type = \"single_mode\"\nvelocity_amplitude = -0.02";
  const fs::path straight = scratch.path / "straight", half = scratch.path / "half",
                 continued = scratch.path / "continued";
  const std::string sets =
      " --quiet --no-report --set physics.K=4e-4 --set physics.q=0.01 "
      "--set hydro.cells=400 --set 'convergence.cells=[]' "
      "--set initial.velocity_amplitude=-0.02 ";
  auto run = testing::run_cli("run single_mode" + sets +
                              "--set hydro.t_end=4 --set 'hydro.output_times=[2.0, 4.0]' --out " +
                              testing::shell_quote(straight.string()));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  run = testing::run_cli("run single_mode" + sets +
                         "--set hydro.t_end=2 --set 'hydro.output_times=[2.0]' --out " +
                         testing::shell_quote(half.string()));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string from = (half / "results.h5").string();
  run = testing::run_cli("run single_mode" + sets +
                         "--set hydro.t_end=2 --set 'hydro.output_times=[2.0]' "
                         "--set initial.type=snapshot --set initial.time=2 --set initial.from=" +
                         testing::shell_quote(from) + " --out " +
                         testing::shell_quote(continued.string()));
  ASSERT_EQ(run.exit_code, 0) << run.output;

  auto read = [](const fs::path& file) {
    const H5::H5File h5(file.string(), H5F_ACC_RDONLY);
    return fields::read_field_series(h5.openGroup("/hydro/fields"));
  };
  const auto a = read(straight / "results.h5"), c = read(continued / "results.h5");
  const auto& a4 = a.snapshots.back();
  const auto& c2 = c.snapshots.back();
  ASSERT_DOUBLE_EQ(a4.t, 4.0);
  ASSERT_DOUBLE_EQ(c2.t, 2.0);
  // Compare on common positions: the continued run's mesh is uniform in x at its start, the
  // straight one's is not, so both are interpolated (linear, periodic) at the straight run's
  // cell centres.
  auto table = [](const fields::FieldSnapshot& s) {
    hydro::ProfileTable t;
    t.x = s.x, t.n = s.n, t.v_x = s.v_x, t.T = s.T;
    return hydro::profile_fields(hydro::wrapped_into_period(t), hydro::Interpolation::linear);
  };
  const auto fc = table(c2);
  double dn = 0.0, dv = 0.0, dT = 0.0;
  for (std::size_t i = 0; i < a4.x.size(); ++i) {
    dn = std::max(dn, std::abs(fc.n(a4.x[i]) - a4.n[i]));
    dv = std::max(dv, std::abs(fc.v(a4.x[i]) - a4.v_x[i]));
    dT = std::max(dT, std::abs(fc.T(a4.x[i]) - a4.T[i]));
  }
  std::printf("snapshot 2 + 2 against straight 4: max |dn| %.3g, |dv| %.3g, |dT| %.3g\n", dn, dv,
              dT);
  EXPECT_LT(dn, 1e-3);
  EXPECT_LT(dv, 1e-4);
  EXPECT_LT(dT, 1e-4);
  // Provenance: the continued run names its file and checksum.
  const auto summary = nlohmann::json::parse(testing::read_text(continued / "summary.json"));
  ASSERT_TRUE(summary.contains("initial")) << summary.dump();
  EXPECT_EQ(summary["initial"]["type"], "snapshot");
  EXPECT_EQ(summary["initial"]["files"][0]["path"], from);
  EXPECT_EQ(summary["initial"]["files"][0]["sha256"].get<std::string>().size(), 64u);
}

// ---------------------------------------------------------------------------------------------
// Every refusal through the real CLI: exit 2, one line naming the key, nothing written.
// ---------------------------------------------------------------------------------------------

struct Refusal {
  std::string name;
  std::string args;                    // after `granvv run single_mode`; {DIR} = scratch folder
  std::vector<std::string> must_name;  // parts of the error line
};

std::ostream& operator<<(std::ostream& os, const Refusal& r) {
  return os << r.name;
}

std::string with_dir(std::string s, const fs::path& dir) {
  for (auto at = s.find("{DIR}"); at != std::string::npos; at = s.find("{DIR}")) {
    s.replace(at, 5, dir.string());
  }
  return s;
}

// The files the refusals read: tables with one fault each, and a hydro-only results.h5.
void write_inputs(const fs::path& dir) {
  const auto table = [&](const std::string& name, const std::string& rows) {
    std::ofstream(dir / name) << "x, n, v_x, T\n" << rows;
  };
  table("good.csv", "-0.375, 1, 0, 1\n-0.125, 1.1, 0, 1\n0.125, 1, 0, 0.9\n0.375, 0.9, 0, 1\n");
  table("unordered.csv", "-0.375, 1, 0, 1\n0.125, 1.1, 0, 1\n-0.125, 1, 0, 1\n0.375, 1, 0, 1\n");
  table("negative_n.csv", "-0.375, 1, 0, 1\n-0.125, -1, 0, 1\n0.125, 1, 0, 1\n0.375, 1, 0, 1\n");
  table("zero_T.csv", "-0.375, 1, 0, 1\n-0.125, 1, 0, 0\n0.125, 1, 0, 1\n0.375, 1, 0, 1\n");
  table("half_period.csv", "-0.5, 1, 0, 1\n-0.4, 1, 0, 1\n-0.2, 1, 0, 1\n0.0, 1, 0, 1\n");
  table("outside.csv", "-0.375, 1, 0, 1\n-0.125, 1, 0, 1\n0.125, 1, 0, 1\n0.75, 1, 0, 1\n");
  std::ofstream(dir / "no_T.csv") << "x, n, v_x\n-0.375, 1, 0\n-0.125, 1, 0\n0.125, 1, 0\n";
  const auto r = testing::run_cli(
      "run single_mode --quiet --no-report --set hydro.cells=64 "
      "--set 'convergence.cells=[]' --set hydro.t_end=0.5 "
      "--set 'hydro.output_times=[0.25]' --out " +
      testing::shell_quote((dir / "hydro_run").string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
}

class UserSceneRefusal : public ::testing::TestWithParam<Refusal> {
 protected:
  static void SetUpTestSuite() {
    inputs_ = new fs::path(testing::fresh_directory("user-scene-inputs"));
    write_inputs(*inputs_);
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(*inputs_, ec);
    delete inputs_;
  }
  static fs::path* inputs_;
};
fs::path* UserSceneRefusal::inputs_ = nullptr;

TEST_P(UserSceneRefusal, ExitsTwoWithOneLineNamingTheKeyAndWritesNothing) {
  const Refusal& refusal = GetParam();
  const fs::path out = *inputs_ / ("out-" + refusal.name);
  const auto r = testing::run_cli_streams("run single_mode --set hydro.cells=64 " +
                                          with_dir(refusal.args, *inputs_) + " --out " +
                                          testing::shell_quote(out.string()));
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_EQ(r.out, "");
  ASSERT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("granvv: error: ", 0), 0u) << r.err;
  for (const auto& part : refusal.must_name) {
    EXPECT_NE(r.err.find(with_dir(part, *inputs_)), std::string::npos)
        << "missing '" << part << "' in " << r.err;
  }
  EXPECT_FALSE(fs::exists(out));
}

const std::string kExpression = "--set initial.type=expression ";
const std::string kTable = "--set initial.type=table --set initial.from={DIR}/";
const std::string kSnapshot =
    "--set initial.type=snapshot --set initial.from={DIR}/hydro_run/results.h5 ";

INSTANTIATE_TEST_SUITE_P(
    Cli, UserSceneRefusal,
    ::testing::Values(
        Refusal{"syntax",
                kExpression + "--set 'initial.density=1 + * x'",
                {"initial.density", "syntax error", "\"1 + * x\"", "position 4"}},
        Refusal{"unknown_name",
                kExpression + "--set 'initial.velocity=a*sin(2*pi*x)'",
                {"initial.velocity", "Unexpected token \"a\""}},
        Refusal{"reserved_constant",
                kExpression + "--set 'initial.constants={ pi = 3 }'",
                {"initial.constants", "reserved"}},
        Refusal{"density_not_positive",
                kExpression + "--set 'initial.density=0.5 + sin(2*pi*x)'",
                {"initial.density", "must be > 0", "x = "}},
        Refusal{"temperature_not_positive",
                kExpression + "--set 'initial.temperature=cos(2*pi*x)'",
                {"initial.temperature", "must be > 0"}},
        Refusal{"values_not_periodic",
                kExpression + "--set 'initial.density=1.5 + x'",
                {"initial.density", "not periodic", "x = -1/2", "x = 1/2"}},
        Refusal{"slopes_not_periodic",
                kExpression + "--set 'initial.density=1 + x^2'",
                {"initial.density", "not periodic: slope"}},
        Refusal{"not_finite",
                kExpression + "--set 'initial.velocity=1/x'",
                {"initial.velocity", "not finite", "x = 0"}},
        Refusal{"transverse_without_its_flag",
                kExpression + "--set 'initial.transverse_velocity=0.1*cos(2*pi*x)'",
                {"initial.transverse_velocity", "hydro.transverse_velocity = true"}},
        Refusal{"mean_density_not_one",
                kExpression + "--set initial.density=2",
                {"initial.density", "mean density of 2", "must be 1"}},
        Refusal{"table_missing_file", kTable + "absent.csv", {"initial.from", "does not exist"}},
        Refusal{"table_out_of_order",
                kTable + "unordered.csv",
                {"initial.from", "row 3", "increasing x"}},
        Refusal{"table_n_not_positive",
                kTable + "negative_n.csv",
                {"initial.from", "row 2: n = -1 must be > 0"}},
        Refusal{"table_T_not_positive",
                kTable + "zero_T.csv",
                {"initial.from", "row 2: T = 0 must be > 0"}},
        Refusal{"table_not_spanning",
                kTable + "half_period.csv",
                {"initial.from", "does not span the period"}},
        Refusal{
            "table_outside_period", kTable + "outside.csv", {"initial.from", "outside the period"}},
        Refusal{"table_missing_column", kTable + "no_T.csv", {"initial.from", "no column T"}},
        Refusal{"snapshot_missing_file",
                "--set initial.type=snapshot --set initial.from={DIR}/absent.h5",
                {"initial.from", "does not exist"}},
        Refusal{"snapshot_time_not_in_file",
                kSnapshot + "--set initial.time=0.3",
                {"initial.time", "t = 0.3 is not in", "0, 0.25, 0.5"}},
        Refusal{"snapshot_wrong_source",
                kSnapshot + "--set initial.source=md",
                {"initial.source", "has no /md/fields"}},
        Refusal{"snapshot_not_results",
                "--set initial.type=snapshot --set initial.from={DIR}/good.csv",
                {"initial.from", "is not an HDF5 file"}}));

}  // namespace
}  // namespace granvv
