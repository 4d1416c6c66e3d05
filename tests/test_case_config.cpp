// The case loader: schema, defaults, --set overrides, one-line error messages, round trip.
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "hydro/closure.hpp"
#include "md_bridge/particle_engine_registry.hpp"
#include "scene/case_config.hpp"
#include "scene/case_schema.hpp"

namespace granvv::app {
namespace {

using Sets = std::vector<std::string>;

// Line numbers matter: the error tests below refer to them.
constexpr const char* kValidCase = R"(# a valid case
[case]
name = "single_mode_test"
description = "flow by inertia"

[physics]
K = 4e-4
q = 0.01

[initial]
type = "single_mode"
velocity_amplitude = -0.05

[hydro]
cells = 500
t_end = 3.5
output_times = [0, 1, 2.5]
transverse_velocity = true

[convergence]
cells = [100, 200, 400]
)";

constexpr const char* kMinimalCase = "[physics]\nK = 1e-3\nq = 0.1\n";

CaseConfig load(const std::string& text, const Sets& sets = {}) {
  return CaseConfig::from_string(text, "cases/x.toml", sets);
}

// The message of the ConfigError that loading throws ("" if none).
std::string error_of(const std::string& text, const Sets& sets = {}) {
  try {
    load(text, sets);
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    return message;
  }
  ADD_FAILURE() << "no ConfigError for:\n" << text;
  return "";
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_TRUE(contains(haystack, needle)) << "'" << (haystack) << "' lacks '" << (needle) << "'"

// ---------------------------------------------------------------------------------------------
// Loading and defaults
// ---------------------------------------------------------------------------------------------
TEST(CaseConfig, LoadsValidCase) {
  const CaseConfig c = load(kValidCase);
  EXPECT_EQ(c.name(), "single_mode_test");
  EXPECT_EQ(c.string("case.description"), "flow by inertia");
  EXPECT_DOUBLE_EQ(c.real("physics.K"), 4e-4);
  EXPECT_DOUBLE_EQ(c.real("physics.q"), 0.01);
  EXPECT_EQ(c.string("initial.type"), "single_mode");
  EXPECT_EQ(c.integer("hydro.cells"), 500);
  EXPECT_DOUBLE_EQ(c.real("hydro.t_end"), 3.5);
  EXPECT_EQ(c.reals("hydro.output_times"), (std::vector<double>{0.0, 1.0, 2.5}));
  EXPECT_TRUE(c.boolean("hydro.transverse_velocity"));
  EXPECT_EQ(c.integers("convergence.cells"), (std::vector<long long>{100, 200, 400}));
  EXPECT_EQ(c.origin("physics.K"), "cases/x.toml:7:5");
  EXPECT_EQ(c.origin("hydro.cfl"), "default");
}

TEST(CaseConfig, FillsDefaults) {
  const CaseConfig c = CaseConfig::from_string(kMinimalCase, "cases/minimal.toml", {});
  EXPECT_EQ(c.name(), "minimal");  // the file stem
  EXPECT_EQ(c.string("case.description"), "");
  EXPECT_EQ(c.string("initial.type"), "single_mode");
  EXPECT_DOUBLE_EQ(c.real("initial.velocity_amplitude"), -0.05);
  EXPECT_EQ(c.integer("initial.mode"), 1);
  EXPECT_EQ(c.integer("initial.random_modes"), 300);
  EXPECT_EQ(c.integer("initial.linear_branch"), 0);
  EXPECT_EQ(c.integer("hydro.cells"), 2000);
  EXPECT_DOUBLE_EQ(c.real("hydro.t_end"), 4.0);
  EXPECT_TRUE(c.reals("hydro.output_times").empty());
  EXPECT_DOUBLE_EQ(c.real("hydro.stop_density"), 1e6);
  EXPECT_DOUBLE_EQ(c.real("hydro.min_cell_width"), 1e-14);
  EXPECT_FALSE(c.boolean("hydro.transverse_velocity"));
  EXPECT_DOUBLE_EQ(c.real("analysis.tau_fit_max_density"), 1e4);
  EXPECT_TRUE(c.integers("convergence.cells").empty());
  EXPECT_DOUBLE_EQ(c.real("convergence.t"), 1.0);
  // Every schema key is resolved, in the resolved case's TOML too.
  EXPECT_EQ(c.flattened().size(), case_schema().size());
  const toml::table resolved = toml::parse(c.resolved_toml());
  for (const KeySpec& spec : case_schema()) {
    EXPECT_TRUE(resolved.at_path(spec.key)) << spec.key;
  }
}

TEST(CaseConfig, IntegerIsAcceptedAsReal) {
  const CaseConfig c = load("[physics]\nK = 1\nq = 0.1\n[hydro]\noutput_times = [1, 2]\n");
  EXPECT_DOUBLE_EQ(c.real("physics.K"), 1.0);
  EXPECT_EQ(c.reals("hydro.output_times"), (std::vector<double>{1.0, 2.0}));
  EXPECT_TRUE(toml::parse(c.resolved_toml()).at_path("physics.K").is_floating_point());
}

TEST(CaseConfig, FlattenedIsSortedTomlSyntax) {
  const CaseConfig c = load(kValidCase);
  const auto flat = c.flattened();
  EXPECT_TRUE(std::is_sorted(flat.begin(), flat.end()));
  const auto find = [&](const std::string& key) {
    for (const auto& [k, v] : flat) {
      if (k == key) return v;
    }
    return std::string("<missing>");
  };
  EXPECT_EQ(find("physics.K"), "0.0004");
  EXPECT_EQ(find("hydro.cells"), "500");
  EXPECT_EQ(find("hydro.t_end"), "3.5");
  EXPECT_EQ(find("hydro.stop_density"), "1e6");
  EXPECT_EQ(find("hydro.output_times"), "[0.0, 1.0, 2.5]");
  EXPECT_EQ(find("hydro.transverse_velocity"), "true");
  EXPECT_EQ(find("initial.type"), "\"single_mode\"");
}

TEST(CaseConfig, LoadsFromFile) {
  const auto dir = std::filesystem::temp_directory_path() / "granvv_test_case_config";
  std::filesystem::create_directories(dir);
  const auto file = dir / "from_disk.toml";
  std::ofstream(file) << kMinimalCase;
  const CaseConfig c = CaseConfig::from_file(file, {"hydro.cells=64"});
  EXPECT_EQ(c.name(), "from_disk");
  EXPECT_EQ(c.integer("hydro.cells"), 64);
  EXPECT_EQ(c.source(), file.string());
  std::filesystem::remove_all(dir);
}

TEST(CaseConfig, MissingFileIsAConfigError) {
  try {
    CaseConfig::from_file("cases/no_such_case.toml", {});
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_CONTAINS(std::string(e.what()), "cases/no_such_case.toml");
    EXPECT_CONTAINS(std::string(e.what()), "does not exist");
  }
  EXPECT_THROW(CaseConfig::from_file(std::filesystem::temp_directory_path(), {}), ConfigError);
}

// Every shipped case must load.
TEST(CaseConfig, ShippedCasesLoad) {
  const std::filesystem::path cases = std::filesystem::path(GRANVV_SOURCE_DIR) / "cases";
  if (!std::filesystem::is_directory(cases)) GTEST_SKIP() << "no cases/ folder";
  for (const auto& entry : std::filesystem::directory_iterator(cases)) {
    if (entry.path().extension() != ".toml") continue;
    EXPECT_NO_THROW(CaseConfig::from_file(entry.path(), {})) << entry.path();
  }
}

// ---------------------------------------------------------------------------------------------
// --set overrides
// ---------------------------------------------------------------------------------------------
TEST(CaseConfig, SetOverridesEveryType) {
  const CaseConfig c = load(kValidCase, {
                                            "physics.K=1e-3",                   // real, in file
                                            "hydro.cfl=1",                      // integer as real
                                            "hydro.cells=64",                   // integer
                                            "hydro.transverse_velocity=false",  // boolean
                                            "initial.type=random_modes",        // bare string
                                            "case.description=\"a b = c\"",     // TOML string
                                            "case.reference=PRL 94, 088001",    // bare, spaces
                                            "hydro.output_times=[1,2,3.225]",   // real array
                                            "convergence.cells=[8, 16]",        // integer array
                                        });
  EXPECT_DOUBLE_EQ(c.real("physics.K"), 1e-3);
  EXPECT_DOUBLE_EQ(c.real("hydro.cfl"), 1.0);
  EXPECT_EQ(c.integer("hydro.cells"), 64);
  EXPECT_FALSE(c.boolean("hydro.transverse_velocity"));
  EXPECT_EQ(c.string("initial.type"), "random_modes");
  EXPECT_EQ(c.string("case.description"), "a b = c");
  EXPECT_EQ(c.string("case.reference"), "PRL 94, 088001");
  EXPECT_EQ(c.reals("hydro.output_times"), (std::vector<double>{1.0, 2.0, 3.225}));
  EXPECT_EQ(c.integers("convergence.cells"), (std::vector<long long>{8, 16}));
  EXPECT_EQ(c.origin("hydro.cells"), "--set hydro.cells=64");
  EXPECT_EQ(toml::parse(c.resolved_toml()).at_path("hydro.cells").value<long long>(), 64);
}

TEST(CaseConfig, SetCreatesMissingTablesAndLastWins) {
  const CaseConfig c = load(kMinimalCase, {"analysis.collapse_tolerance=0.03", "initial.seed=7",
                                           "initial.seed=8", " hydro.t_end = 2 "});
  EXPECT_DOUBLE_EQ(c.real("analysis.collapse_tolerance"), 0.03);
  EXPECT_EQ(c.integer("initial.seed"), 8);
  EXPECT_DOUBLE_EQ(c.real("hydro.t_end"), 2.0);
}

TEST(CaseConfig, SetBareNumberIsAStringForStringKeys) {
  const CaseConfig c = load(kMinimalCase, {"case.name=2024", "case.description=true"});
  EXPECT_EQ(c.name(), "2024");
  EXPECT_EQ(c.string("case.description"), "true");
}

TEST(CaseConfig, SetRepairsABadFileValue) {
  const CaseConfig c = load("[physics]\nK = -1\nq = 0.1\n", {"physics.K=0.5"});
  EXPECT_DOUBLE_EQ(c.real("physics.K"), 0.5);
}

// ---------------------------------------------------------------------------------------------
// Errors: one line naming place, key, value and what is allowed
// ---------------------------------------------------------------------------------------------
TEST(CaseConfigErrors, ValueOutOfRange) {
  const std::string case_text = "[case]\nname = \"x\"\n\n[physics]\nq = 0.01\n\nK = -0.001\n";
  const std::string m = error_of(case_text);
  EXPECT_EQ(m.rfind("cases/x.toml:7:5: physics.K = -0.001: must be in (0, 100] (Knudsen number", 0),
            0u)
      << m;
}

TEST(CaseConfigErrors, ValueOutsideInterval) {
  const std::string m = error_of("[physics]\nK = 1e-3\nq = 0.7\n");
  EXPECT_CONTAINS(m, "cases/x.toml:3:5:");
  EXPECT_CONTAINS(m, "physics.q = 0.7");
  EXPECT_CONTAINS(m, "must be in (0, 0.5]");
  const std::string n = error_of(std::string(kMinimalCase) + "[hydro]\nnode_offset = 1.0\n");
  EXPECT_CONTAINS(n, "cases/x.toml:5:15: hydro.node_offset = 1.0: must be in [0, 1)");
  const std::string b = error_of(std::string(kMinimalCase) + "[initial]\nlinear_branch = 3\n");
  EXPECT_CONTAINS(b, "cases/x.toml:5:17: initial.linear_branch = 3: must be in [0, 2]");
}

TEST(CaseConfigErrors, IntegerBelowMinimum) {
  const std::string m = error_of(std::string(kMinimalCase) + "[hydro]\ncells = 3\n");
  EXPECT_CONTAINS(m, "cases/x.toml:5:9: hydro.cells = 3: must be in [4, 1e7] (number of");
}

TEST(CaseConfigErrors, UnknownKeySuggestsClosest) {
  const std::string m = error_of("[hydro]\ncells = 100\ncels = 200\n[physics]\nK=1\nq=0.1\n");
  EXPECT_EQ(m.rfind("cases/x.toml:3:1: unknown key 'hydro.cels' (did you mean 'hydro.cells'?); "
                    "allowed in [hydro]: enabled, cells, t_end, output_times, cfl,",
                    0),
            0u)
      << m;
}

TEST(CaseConfigErrors, UnknownTable) {
  const std::string m = error_of(std::string(kMinimalCase) + "\n[hydroo]\ncells = 100\n");
  EXPECT_CONTAINS(m, "cases/x.toml:5:");
  EXPECT_CONTAINS(m, "unknown key 'hydroo' (did you mean 'hydro'?)");
  EXPECT_CONTAINS(m, "allowed at top level: case, physics, initial, hydro, analysis, convergence");
}

TEST(CaseConfigErrors, UnknownKeyWithoutSuggestion) {
  const std::string m = error_of(std::string(kMinimalCase) + "[hydro]\nflux_limiter = 1\n");
  EXPECT_CONTAINS(m, "cases/x.toml:5:1: unknown key 'hydro.flux_limiter'; allowed in [hydro]:");
}

TEST(CaseConfigErrors, TableExpected) {
  const std::string m = error_of("hydro = 3\n" + std::string(kMinimalCase));
  EXPECT_CONTAINS(m, "hydro = 3: expected a table [hydro] with keys enabled, cells, t_end");
}

TEST(CaseConfigErrors, WrongTypeInFile) {
  const std::string m = error_of("[physics]\nK = 1e-3\nq = 0.1\n\n[hydro]\ncells = \"many\"\n");
  EXPECT_EQ(m, "cases/x.toml:6:9: hydro.cells = \"many\": expected an integer in [4, 1e7]");
  const std::string b = error_of(std::string(kMinimalCase) + "[hydro]\ntransverse_velocity = 1\n");
  EXPECT_CONTAINS(b, "hydro.transverse_velocity = 1: expected a boolean (true or false)");
  const std::string a =
      error_of(std::string(kMinimalCase) + "[hydro]\noutput_times = [1, \"x\"]\n");
  EXPECT_CONTAINS(a, "hydro.output_times = [1, \"x\"]: expected an array of reals, each >= 0");
}

TEST(CaseConfigErrors, RealWhereIntegerExpected) {
  const std::string m = error_of(std::string(kMinimalCase) + "[hydro]\ncells = 2000.0\n");
  EXPECT_EQ(m, "cases/x.toml:5:9: hydro.cells = 2000.0: expected an integer in [4, 1e7]");
}

TEST(CaseConfigErrors, WrongTypeInOverride) {
  const std::string m = error_of(kMinimalCase, {"hydro.cells=2.5"});
  EXPECT_EQ(m, "--set hydro.cells=2.5: hydro.cells = 2.5: expected an integer in [4, 1e7]");
  const std::string s = error_of(kMinimalCase, {"physics.K=small"});
  EXPECT_EQ(s, "--set physics.K=small: physics.K = \"small\": expected a real in (0, 100]");
}

TEST(CaseConfigErrors, OverrideOutOfRange) {
  const std::string m = error_of(kValidCase, {"physics.q=0.6"});
  EXPECT_CONTAINS(m, "--set physics.q=0.6: physics.q = 0.6: must be in (0, 0.5]");
}

TEST(CaseConfigErrors, MalformedOverride) {
  EXPECT_EQ(error_of(kMinimalCase, {"physicsK"}),
            "--set 'physicsK': malformed override; expected KEY=VALUE with a dotted KEY, e.g. "
            "--set physics.K=1e-3");
  EXPECT_CONTAINS(error_of(kMinimalCase, {"physics=1"}), "malformed override");
  EXPECT_CONTAINS(error_of(kMinimalCase, {"physics..K=1"}), "malformed override");
  EXPECT_CONTAINS(error_of(kMinimalCase, {"=1"}), "malformed override");
}

TEST(CaseConfigErrors, UnknownKeyInOverride) {
  const std::string m = error_of(kMinimalCase, {"hydro.cels=100"});
  EXPECT_CONTAINS(m,
                  "--set hydro.cels=100: unknown key 'hydro.cels' (did you mean "
                  "'hydro.cells'?); allowed in [hydro]: enabled, cells,");
  const std::string t = error_of(kMinimalCase, {"hydroo.cells=100"});
  EXPECT_CONTAINS(t,
                  "unknown key 'hydroo.cells' (did you mean 'hydro.cells'?); allowed at top "
                  "level: case, physics");
}

TEST(CaseConfigErrors, OneOfStrings) {
  const std::string m = error_of(std::string(kMinimalCase) + "[initial]\ntype = \"single-mode\"\n");
  EXPECT_CONTAINS(m,
                  "cases/x.toml:5:8: initial.type = \"single-mode\": must be one of uniform, "
                  "single_mode, random_modes, linear_mode");
  const std::string o = error_of(kMinimalCase, {"initial.type=sine"});
  EXPECT_CONTAINS(o, "--set initial.type=sine: initial.type = \"sine\": must be one of uniform,");
  EXPECT_CONTAINS(m, "(initial condition); did you mean \"single_mode\"?");
}

TEST(CaseConfigErrors, TomlSyntaxError) {
  const std::string m = error_of("[physics]\nK = 1e-3\nq = 0.1\nhydro.cells = [1,\n");
  EXPECT_EQ(m.rfind("cases/x.toml:", 0), 0u) << m;
  EXPECT_CONTAINS(m, "TOML syntax error: ");
  const std::string d = error_of("[physics]\nK = 1e-3\nK = 2e-3\nq = 0.1\n");
  EXPECT_CONTAINS(d, "cases/x.toml:3:");
  EXPECT_CONTAINS(d, "TOML syntax error:");
}

TEST(CaseConfigErrors, MissingRequiredKey) {
  const std::string m = error_of("[physics]\nK = 1e-3\n");
  EXPECT_EQ(
      m.rfind("missing required key physics.q in cases/x.toml; expected a real in (0, 0.5]", 0), 0u)
      << m;
  EXPECT_CONTAINS(error_of(""), "missing required key physics.K in cases/x.toml");
}

TEST(CaseConfigErrors, RejectsNanAndInfinity) {
  const std::string m = error_of("[physics]\nK = nan\nq = 0.1\n");
  EXPECT_CONTAINS(m, "cases/x.toml:2:5: physics.K = nan: must be a finite real in (0, 100]");
  const std::string o = error_of(kMinimalCase, {"hydro.t_end=inf"});
  EXPECT_CONTAINS(o, "--set hydro.t_end=inf: hydro.t_end = inf: must be a finite real > 0");
  const std::string a = error_of(kMinimalCase, {"hydro.output_times=[1, -inf]"});
  EXPECT_CONTAINS(a, "hydro.output_times = [1, -inf]: every element must be finite");
  EXPECT_CONTAINS(error_of(kMinimalCase, {"initial.velocity_amplitude=nan"}), "finite");
}

TEST(CaseConfigErrors, ArrayElements) {
  const std::string neg = error_of(std::string(kMinimalCase) + "[hydro]\noutput_times = [1, -2]\n");
  EXPECT_CONTAINS(neg,
                  "cases/x.toml:5:16: hydro.output_times = [1, -2]: every element must be "
                  ">= 0, but element 2 is -2.0");
  const std::string up = error_of(std::string(kMinimalCase) + "[hydro]\noutput_times = [1, 1]\n");
  EXPECT_CONTAINS(up, "hydro.output_times = [1, 1]: must be strictly increasing, but element 2");
  const std::string conv = error_of(kMinimalCase, {"convergence.cells=[8, 4]"});
  EXPECT_CONTAINS(conv,
                  "--set 'convergence.cells=[8, 4]': convergence.cells = [8, 4]: must be "
                  "strictly increasing");
  const std::string small = error_of(kMinimalCase, {"convergence.cells=[2,8]"});
  EXPECT_CONTAINS(small,
                  "convergence.cells = [2, 8]: every element must be in [4, 1e7], but element 1 "
                  "is 2");
  const std::string real = error_of(kMinimalCase, {"convergence.cells=[8,16.5]"});
  EXPECT_CONTAINS(real,
                  "convergence.cells = [8, 16.5]: expected an array of integers, each in [4, 1e7], "
                  "strictly increasing");
}

TEST(CaseConfigErrors, OutputTimesBeyondEnd) {
  const std::string m =
      error_of(std::string(kMinimalCase) + "[hydro]\nt_end = 3.0\noutput_times = [1, 2, 3.5]\n");
  EXPECT_CONTAINS(m,
                  "cases/x.toml:6:16: hydro.output_times = [1.0, 2.0, 3.5]: every element must "
                  "be <= hydro.t_end = 3.0 (from cases/x.toml:5:9), but element 3 is 3.5");
  // The key changed on the command line is the one blamed.
  const std::string o = error_of(kValidCase, {"hydro.t_end=2"});
  EXPECT_CONTAINS(o,
                  "--set hydro.t_end=2: hydro.t_end = 2.0: must be >= every "
                  "hydro.output_times, the last being 2.5 (from cases/x.toml:17:16)");
}

TEST(CaseConfigErrors, FitWindowsMustBeOrdered) {
  const std::string m =
      error_of(std::string(kMinimalCase) + "[analysis]\ntau_fit_min_density = 1e5\n");
  EXPECT_CONTAINS(m,
                  "cases/x.toml:5:23: analysis.tau_fit_min_density = 100000.0: must be < "
                  "analysis.tau_fit_max_density = 10000.0 (default)");
  const std::string o = error_of(kMinimalCase, {"analysis.profile_fit_x_max=1e-4"});
  EXPECT_CONTAINS(o,
                  "--set analysis.profile_fit_x_max=1e-4: analysis.profile_fit_x_max = "
                  "0.0001: must be > analysis.profile_fit_x_min = 0.001 (default)");
}

TEST(CaseConfigErrors, BadCaseName) {
  const std::string m = error_of(std::string(kMinimalCase) + "[case]\nname = \"../up\"\n");
  EXPECT_CONTAINS(m, "case.name = \"../up\": must be non-empty, at most 255 bytes, without '/'");
}

TEST(CaseConfigErrors, FirstProblemInFileIsReported) {
  const std::string m = error_of("[physics]\nK = -1\nq = 0.1\n[hydro]\ncels = 3\n");
  EXPECT_CONTAINS(m, "cases/x.toml:2:5: physics.K = -1");
}

// ---------------------------------------------------------------------------------------------
// Programming errors
// ---------------------------------------------------------------------------------------------
TEST(CaseConfig, UnknownKeyOrWrongAccessorIsLogicError) {
  const CaseConfig c = load(kMinimalCase);
  EXPECT_THROW(c.real("physics.k"), std::logic_error);
  EXPECT_THROW(c.real("hydro.cells"), std::logic_error);
  EXPECT_THROW(c.integer("physics.K"), std::logic_error);
  EXPECT_THROW(c.reals("convergence.cells"), std::logic_error);
  EXPECT_THROW(c.string("hydro.transverse_velocity"), std::logic_error);
  try {
    c.real("physics.k");
  } catch (const ConfigError&) {
    FAIL() << "must not be a ConfigError";
  } catch (const std::logic_error&) {
  }
}

// ---------------------------------------------------------------------------------------------
// Round trip and schema sanity
// ---------------------------------------------------------------------------------------------
TEST(CaseConfig, ResolvedTomlRoundTrips) {
  const Sets sets = {"case.description=quote \" backslash \\ tab\t end",
                     "case.reference=line1\nline2", "hydro.output_times=[0.1, 0.2, 1e-3]",
                     "hydro.output_times=[1e-3, 0.1, 1, 3.225]", "physics.K=3e-7"};
  const CaseConfig c = load(kValidCase, sets);
  const std::string resolved = c.resolved_toml();
  const CaseConfig back = CaseConfig::from_string(resolved, "resolved.toml", {});
  EXPECT_EQ(back.flattened(), c.flattened()) << resolved;
  EXPECT_EQ(back.string("case.reference"), "line1\nline2");
  EXPECT_EQ(back.real("physics.K"), 3e-7);  // exact
  // Defaults are spelled out, so the name no longer depends on the file name.
  const CaseConfig minimal = CaseConfig::from_string(kMinimalCase, "cases/minimal.toml", {});
  EXPECT_EQ(CaseConfig::from_string(minimal.resolved_toml(), "out/x/case.toml", {}).flattened(),
            minimal.flattened());
}

TEST(CaseConfigSchema, RowsAreWellFormed) {
  std::set<std::string> keys;
  for (const KeySpec& spec : case_schema()) {
    EXPECT_TRUE(keys.insert(spec.key).second) << "duplicate " << spec.key;
    EXPECT_NE(spec.key.find('.'), std::string::npos) << spec.key << " is not inside a table";
    for (const char ch : spec.key) {
      EXPECT_TRUE(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '.' ||
                  ch == '-')
          << spec.key;
    }
    EXPECT_FALSE(spec.description.empty()) << spec.key;
    EXPECT_EQ(spec.description.find('\n'), std::string::npos) << spec.key;
    if (spec.default_value.kind == Default::Kind::value) {
      Value v = spec.default_value.value;
      if (spec.type == ValueType::real && std::holds_alternative<long long>(v)) {
        v = static_cast<double>(std::get<long long>(v));
      }
      EXPECT_EQ(v.index(), static_cast<std::size_t>(spec.type)) << spec.key;
      EXPECT_FALSE(constraint_violation(spec, v)) << spec.key << ": default not allowed";
    }
  }
}

TEST(CaseConfigSchema, ConstraintTexts) {
  EXPECT_EQ(positive().text(), "> 0");
  EXPECT_EQ(non_negative().text(), ">= 0");
  EXPECT_EQ(open_closed(0, 0.5).text(), "in (0, 0.5]");
  EXPECT_EQ(closed_open(0, 1).text(), "in [0, 1)");
  EXPECT_EQ(open_open(0, 1).text(), "in (0, 1)");
  EXPECT_EQ(greater_than(1).text(), "> 1");
  EXPECT_EQ(at_least(4).text(), ">= 4");
  EXPECT_EQ(one_of({"a", "b"}).text(), "one of a, b");
  EXPECT_EQ(increasing(non_negative()).text(), "each >= 0, strictly increasing");
  EXPECT_EQ(format_real(1e6), "1e6");
  EXPECT_EQ(format_real(1e-14), "1e-14");
  EXPECT_EQ(format_real(2000.0), "2000.0");
  EXPECT_EQ(format_real(0.0004), "0.0004");
  EXPECT_EQ(format_real(1e-5), "1e-5");
  EXPECT_EQ(format_real(-0.05), "-0.05");
  EXPECT_EQ(format_real(1.5e7), "1.5e7");
  EXPECT_EQ(format_real(123456.5), "123456.5");
  EXPECT_EQ(format_real(0.0), "0.0");
  EXPECT_EQ(format_real(3e-7), "3e-7");
}

}  // namespace
}  // namespace granvv::app

