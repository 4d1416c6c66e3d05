// hydro.closure = "formula" through the real CLI: given the dilute closure's own formulas
// (paper Eqs. (1)-(2), hydro/dilute_closure.hpp) it reproduces the dilute closure's runs of
// shipped scenes, every dataset of /hydro in results.h5, and a formula outside its range, or a
// formula key set with another closure, is refused with one line naming the key (exit 2).
#include <H5Cpp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fields/hdf5_datasets.hpp"
#include "support/cli_runner.hpp"

namespace granvv::testing {
namespace {

namespace fs = std::filesystem;

// The dilute closure's formulas, with physics.cooling's loss applied by the closure.
const std::string kDiluteFormulas =
    " --set hydro.closure=formula --set 'hydro.pressure=n*T'"
    " --set 'hydro.viscosity=K/4*sqrt(T)' --set 'hydro.shear_viscosity=0.25*K*T^0.5'"
    " --set 'hydro.conductivity=K*sqrt(T)' --set hydro.mu=0"
    " --set 'hydro.cooling_rate=8*q/K*n*T*sqrt(T)'";

// Every dataset below `path` in `group`, by path.
void collect(const H5::Group& group, const std::string& path, std::vector<std::string>& out) {
  for (hsize_t i = 0; i < group.getNumObjs(); ++i) {
    const std::string name = path + "/" + group.getObjnameByIdx(i);
    if (group.getObjTypeByIdx(i) == H5G_GROUP) {
      collect(group.openGroup(group.getObjnameByIdx(i)), name, out);
    } else if (group.getObjTypeByIdx(i) == H5G_DATASET) {
      out.push_back(name);
    }
  }
}

// Compares every dataset of /hydro: numbers to 1e-9 of the value plus 1e-12, texts exactly.
// The two runs differ by the round-off of the numerical adiabatic modulus (~1e-13) and of the
// cooling integrator, which a smooth run does not amplify past ~1e-11. The absolute 1e-12 (the
// fields are O(1) at t = 0 in the scaled units) is for values that are round-off themselves:
// haff's v = 0 (~1e-17) and its gradient over cells 1/64 wide (dvdx_peak ~1e-14), and the
// Knudsen number of single_mode's T in its first steps (~1e-8, a difference of temperatures
// equal to 1e-8).
void expect_same_hydro(const fs::path& a, const fs::path& b) {
  const H5::H5File fa(a.string(), H5F_ACC_RDONLY), fb(b.string(), H5F_ACC_RDONLY);
  std::vector<std::string> names, other;
  collect(fa.openGroup("/hydro"), "/hydro", names);
  collect(fb.openGroup("/hydro"), "/hydro", other);
  ASSERT_EQ(names, other);
  ASSERT_GT(names.size(), 10u);
  int compared = 0;
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const auto slash = name.rfind('/');
    const H5::Group ga = fa.openGroup(name.substr(0, slash)),
                    gb = fb.openGroup(name.substr(0, slash));
    const std::string leaf = name.substr(slash + 1);
    if (ga.openDataSet(leaf).getTypeClass() == H5T_STRING) {
      EXPECT_EQ(h5::read_strings(ga, leaf), h5::read_strings(gb, leaf));
      continue;
    }
    const auto x = h5::read_doubles(ga, leaf), y = h5::read_doubles(gb, leaf);
    ASSERT_EQ(x.values.size(), y.values.size());
    for (size_t i = 0; i < x.values.size(); ++i) {
      const double tolerance = 1e-9 * std::abs(y.values[i]) + 1e-12;
      ASSERT_NEAR(x.values[i], y.values[i], tolerance) << "element " << i;
    }
    ++compared;
  }
  EXPECT_GT(compared, 10);
}

// Runs `granvv run <scene> <args>` into dir/<label> and returns its results.h5.
fs::path run(const fs::path& dir, const std::string& label, const std::string& args) {
  const fs::path out = dir / label;
  const CliStreams r =
      run_cli_streams(args + " --quiet --no-report --out " + shell_quote(out.string()));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return out / "results.h5";
}

TEST(FormulaClosureCli, DiluteFormulasReproduceTheDiluteRuns) {
  const fs::path dir = fresh_directory("formula-closure");
  // single_mode into its singularity (n_max = 1e6), without its convergence study, and haff
  // with each cooling variant and an injected model error.
  const std::string scenes[] = {
      "run single_mode --set 'convergence.cells=[]'",
      "run haff",
      "run haff --set physics.cooling=exact --set hydro.viscosity_factor=1.5",
  };
  int i = 0;
  for (const std::string& scene : scenes) {
    SCOPED_TRACE(scene);
    const std::string label = std::to_string(i++);
    const fs::path dilute = run(dir, label + "-dilute", scene);
    const fs::path formula = run(dir, label + "-formula", scene + kDiluteFormulas);
    expect_same_hydro(formula, dilute);
  }
  fs::remove_all(dir);
}

// A mu of the user's reaches the run and its linear theory: with mu = 0.3 K T^{3/2} / n the
// clustering mode of single_mode sees the conduction kappa - mu p_T/p_n = 0.7 K, so its cutoff
// is the dilute one over sqrt(0.7) (hydro/hcs_cutoffs.hpp).
TEST(FormulaClosureCli, MuOfTheUsersMovesTheClusteringCutoff) {
  const fs::path dir = fresh_directory("formula-closure-mu");
  const std::string scene =
      "run single_mode --set hydro.t_end=0.1 --set 'hydro.output_times=[]'"
      " --set 'convergence.cells=[]'";
  run(dir, "dilute", scene);
  run(dir, "mu", scene + " --set hydro.closure=formula --set 'hydro.mu=0.3*K*T^(3/2)/n'");
  const auto cutoff = [&](const char* label) {
    const auto s = nlohmann::json::parse(read_text(dir / label / "summary.json"));
    return s["hydro"]["clustering_cutoff_mode"].get<double>();
  };
  EXPECT_NEAR(cutoff("mu") * std::sqrt(0.7) / cutoff("dilute"), 1.0, 1e-11);
  fs::remove_all(dir);
}

TEST(FormulaClosureCli, BadFormulaOrForeignKeyExitsTwoWithOneLineNamingTheKey) {
  const fs::path dir = fresh_directory("formula-closure-bad");
  struct Bad {
    std::string args;
    std::vector<std::string> says;
  };
  const Bad bad[] = {
      {"--set hydro.closure=formula --set 'hydro.pressure=n*T - 1'",
       {"hydro.pressure = \"n*T - 1\"", "hydro.closure = \"formula\"", "is -1 at n = 1e-06",
        "allowed: finite and > 0"}},
      {"--set hydro.closure=formula --set 'hydro.conductivity=sqrt(T - 2)'",
       {"hydro.conductivity", "nan at n = 1e-06, T = 1e-12", "allowed"}},
      {"--set hydro.closure=formula --set 'hydro.constants={ q = 2 }'",
       {"hydro.constants", "reserved"}},
      {"--set hydro.closure=formula --set 'hydro.viscosity=K*sqrt(T' ",
       {"hydro.viscosity", "syntax error"}},
      {"--set 'hydro.pressure=2*n*T'", {"hydro.pressure", "a key of hydro.closure = \"formula\""}},
  };
  for (const Bad& b : bad) {
    SCOPED_TRACE(b.args);
    const CliStreams r =
        run_cli_streams("run haff " + b.args + " --out " + shell_quote((dir / "out").string()));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    for (const std::string& part : b.says) {
      EXPECT_NE(r.err.find(part), std::string::npos) << "missing '" << part << "' in " << r.err;
    }
    EXPECT_FALSE(fs::exists(dir / "out"));
  }
  // A formula closure among the compared ones is checked like hydro.closure.
  const CliStreams r = run_cli_streams(
      "run quickstart --dry-run --set 'compare.closures=[\"dilute\", \"formula\"]' "
      "--set 'hydro.pressure=n*T - 1'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("hydro.pressure = \"n*T - 1\": closure \"formula\" of compare.closures"),
            std::string::npos)
      << r.err;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace granvv::testing