// ---------------------------------------------------------------------------------------------
// Issue 9: integers, text and the key a message names
// ---------------------------------------------------------------------------------------------
namespace granvv::app {
namespace {

TEST(CaseSchemaIntegers, EveryIntegerKeyIsBoundedWithinAnInt) {
  for (const KeySpec& spec : case_schema()) {
    if (spec.type != ValueType::integer && spec.type != ValueType::integer_array) continue;
    ASSERT_TRUE(spec.constraint.max.has_value()) << spec.key;
    EXPECT_LE(*spec.constraint.max, 2147483647.0) << spec.key;
    EXPECT_TRUE(spec.constraint.min.has_value()) << spec.key;
  }
}

TEST(CaseSchemaIntegers, BeyondAnIntIsRefusedWithTheKeyAndRange) {
  // 2^32 + 4 truncates to 4 as an int: it must be refused, naming the key that was wrong.
  EXPECT_EQ(error_of(kMinimalCase, {"hydro.cells=4294967300"}),
            "--set hydro.cells=4294967300: hydro.cells = 4294967300: must be in [4, 1e7] "
            "(number of Lagrangian cells)");
  EXPECT_CONTAINS(error_of(kMinimalCase, {"initial.mode=4294967297"}),
                  "initial.mode = 4294967297: must be in [1, 2147483647]");
  EXPECT_CONTAINS(error_of(kMinimalCase, {"md.ensemble=4294967296"}),
                  "md.ensemble = 4294967296: must be in [1, 1000]");
  EXPECT_CONTAINS(error_of(kMinimalCase, {"hydro.series_every=4294967296"}),
                  "hydro.series_every = 4294967296: must be in [1, 2147483647]");
  // Beyond int64 TOML has no integer: the value is a bare string, not an integer.
  EXPECT_CONTAINS(error_of(kMinimalCase, {"hydro.cells=99999999999999999999"}),
                  "expected an integer in [4, 1e7]");
}

TEST(CaseSchemaIntegers, IntValueReadsTheCheckedValue) {
  const CaseConfig c = load(kMinimalCase, {"hydro.cells=12", "convergence.cells=[5, 15, 45]"});
  EXPECT_EQ(c.int_value("hydro.cells"), 12);
  EXPECT_EQ(c.int_values("convergence.cells"), (std::vector<int>{5, 15, 45}));
  EXPECT_THROW((void)c.int_value("physics.K"), std::logic_error);
}

TEST(CaseText, NonUtf8AndOverlongStrings) {
  EXPECT_CONTAINS(error_of(kMinimalCase, {"case.description=a\xff"}),
                  "case.description = \"a\xff\": must be valid UTF-8 text");
  EXPECT_CONTAINS(error_of(kMinimalCase, {"case.name=\xc0\xaf"}), "must be valid UTF-8 text");
  // A 300 kB name is refused (a folder name has at most 255 bytes) and not echoed whole.
  const std::string name(300000, 'a');
  const std::string m = error_of(std::string(kMinimalCase) + "[case]\nname = \"" + name + "\"\n");
  EXPECT_LT(m.size(), 600u);
  EXPECT_CONTAINS(m, "... (300000 bytes)");
  EXPECT_CONTAINS(m, "at most 255 bytes");
  EXPECT_TRUE(valid_utf8("é€𝄞"));
  EXPECT_FALSE(valid_utf8("\xed\xa0\x80"));      // a surrogate
  EXPECT_FALSE(valid_utf8("\xf4\x90\x80\x80"));  // above U+10FFFF
  EXPECT_FALSE(valid_utf8("\xe0\x80\xaf"));      // overlong
  EXPECT_EQ(utf8_repaired("a\xff\xc3\xa9", '_'), "a_\xc3\xa9");
}

TEST(CaseText, DefaultNameFromAFileNameIsAFolderName) {
  const CaseConfig c = CaseConfig::from_string(kMinimalCase, "cases/x\xff\x01y.toml");
  EXPECT_EQ(c.name(), "x__y");
  // The resolved case names its source with the bad bytes replaced, and parses again.
  const CaseConfig again = CaseConfig::from_string(c.resolved_toml(), "again.toml");
  EXPECT_EQ(again.flattened(), c.flattened());
}

TEST(CaseOrigins, TheLaterSetIsBlamed) {
  const CaseConfig c = load(kMinimalCase, {"hydro.t_end=2", "hydro.dt_max=1e-3"});
  EXPECT_GT(c.origin_precedence("hydro.dt_max"), c.origin_precedence("hydro.t_end"));
  EXPECT_GT(c.origin_precedence("hydro.t_end"), c.origin_precedence("hydro.cells"));
}

// ---------------------------------------------------------------------------------------------
// The keys an engine or a closure declares as its own.
// ---------------------------------------------------------------------------------------------

// Every registered engine's declared keys are schema keys with the declared default, range and
// help, owned by that engine; likewise every closure's.
TEST(ModelKeys, TheSchemaHasEveryEnginesAndClosuresOwnKeysAsDeclared) {
  std::set<std::string> engines_with_keys;
  for (const auto& declared : md::particle_engine_keys()) {
    SCOPED_TRACE(declared.key());
    const KeySpec* spec = find_key_spec(declared.key());
    ASSERT_NE(spec, nullptr);
    EXPECT_EQ(spec->description, declared.spec.help);
    EXPECT_EQ(spec->constraint.min, declared.spec.range.min);
    EXPECT_EQ(spec->constraint.max, declared.spec.range.max);
    const auto owner = key_owner(declared.key());
    ASSERT_TRUE(owner.has_value());
    EXPECT_EQ(owner->selector, "md.engine");
    EXPECT_EQ(owner->model, declared.engine);
    engines_with_keys.insert(declared.engine);
  }
  // Both engines have keys of their own (the contact of LAMMPS, the collapse rules of the hard
  // disks), and the key list of --dry-run (the resolved case) holds them.
  EXPECT_EQ(engines_with_keys, (std::set<std::string>{"lammps", "event_driven", "recorded"}));
  const std::string resolved = load(kMinimalCase).resolved_toml();
  for (const char* leaf :
       {"max_overlap", "steps_per_contact", "adaptive_stiffness", "collapse_speed",
        "contact_duration", "contact_speed", "elastic_speed", "max_collision_rate"}) {
    EXPECT_NE(resolved.find("\n" + std::string(leaf) + " = "), std::string::npos) << leaf;
    EXPECT_TRUE(key_owner("md." + std::string(leaf)).has_value()) << leaf;
  }
  for (const auto& declared : hydro::closure_keys()) {
    ASSERT_NE(find_key_spec(declared.key()), nullptr) << declared.key();
    EXPECT_EQ(key_owner(declared.key())->model, declared.closure);
  }
  // Keys every scene has belong to no model.
  for (const char* key : {"md.bins", "md.engine", "physics.area_fraction", "hydro.closure"}) {
    EXPECT_FALSE(key_owner(key).has_value()) << key;
  }
}

// The refusal message of refuse_keys_of_models_not_run ("" if the case passes).
std::string model_key_error(const std::string& text, const Sets& sets = {},
                            RunningCommand command = RunningCommand::run) {
  const CaseConfig c = load(text, sets);
  try {
    refuse_keys_of_models_not_run(c, command);
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    return message;
  }
  return "";
}

constexpr const char* kEventDrivenCase =
    "[physics]\nK = 1e-3\nq = 0.1\n\n[md]\nenabled = true\nengine = \"event_driven\"\n";

TEST(ModelKeys, AKeyOfAnEngineTheCaseDoesNotRunIsRefused) {
  // By --set: the message names the key, its value and both engines.
  EXPECT_EQ(model_key_error(kEventDrivenCase, {"md.max_overlap=0.02"}),
            "--set md.max_overlap=0.02: md.max_overlap = 0.02: a key of md.engine = \"lammps\", "
            "but this case runs md.engine = \"event_driven\" (from cases/x.toml:7:10)");
  // In the case file.
  const std::string in_file =
      model_key_error(std::string(kEventDrivenCase) + "steps_per_contact = 40\n");
  EXPECT_EQ(in_file.rfind("cases/x.toml:8:", 0), 0u) << in_file;
  EXPECT_NE(in_file.find("md.steps_per_contact = 40: a key of md.engine = \"lammps\""),
            std::string::npos)
      << in_file;
  // The other way round, with the engine from its default.
  EXPECT_EQ(model_key_error("[physics]\nK = 1e-3\nq = 0.1\n[md]\nenabled = true\n",
                            {"md.collapse_speed=1"}),
            "--set md.collapse_speed=1: md.collapse_speed = 1.0: a key of md.engine = "
            "\"event_driven\", but this case runs md.engine = \"lammps\" (default)");
  // A switch to the other engine over a case that tunes the first is refused too.
  EXPECT_NE(model_key_error(std::string(kEventDrivenCase) + "contact_duration = 10.0\n",
                            {"md.engine=\"lammps\""})
                .find("md.contact_duration = 10.0: a key of md.engine = \"event_driven\""),
            std::string::npos);
}

TEST(ModelKeys, OwnKeysDefaultValuesAndPartsThatDoNotRunPass) {
  // The engine's own keys.
  EXPECT_EQ(model_key_error(kEventDrivenCase, {"md.collapse_speed=0.1", "md.max_collision_rate=5"}),
            "");
  // Another engine's key at its default changes nothing: every resolved case.toml lists it.
  EXPECT_EQ(
      model_key_error(kEventDrivenCase, {"md.max_overlap=0.01", "md.adaptive_stiffness=true"}), "");
  const CaseConfig resolved = load(kEventDrivenCase, {"md.collapse_speed=0.1"});
  EXPECT_EQ(model_key_error(resolved.resolved_toml()), "");
  // No particle engine runs: [md] is not read, none of its keys is refused.
  EXPECT_EQ(model_key_error(kMinimalCase, {"md.max_overlap=0.02", "md.collapse_speed=1"}), "");
}

TEST(ModelKeys, TheAtlasRefusesTheKeysOfModelsItDoesNotRun) {
  // The atlas weighs every engine on a particle scene: the other engine's key is in use there.
  EXPECT_EQ(model_key_error(kEventDrivenCase, {"md.max_overlap=0.02"}, RunningCommand::atlas), "");
  // A closure that is on the atlas's ladder only where the case chooses it (the formula
  // closure): its formulas are refused in a case with another closure, in the atlas as in a run.
  for (const RunningCommand command : {RunningCommand::run, RunningCommand::atlas}) {
    EXPECT_NE(model_key_error(kMinimalCase, {"hydro.viscosity=\"2*sqrt(T)\""}, command)
                  .find("a key of hydro.closure = \"formula\""),
              std::string::npos);
  }
  EXPECT_EQ(
      model_key_error(kMinimalCase, {"hydro.closure=\"formula\"", "hydro.viscosity=\"2*sqrt(T)\""},
                      RunningCommand::atlas),
      "");
}

}  // namespace
}  // namespace granvv::app

namespace granvv::app {
namespace {

// The particles' r and the hydro's q are one gas's (r = 1 - 2q): the key set last decides.
TEST(OneGas, TheRestitutionSetLastMovesTheHydroAndTheParticlesTogether) {
  const std::string both_run = std::string(kMinimalCase) + "[md]\nenabled = true\n";
  // A sweep over md.restitution moves the hydro's q (and with it every closure).
  const CaseConfig by_r = load(both_run, {"md.restitution=0.8"});
  EXPECT_NEAR(by_r.real("physics.q"), 0.1, 1e-15);
  const CaseConfig by_r_low = load(both_run, {"md.restitution=0.6"});
  EXPECT_NEAR(by_r_low.real("physics.q"), 0.2, 1e-15);
  EXPECT_EQ(by_r_low.origin("physics.q"), by_r_low.origin("md.restitution"));
  // A sweep over physics.q moves the particles of a case file that names r.
  const CaseConfig by_q = load(both_run + "restitution = 0.8\n", {"physics.q=0.05"});
  EXPECT_NEAR(by_q.real("md.restitution"), 0.9, 1e-15);
  // The case file names both, and they disagree: refused in one line.
  try {
    load(both_run + "restitution = 0.9\n");
    ADD_FAILURE() << "r = 0.9 beside q = 0.1 was accepted";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("md.restitution = 0.9"), std::string::npos) << m;
    EXPECT_NE(m.find("one gas"), std::string::npos) << m;
  }
  // Left alone: r from q (0), the hydro not running, and the elastic gas (no q > 0).
  EXPECT_NEAR(load(both_run).real("physics.q"), 0.1, 0.0);
  EXPECT_NEAR(
      load(both_run + "[hydro]\nenabled = false\n", {"md.restitution=0.5"}).real("physics.q"), 0.1,
      0.0);
  EXPECT_NEAR(load(both_run, {"md.restitution=1"}).real("physics.q"), 0.1, 0.0);
}

}  // namespace
}  // namespace granvv::app
