// The command-line contract (docs/outputs.md, docs/architecture.md), driven through the real
// build/granvv binary: bad input, --dry-run, `granvv list`, a small real run and its output folder,
// the report, and the embedded default scene. Runs use tiny meshes so the whole file takes a few
// seconds.
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "fields/field_series_file.hpp"
#include "fields/hdf5_datasets.hpp"
#include "scene/case_schema.hpp"
#include "support/cli_runner.hpp"

namespace granvv::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A run that takes a fraction of a second: 64 cells, no convergence study, one output time.
const std::string kSmall =
    "--set hydro.cells=64 --set 'convergence.cells=[]' --set hydro.t_end=0.5 "
    "--set 'hydro.output_times=[0.25]'";

std::string q(const fs::path& p) {
  return shell_quote(p.string());
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const auto end = text.find('\n', start);
    lines.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return lines;
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.rfind(prefix, 0) == 0;
}

void write_file(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  ASSERT_TRUE(out.good()) << "cannot write " << file;
}

bool has_signature(const fs::path& file, const std::string& magic) {
  std::ifstream in(file, std::ios::binary);
  std::string head(magic.size(), '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  return in.good() && head == magic;
}

const std::string kHdf5Magic("\x89HDF\r\n\x1a\n", 8);
const std::string kPngMagic("\x89PNG\r\n\x1a\n", 8);

std::string describe(const CliStreams& r) {
  return "exit " + std::to_string(r.exit_code) + "\n--- stdout ---\n" + r.out + "--- stderr ---\n" +
         r.err;
}

// Parses TOML text, failing the test (and returning an empty table) if it is not TOML.
toml::table parse_toml(const std::string& text, const std::string& what) {
  try {
    return toml::parse(text, std::string_view(what));
  } catch (const toml::parse_error& e) {
    ADD_FAILURE() << what << " is not valid TOML: " << e << "\n" << text;
    return {};
  }
}

// Removes a test's temporary folder unless the test failed (then it is kept for inspection).
struct ScratchFolder {
  explicit ScratchFolder(const std::string& name) : path(fresh_directory(name)) {}
  ~ScratchFolder() {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    if (test && !test->result()->Failed()) {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  }
  fs::path path;
};

// ---------------------------------------------------------------------------------------------
// 1. Bad input: exit code 2, one line "granvv: error: ..." on stderr, nothing written.
// ---------------------------------------------------------------------------------------------

// A case file with known line numbers: K on line 5, q on line 6, [hydro] keys from line 9.
std::string case_text(const std::string& K, const std::string& q_value,
                      const std::string& hydro_lines) {
  return "[case]\n"
         "name = \"cli_bad_input\"\n"
         "\n"
         "[physics]\n"
         "K = " +
         K +
         "\n"
         "q = " +
         q_value +
         "\n"
         "\n"
         "[hydro]\n" +
         hydro_lines + "\n";
}

struct BadInput {
  std::string name;
  std::string case_file;  // written to {DIR}/case.toml if non-empty
  std::string args;       // after `granvv run`; {CASE} = that file, {DIR} = the scratch folder
  std::vector<std::string> message_parts;  // the error line must contain each ({CASE}, {DIR})
};

std::string substitute(std::string s, const fs::path& dir, const fs::path& case_file) {
  const std::pair<std::string, std::string> vars[] = {{"{CASE}", case_file.string()},
                                                      {"{DIR}", dir.string()}};
  for (const auto& [var, value] : vars) {
    for (auto at = s.find(var); at != std::string::npos; at = s.find(var, at + value.size())) {
      s.replace(at, var.size(), value);
    }
  }
  return s;
}

std::ostream& operator<<(std::ostream& os, const BadInput& b) {
  return os << b.name;
}

class CliBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CliBadInput, ExitsTwoWithOneErrorLineAndWritesNothing) {
  const BadInput& bad = GetParam();
  ScratchFolder scratch("bad-" + bad.name);
  const fs::path case_file = scratch.path / "case.toml";
  if (!bad.case_file.empty()) write_file(case_file, bad.case_file);
  const fs::path out = scratch.path / "out";

  const CliStreams r = run_cli_streams(
      "run " + substitute(bad.args, scratch.path, case_file) + " --out " + q(out), scratch.path);

  EXPECT_EQ(r.exit_code, 2) << describe(r);
  const auto lines = lines_of(r.err);
  ASSERT_EQ(lines.size(), 1u) << "expected exactly one line on stderr\n" << describe(r);
  const std::string& line = lines.front();
  EXPECT_TRUE(starts_with(line, "granvv: error: ")) << line;
  for (const std::string& part : bad.message_parts) {
    const std::string expected = substitute(part, scratch.path, case_file);
    EXPECT_TRUE(contains(line, expected)) << "missing '" << expected << "' in\n" << line;
  }
  EXPECT_EQ(r.out, "") << "nothing on stdout for a rejected run";
  EXPECT_FALSE(fs::exists(out)) << "a rejected run created its output folder " << out;
  EXPECT_FALSE(fs::exists(scratch.path / "out" / "cli_bad_input"));
}

const std::string kQ = "0.01";
const std::string kK = "4e-4";

INSTANTIATE_TEST_SUITE_P(
    Cli, CliBadInput,
    ::testing::Values(
        // Case files: the message names file:line, the key, the value and what is allowed.
        BadInput{"unknown_key_in_file",
                 case_text(kK, kQ, "cels = 64"),
                 "{CASE}",
                 {"{CASE}:9:", "'hydro.cels'", "did you mean 'hydro.cells'", "allowed"}},
        BadInput{"unknown_table_in_file",
                 case_text(kK, kQ, "cells = 64\n[hydrox]\ncells = 64"),
                 "{CASE}",
                 {"{CASE}:10:", "hydrox", "allowed"}},
        BadInput{"wrong_type_string_for_integer",
                 case_text(kK, kQ, "cells = \"many\""),
                 "{CASE}",
                 {"{CASE}:9:", "hydro.cells", "\"many\"", "an integer"}},
        BadInput{"wrong_type_real_for_integer",
                 case_text(kK, kQ, "cells = 64.5"),
                 "{CASE}",
                 {"{CASE}:9:", "hydro.cells", "64.5", "an integer"}},
        BadInput{"wrong_type_string_for_real",
                 case_text("\"big\"", kQ, "cells = 64"),
                 "{CASE}",
                 {"{CASE}:5:", "physics.K", "\"big\"", "a real"}},
        BadInput{"K_zero",
                 case_text("0", kQ, "cells = 64"),
                 "{CASE}",
                 {"{CASE}:5:", "physics.K = 0", "(0, 100]"}},
        BadInput{"K_negative",
                 case_text("-1e-3", kQ, "cells = 64"),
                 "{CASE}",
                 {"{CASE}:5:", "physics.K = -0.001", "(0, 100]"}},
        BadInput{"q_zero",
                 case_text(kK, "0.0", "cells = 64"),
                 "{CASE}",
                 {"{CASE}:6:", "physics.q = 0", "(0, 0.5]"}},
        BadInput{"q_negative",
                 case_text(kK, "-0.1", "cells = 64"),
                 "{CASE}",
                 {"{CASE}:6:", "physics.q = -0.1", "(0, 0.5]"}},
        BadInput{"q_above_half",
                 case_text(kK, "0.6", "cells = 64"),
                 "{CASE}",
                 {"{CASE}:6:", "physics.q = 0.6", "(0, 0.5]"}},
        BadInput{"cells_below_4",
                 case_text(kK, kQ, "cells = 3"),
                 "{CASE}",
                 {"{CASE}:9:", "hydro.cells = 3", "[4, 1e7]"}},
        BadInput{"output_times_beyond_t_end_in_file",
                 case_text(kK, kQ, "t_end = 1.0\noutput_times = [0.5, 2.0]"),
                 "{CASE}",
                 {"{CASE}:10:", "hydro.output_times", "2.0", "hydro.t_end = 1.0", "<="}},
        BadInput{"toml_syntax_error",
                 case_text(kK, kQ, "cells = = 3"),
                 "{CASE}",
                 {"{CASE}:9:", "syntax"}},
        BadInput{"missing_case_file",
                 "",
                 "{DIR}/no_such_case.toml",
                 {"{DIR}/no_such_case.toml", "not found"}},
        BadInput{"unknown_scene_name", "", "no_such_scene", {"'no_such_scene'", "not found"}},
        // --set: the message names the --set argument, the key, the value and what is allowed.
        BadInput{"set_without_equals", "", "--set physics.K", {"--set", "physics.K", "KEY=VALUE"}},
        BadInput{"set_without_dotted_key", "", "--set K=1e-3", {"--set", "K=1e-3", "KEY=VALUE"}},
        BadInput{"set_unknown_key",
                 "",
                 "--set physics.Kx=1",
                 {"--set physics.Kx=1", "'physics.Kx'", "allowed in [physics]: K, q"}},
        BadInput{"set_unknown_key_on_file",
                 case_text(kK, kQ, "cells = 64"),
                 "{CASE} --set hydro.cels=64",
                 {"--set hydro.cels=64", "'hydro.cels'"}},
        BadInput{"set_wrong_type",
                 "",
                 "--set hydro.cells=abc",
                 {"--set hydro.cells=abc", "hydro.cells", "abc", "an integer"}},
        // The closure keys (docs/physics.md §9).
        BadInput{"closure_unknown",
                 "",
                 "single_mode --set hydro.closure=van_der_waals",
                 {"--set hydro.closure=van_der_waals", "hydro.closure", "van_der_waals",
                  "dilute, enskog"}},
        BadInput{"cooling_unknown",
                 "",
                 "single_mode --set physics.cooling=large_q",
                 {"--set physics.cooling=large_q", "physics.cooling", "large_q", "small_q, exact"}},
        BadInput{"enskog_without_area_fraction",
                 "",
                 "single_mode --set hydro.closure=enskog",
                 {"single_mode.toml", "physics.area_fraction = 0", "hydro.closure = \"enskog\"",
                  "(0, 0.69)"}},
        BadInput{"enskog_area_fraction_at_freezing",
                 "",
                 "single_mode --set hydro.closure=enskog --set physics.area_fraction=0.69",
                 {"--set physics.area_fraction=0.69", "physics.area_fraction = 0.69", "(0, 0.69)"}},
        BadInput{"area_fraction_contradicts_particle_scene",
                 "",
                 "quickstart --set hydro.closure=enskog --set physics.area_fraction=0.1",
                 {"--set physics.area_fraction=0.1", "physics.area_fraction = 0.1",
                  "md.area_fraction = 0.05"}},
        BadInput{
            "set_K_negative", "", "--set physics.K=-1", {"--set", "physics.K = -1", "(0, 100]"}},
        BadInput{"set_q_above_half",
                 "",
                 "--set physics.q=0.6",
                 {"--set", "physics.q = 0.6", "(0, 0.5]"}},
        BadInput{"set_cells_below_4",
                 "",
                 "--set hydro.cells=2",
                 {"--set", "hydro.cells = 2", "[4, 1e7]"}},
        BadInput{"set_output_times_beyond_t_end",
                 "",
                 "--set 'hydro.output_times=[1,5]'",
                 {"--set", "hydro.output_times", "5", "hydro.t_end = 4.0"}},
        // single_mode's own output times all lie beyond t = 0.5; the message names the last
        // one (whatever the file says) and where it came from.
        BadInput{"set_t_end_before_output_times",
                 "",
                 "single_mode --set hydro.t_end=0.5",
                 {"--set hydro.t_end=0.5", "hydro.t_end = 0.5", "the last being",
                  "cases/single_mode.toml:"}},
        BadInput{"compare_without_md",
                 "",
                 "single_mode --set compare.enabled=true",
                 {"compare.enabled", "md.enabled = true"}},
        BadInput{"compare_with_hydro_output_times",
                 "",
                 "--set 'hydro.output_times=[0.1]'",
                 {"hydro.output_times", "must be empty when compare.enabled"}},
        BadInput{"compare_from_md_needs_t0_snapshot",
                 "",
                 "--set 'md.output_times=[10, 20]'",
                 {"md.output_times", "must start at 0"}},
        BadInput{"density_modes_beyond_nyquist",
                 "",
                 "--set compare.density_modes=10",
                 {"compare.density_modes = 10", "md.bins / 2 = 10"}},
        BadInput{
            "time_unit_unknown", "", "--set md.time_unit='s'", {"md.time_unit", "one of md, haff"}},
        BadInput{"set_on_named_scene",
                 "",
                 "single_mode --set hydro.cells=3",
                 {"hydro.cells = 3", "[4, 1e7]"}},
        // Issue 9: integers beyond an int are refused with their key and range, not truncated.
        BadInput{"cells_beyond_int",
                 "",
                 "single_mode --set hydro.cells=4294967300",
                 {"hydro.cells = 4294967300", "[4, 1e7]"}},
        BadInput{"mode_beyond_int",
                 "",
                 "linear_mode --set initial.mode=4294967297",
                 {"initial.mode = 4294967297", "[1, 2147483647]"}},
        BadInput{"convergence_cells_beyond_int",
                 "",
                 "single_mode --set 'convergence.cells=[5,15,4294967295]'",
                 {"convergence.cells", "element 3 is 4294967295"}},
        BadInput{"density_modes_beyond_int",
                 "",
                 "--set compare.density_modes=4294967296",
                 {"compare.density_modes = 4294967296", "[0, 10000]"}},
        BadInput{"series_every_beyond_int",
                 "",
                 "single_mode --set hydro.series_every=4294967296",
                 {"hydro.series_every = 4294967296", "[1, 2147483647]"}},
        BadInput{"ensemble_beyond_int",
                 "",
                 "md_cooling_sweep --set md.ensemble=4294967296",
                 {"md.ensemble = 4294967296", "[1, 1000]"}},
        // Measurements the configuration cannot deliver.
        BadInput{"mode_not_resolved",
                 "",
                 "linear_mode --set initial.mode=100000",
                 {"initial.mode = 100000", "hydro.cells = 1000", "<= hydro.cells / 4 = 250"}},
        BadInput{"sample_interval_below_step",
                 "",
                 "md_cooling_sweep --set md.sample_interval=1e-7",
                 {"md.sample_interval = 1e-7", "below the particle time step"}},
        // Hangs and hopeless work, refused before anything runs.
        BadInput{"convergence_past_singularity",
                 "",
                 "single_mode --set initial.velocity_amplitude=-0.2",
                 {"initial.velocity_amplitude = -0.2", "flow-by-inertia singularity", "0.7957"}},
        BadInput{"haff_units_without_cooling",
                 "",
                 "md_cooling_sweep --set md.restitution=1",
                 {"md.restitution = 1.0", "Haff time is infinite"}},
        BadInput{
            "K_overflows", "", "haff --set physics.K=1e154", {"physics.K = 1e154", "(0, 100]"}},
        BadInput{"dt_max_hopeless",
                 "",
                 "haff --set hydro.dt_max=1e-300",
                 {"hydro.dt_max = 1e-300", "cell-steps", "the limit is 1e+12"}},
        BadInput{"t_end_hopeless",
                 "",
                 "haff --set hydro.t_end=1e300",
                 {"hydro.t_end = 1e300", "cell-steps"}},
        BadInput{"convergence_t_hopeless",
                 "",
                 "single_mode --set convergence.t=1e300",
                 {"convergence.t = 1e300"}},
        BadInput{"max_compression_hopeless",
                 "",
                 "single_mode --set hydro.max_compression=1e-300",
                 {"hydro.max_compression = 1e-300", "[1e-6, 0.5]"}},
        BadInput{"cells_beyond_memory",
                 "",
                 "single_mode --dry-run --set hydro.cells=1000000000",
                 {"hydro.cells = 1000000000", "[4, 1e7]"}},
        // Issue 15: no fixed cap on the disks; a scene is refused when one rank would need more
        // memory than the machine has (5e8 disks: ~350 GB), or when its work is beyond what
        // can finish here and md.accept_long_run is not set.
        BadInput{"md_particles_beyond_memory",
                 "",
                 "md_haff --dry-run --set md.particles=500000000",
                 {"md.particles = 500000000", "needs more memory than this machine has",
                  "atom-steps", "GB of memory"}},
        BadInput{
            "md_long_run_not_accepted",
            "",
            "md_paper_wide --dry-run --set md.accept_long_run=false",
            {"md.t_end = 141796.3", "atom-steps", "wall time", "set md.accept_long_run = true"}},
        BadInput{"random_modes_beyond_mesh",
                 "",
                 "clustering --dry-run --set initial.random_modes=100000000",
                 {"initial.random_modes = 100000000", "<= hydro.cells / 4"}},
        BadInput{"md_r_zero_names_q",
                 "",
                 "md_cooling_sweep --set physics.q=0.5 --set md.restitution=0",
                 {"--set physics.q=0.5: physics.q = 0.5", "restitution 0"}},
        BadInput{"md_K_out_of_particle_range",
                 "",
                 "md_single_mode --set physics.K=1e-6",
                 {"--set physics.K=1e-6: physics.K = 1e-6", "particles"}},
        BadInput{"case_file_is_a_directory", "", "{DIR}", {"{DIR}", "is a directory"}},
        BadInput{"comparison_without_hydro",
                 "",
                 "md_haff --set hydro.enabled=false",
                 {"compare.enabled", "hydro.enabled = true", "runs both"}},
        BadInput{"nothing_to_run",
                 "",
                 "haff --set hydro.enabled=false",
                 {"hydro.enabled", "runs nothing"}}),
    [](const ::testing::TestParamInfo<BadInput>& info) { return info.param.name; });

// The contract: "Nothing already written is lost."
TEST(CliBadInputKeepsOutput, RejectedRunLeavesAnExistingFolderUntouched) {
  ScratchFolder scratch("bad-keeps-output");
  const fs::path out = scratch.path / "out";
  fs::create_directories(out);
  write_file(out / "summary.json", "{\"earlier\": true}\n");
  const CliStreams r = run_cli_streams("run --set physics.K=0 --out " + q(out));
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_EQ(read_text(out / "summary.json"), "{\"earlier\": true}\n");
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(out)) files.push_back(e.path().filename().string());
  EXPECT_EQ(files, std::vector<std::string>{"summary.json"});
}

// `granvv sweep`: every point's case is checked before anything runs; bad input is one line,
// exit 2, and the output folder is not created.
TEST(CliSweep, BadSweepsExitTwoWithOneLineAndWriteNothing) {
  ScratchFolder scratch("sweep-bad");
  const fs::path out = scratch.path / "sweep";
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"md_cooling_sweep --set md.restitution=0.9", {"one --set KEY=V1,V2"}},
      {"md_cooling_sweep --set md.restitution=0.5,1.5", {"md.restitution = 1.5", "[0, 1]"}},
      {"md_cooling_sweep --set md.kernel=bin,lucy", {"md.kernel", "only numeric keys"}},
      {"md_cooling_sweep --set md.restitution=0.5,0.7 --set md.seed=1,2", {"only one key"}},
      {"md_cooling_sweep --set md.frobnicate=1,2", {"md.frobnicate"}},
      {"no_such_scene --set md.restitution=0.5,0.7", {"no_such_scene"}},
  };
  for (const auto& [args, expected] : cases) {
    SCOPED_TRACE(args);
    const CliStreams r = run_cli_streams("sweep " + args + " --out " + q(out));
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    const auto lines = lines_of(r.err);
    ASSERT_EQ(lines.size(), 1u) << describe(r);
    EXPECT_TRUE(starts_with(lines[0], "granvv: error: ")) << lines[0];
    for (const auto& e : expected) EXPECT_TRUE(contains(lines[0], e)) << lines[0];
    EXPECT_FALSE(fs::exists(out)) << "a rejected sweep created its folder";
  }
}

// A key that another particle engine declares as its own (md_bridge/*_engine.cpp, keys()) is
// refused where the case runs one engine: in `run` (--dry-run too) and in every point of a
// `sweep`, whether it comes from --set or from the case file; one line, exit 2, nothing
// written. --dry-run lists every engine's keys.
TEST(CliModelKeys, AKeyOfTheEngineTheCaseDoesNotRunIsRefused) {
  ScratchFolder scratch("model-keys");
  const fs::path out = scratch.path / "out";
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"run md_paper_scene --dry-run --set md.max_overlap=0.02",
       {"--set md.max_overlap=0.02: md.max_overlap = 0.02: a key of md.engine = \"lammps\", "
        "but this case runs md.engine = \"event_driven\" (from "}},
      {"run md_paper_scene --set md.max_overlap=0.02 --out " + q(out),
       {"md.max_overlap = 0.02", "md.engine = \"event_driven\""}},
      {"run md_cooling_sweep --set md.engine=event_driven --out " + q(out),
       {"md_cooling_sweep.toml:", "md.max_overlap = 0.02: a key of md.engine = \"lammps\"",
        "(from --set md.engine=event_driven)"}},
      {"sweep md_paper_scene --set md.max_overlap=0.005,0.02 --out " + q(out),
       {"md.max_overlap = 0.005: a key of md.engine = \"lammps\""}},
      {"sweep md_haff --set md.collapse_speed=0.1,1 --out " + q(out),
       {"md.collapse_speed = 0.1: a key of md.engine = \"event_driven\"",
        "md.engine = \"lammps\" (default)"}},
  };
  for (const auto& [args, expected] : cases) {
    SCOPED_TRACE(args);
    const CliStreams r = run_cli_streams(args);
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    const auto lines = lines_of(r.err);
    ASSERT_EQ(lines.size(), 1u) << describe(r);
    EXPECT_TRUE(starts_with(lines[0], "granvv: error: ")) << lines[0];
    for (const auto& e : expected) EXPECT_TRUE(contains(lines[0], e)) << lines[0];
    EXPECT_FALSE(fs::exists(out)) << "a refused case created its folder";
  }
  // The engine's own keys pass, and --dry-run lists both engines' keys with their defaults.
  const CliStreams own =
      run_cli_streams("run md_paper_scene --dry-run --set md.collapse_speed=0.1");
  ASSERT_EQ(own.exit_code, 0) << describe(own);
  for (const char* line :
       {"\nmax_overlap = 0.01 ", "\nsteps_per_contact = 30 ", "\nadaptive_stiffness = true ",
        "\ncollapse_speed = 0.1 ", "\nmax_collision_rate = 2.0 "}) {
    EXPECT_TRUE(contains(own.out, line)) << line;
  }
}

TEST(CliReportCommand, FolderWithoutResultsExitsTwo) {
  ScratchFolder scratch("report-no-results");
  const CliStreams r = run_cli_streams("report " + q(scratch.path));
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  const auto lines = lines_of(r.err);
  ASSERT_EQ(lines.size(), 1u) << describe(r);
  EXPECT_TRUE(starts_with(lines[0], "granvv: error: ")) << lines[0];
  EXPECT_TRUE(contains(lines[0], scratch.path.string())) << lines[0];
  EXPECT_TRUE(contains(lines[0], "results.h5")) << lines[0];
  EXPECT_TRUE(fs::is_empty(scratch.path)) << "report wrote into a folder without results";

  const CliStreams missing = run_cli_streams("report " + q(scratch.path / "no_such_folder"));
  EXPECT_EQ(missing.exit_code, 2) << describe(missing);
  EXPECT_FALSE(fs::exists(scratch.path / "no_such_folder"));
}

TEST(CliUsage, UnknownSubcommandOrOptionFails) {
  ScratchFolder scratch("usage");
  const fs::path out = scratch.path / "out";
  for (const std::string& args :
       std::vector<std::string>{"frobnicate", "run --frobnicate --out " + q(out), "run --set",
                                "report", "list extra", ""}) {
    SCOPED_TRACE("granvv " + args);
    const CliStreams r = run_cli_streams(args, scratch.path);
    EXPECT_NE(r.exit_code, 0) << describe(r);
    EXPECT_FALSE(r.err.empty()) << "a usage error should say what is wrong";
  }
  EXPECT_TRUE(fs::is_empty(scratch.path)) << "a usage error wrote files";
}

TEST(CliUsage, UnknownCommandIsNamed) {
  const CliStreams r = run_cli_streams("frobnicate");
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_EQ(r.err,
            "granvv: error: unknown command 'frobnicate'; the commands are run, resume, sweep, "
            "atlas, list, report, movie (granvv --help)\n");
}

// Non-UTF-8 bytes: refused in case.name itself; a case file's name with them gives a case.name
// whose bad bytes are '_', and summary.json and case.toml stay valid text.
TEST(CliText, NonUtf8NamesNeverAbort) {
  ScratchFolder scratch("non-utf8");
  const fs::path out = scratch.path / "out";
  const CliStreams bad = run_cli_streams(
      "run haff --set \"case.name=$(printf 'a\\377b')\" --out " + q(out), scratch.path);
  EXPECT_EQ(bad.exit_code, 2) << describe(bad);
  EXPECT_TRUE(contains(bad.err, "must be valid UTF-8 text")) << bad.err;
  EXPECT_FALSE(fs::exists(out));

  std::string text = read_text(fs::path(GRANVV_SOURCE_DIR) / "cases" / "haff.toml");
  text = std::regex_replace(text, std::regex("\nname = \"haff\"\n"), "\n");
  const std::string stem = "x\xff\x01y";
  write_file(scratch.path / (stem + ".toml"), text);
  const CliStreams r = run_cli_streams(
      "run \"$(printf 'x\\377\\001y').toml\" --no-report --quiet --out " + q(out), scratch.path);
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary["case"], "x__y");
  const CliStreams again =
      run_cli_streams("run " + q(out / "case.toml") + " --dry-run", scratch.path);
  EXPECT_EQ(again.exit_code, 0) << describe(again);
}

TEST(CliUsage, HelpListsTheRunOptions) {
  const CliStreams r = run_cli_streams("run --help");
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  for (const char* option : {"--out", "--set", "--dry-run", "--quiet", "--no-report"}) {
    EXPECT_TRUE(contains(r.out, option)) << option << " missing from\n" << r.out;
  }
  const CliStreams top = run_cli_streams("--help");
  EXPECT_EQ(top.exit_code, 0) << describe(top);
  for (const char* sub : {"run", "list", "report"}) {
    EXPECT_TRUE(contains(top.out, sub)) << sub << " missing from\n" << top.out;
  }
}

// ---------------------------------------------------------------------------------------------
// 2. --dry-run
// ---------------------------------------------------------------------------------------------

// Compares a node of the resolved TOML with a schema default.
void expect_equals_default(const toml::node* node, const app::KeySpec& spec) {
  ASSERT_NE(node, nullptr) << spec.key;
  const app::Value& v = spec.default_value.value;
  switch (spec.type) {
    case app::ValueType::real: {
      const double expected = std::holds_alternative<long long>(v)
                                  ? static_cast<double>(std::get<long long>(v))
                                  : std::get<double>(v);
      ASSERT_TRUE(node->is_number()) << spec.key;
      EXPECT_DOUBLE_EQ(node->value<double>().value(), expected) << spec.key;
      break;
    }
    case app::ValueType::integer:
      ASSERT_TRUE(node->is_integer()) << spec.key;
      EXPECT_EQ(node->value<std::int64_t>().value(), std::get<long long>(v)) << spec.key;
      break;
    case app::ValueType::boolean:
      ASSERT_TRUE(node->is_boolean()) << spec.key;
      EXPECT_EQ(node->value<bool>().value(), std::get<bool>(v)) << spec.key;
      break;
    case app::ValueType::string:
      ASSERT_TRUE(node->is_string()) << spec.key;
      EXPECT_EQ(node->value<std::string>().value(), std::get<std::string>(v)) << spec.key;
      break;
    default:
      break;  // array defaults are the empty array
  }
}

TEST(CliDryRun, PrintsTheResolvedQuickstartAndWritesNothing) {
  ScratchFolder scratch("dry-run");
  const fs::path out = scratch.path / "out-folder";
  const CliStreams r = run_cli_streams("run --dry-run --out " + q(out), scratch.path);
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.err, "");
  EXPECT_TRUE(contains(r.out, "K = 0.02")) << r.out;
  EXPECT_TRUE(contains(r.out, "[hydro]")) << r.out;
  EXPECT_TRUE(contains(r.out, "[compare]")) << r.out;

  const toml::table resolved = parse_toml(r.out, "dry-run output");
  const toml::table quickstart =
      toml::parse_file(std::string(GRANVV_SOURCE_DIR) + "/cases/quickstart.toml");
  EXPECT_EQ(resolved["case"]["name"].value<std::string>(), "quickstart");
  EXPECT_EQ(resolved["physics"]["K"].value<double>(), 2e-2);
  EXPECT_EQ(resolved["physics"]["q"].value<double>(), 0.05);
  EXPECT_EQ(resolved["compare"]["enabled"].value<bool>(), true);

  // Every key of the schema, the file's values where it has them, the defaults elsewhere.
  std::size_t hydro_keys = 0;
  for (const app::KeySpec& spec : app::case_schema()) {
    SCOPED_TRACE(spec.key);
    const toml::node* node = resolved.at_path(spec.key).node();
    ASSERT_NE(node, nullptr) << spec.key << " missing from the resolved case\n" << r.out;
    if (spec.section() == "hydro") ++hydro_keys;
    if (const toml::node* given = quickstart.at_path(spec.key).node()) {
      if (given->is_number()) {
        EXPECT_DOUBLE_EQ(node->value<double>().value_or(NAN), given->value<double>().value());
      } else if (given->is_string()) {
        EXPECT_EQ(node->value<std::string>(), given->value<std::string>());
      }
    } else if (spec.default_value.kind == app::Default::Kind::value) {
      expect_equals_default(node, spec);
    }
  }
  ASSERT_TRUE(resolved["hydro"].is_table());
  EXPECT_EQ(resolved["hydro"].as_table()->size(), hydro_keys) << "keys outside the schema";
  EXPECT_GE(hydro_keys, 13u);
  // Values are compared with the file above; here, that each [hydro] key is printed.
  for (const char* key : {"cells = ", "t_end = ", "output_times = [",
                          "cfl = ", "max_compression = ", "max_temperature_change = ", "dt_max = ",
                          "stop_density = ", "min_cell_width = ", "transverse_velocity = true",
                          "node_offset = ", "progress_seconds = ", "series_every = 1"}) {
    EXPECT_TRUE(contains(r.out, key)) << key;
  }

  EXPECT_FALSE(fs::exists(out)) << "--dry-run created the output folder";
  EXPECT_TRUE(fs::is_empty(scratch.path)) << "--dry-run wrote into the working directory";
}

TEST(CliDryRun, ShowsASetOverride) {
  ScratchFolder scratch("dry-run-set");
  const CliStreams r = run_cli_streams("run --set physics.K=1e-3 --dry-run", scratch.path);
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(contains(r.out, "K = 0.001")) << r.out;
  EXPECT_FALSE(contains(r.out, "K = 0.02")) << r.out;
  EXPECT_TRUE(contains(r.out, "--set physics.K=1e-3")) << "the override is recorded\n" << r.out;
  const toml::table resolved = parse_toml(r.out, "dry-run output");
  EXPECT_EQ(resolved["physics"]["K"].value<double>(), 1e-3);
  EXPECT_EQ(resolved["physics"]["q"].value<double>(), 0.05);
  EXPECT_TRUE(fs::is_empty(scratch.path));
}

TEST(CliDryRun, AcceptsAnArrayOverride) {
  const CliStreams r =
      run_cli_streams("run single_mode --dry-run --set 'hydro.output_times=[1,2,3.225]'");
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(contains(r.out, "output_times = [1.0, 2.0, 3.225]")) << r.out;
  const toml::table resolved = parse_toml(r.out, "dry-run output");
  const toml::array* times = resolved["hydro"]["output_times"].as_array();
  ASSERT_NE(times, nullptr);
  ASSERT_EQ(times->size(), 3u);
  EXPECT_EQ((*times)[0].value<double>(), 1.0);
  EXPECT_EQ((*times)[1].value<double>(), 2.0);
  EXPECT_EQ((*times)[2].value<double>(), 3.225);
  EXPECT_EQ(resolved["case"]["name"].value<std::string>(), "single_mode");
}

// Issue 15: the paper's scene in a 1000 sigma channel (2.8e6 disks, above the former 2e6 cap)
// is not refused; its dry run ends with the work estimate per rank as a TOML comment, the
// atom-steps of which are N x steps with steps = (t0/dt0) ln(1 + t_end/t0) (particle_work.hpp),
// and its work, above the 1e13 atom-steps of a run that finishes here, is accepted by
// md.accept_long_run = true in the case file.
TEST(CliDryRun, WideScenePrintsItsWorkEstimate) {
  const CliStreams r = run_cli_streams("run md_paper_wide --dry-run");
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const toml::table resolved = parse_toml(r.out, "dry-run output");
  EXPECT_EQ(resolved["md"]["accept_long_run"].value<bool>(), true);
  const std::regex estimate(
      "# md work estimate per rank \\(1 rank\\): ([0-9.e+]+) atom-steps, ([0-9.]+) GB of memory "
      "\\(this machine has ([0-9.]+) GB\\), about ([0-9.]+) days of wall time");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, estimate)) << r.out;
  const double atom_steps = std::stod(m[1]), gigabytes = std::stod(m[2]);
  EXPECT_GT(atom_steps, 1e13);  // beyond the limit, so accepted only by the key
  EXPECT_LT(atom_steps, 1e15);
  EXPECT_GT(gigabytes, 2.82e6 * 500 / 1e9);  // at least the LAMMPS atoms' few hundred bytes each
  EXPECT_LT(gigabytes, std::stod(m[3]));
  EXPECT_NEAR(std::stod(m[4]), atom_steps / 7.1e7 / 86400, 0.01 * atom_steps / 7.1e7 / 86400);
}

TEST(CliDryRun, LastSetOfAKeyWins) {
  const CliStreams r = run_cli_streams("run --dry-run --set hydro.cells=100 --set hydro.cells=200");
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const toml::table resolved = parse_toml(r.out, "dry-run output");
  EXPECT_EQ(resolved["hydro"]["cells"].value<std::int64_t>(), 200);
}

// ---------------------------------------------------------------------------------------------
// 3. granvv list
// ---------------------------------------------------------------------------------------------
TEST(CliList, ListsTheScenesWithTheirDescriptions) {
  const CliStreams r = run_cli_streams("list");
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const auto lines = lines_of(r.out);
  std::set<std::string> scenes;
  for (const auto& e : fs::directory_iterator(fs::path(GRANVV_SOURCE_DIR) / "cases")) {
    if (e.path().extension() == ".toml") scenes.insert(e.path().stem().string());
  }
  EXPECT_TRUE(scenes.count("quickstart"));
  EXPECT_TRUE(scenes.count("single_mode"));
  for (const std::string& scene : scenes) {
    SCOPED_TRACE(scene);
    const toml::table t =
        toml::parse_file((fs::path(GRANVV_SOURCE_DIR) / "cases" / (scene + ".toml")).string());
    const std::string description = t["case"]["description"].value_or(std::string());
    EXPECT_FALSE(description.empty());
    bool found = false;
    for (const auto& line : lines) {
      found |= starts_with(line, scene + " ") && contains(line, description);
    }
    EXPECT_TRUE(found) << "no line '" << scene << "  " << description << "' in\n" << r.out;
  }
}

// ---------------------------------------------------------------------------------------------
// 4. A real small run and its output folder
// ---------------------------------------------------------------------------------------------
class CliSmallRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(fresh_directory("small-run"));
    result_ = new CliStreams(
        run_cli_streams("run single_mode --no-report --out " + q(dir()) + " " + kSmall, *root_));
  }
  static void TearDownTestSuite() {
    const auto* suite = ::testing::UnitTest::GetInstance()->current_test_suite();
    if (suite && !suite->failed_test_count()) {
      std::error_code ec;
      fs::remove_all(*root_, ec);
    }
    delete result_;
    delete root_;
  }
  static fs::path dir() { return *root_ / "run"; }
  static const CliStreams& result() { return *result_; }
  static json summary() {
    const std::string text = read_text(dir() / "summary.json");
    json j = json::parse(text, nullptr, false);
    EXPECT_FALSE(j.is_discarded()) << "summary.json is not JSON:\n" << text;
    return j;
  }

  static fs::path* root_;
  static CliStreams* result_;
};
fs::path* CliSmallRun::root_ = nullptr;
CliStreams* CliSmallRun::result_ = nullptr;

TEST_F(CliSmallRun, ExitsZeroAndFillsTheOutputFolder) {
  ASSERT_EQ(result().exit_code, 0) << describe(result());
  for (const char* file : {"results.h5", "summary.json", "run.log", "case.toml"}) {
    EXPECT_TRUE(fs::is_regular_file(dir() / file)) << file << " missing in " << dir();
    EXPECT_GT(fs::file_size(dir() / file), 0u) << file;
  }
  EXPECT_TRUE(has_signature(dir() / "results.h5", kHdf5Magic)) << "results.h5 is not HDF5";
  EXPECT_FALSE(fs::exists(dir() / "report.html")) << "--no-report wrote a report";
  for (const auto& e : fs::directory_iterator(dir())) {
    EXPECT_NE(e.path().extension(), ".partial") << "left behind: " << e.path();
  }
  EXPECT_FALSE(fs::exists(*root_ / "out")) << "--out was ignored";
}

TEST_F(CliSmallRun, SummaryJsonFollowsTheContract) {
  ASSERT_EQ(result().exit_code, 0) << describe(result());
  json s = summary();
  ASSERT_TRUE(s.is_object());
  EXPECT_EQ(s.value("case", ""), "single_mode");
  ASSERT_TRUE(s["status"].is_string());
  const std::string status = s["status"];
  EXPECT_TRUE(status == "ok" || status == "singularity") << status;
  EXPECT_TRUE(s.contains("md") && s["md"].is_null()) << s.dump(2);
  EXPECT_TRUE(s.contains("compare") && s["compare"].is_null()) << s.dump(2);

  ASSERT_TRUE(s["hydro"].is_object()) << s.dump(2);
  json& h = s["hydro"];
  EXPECT_EQ(h["status"], s["status"]);
  ASSERT_TRUE(h["wall_seconds"].is_number()) << h.dump(2);
  EXPECT_GE(h["wall_seconds"].get<double>(), 0.0);
  EXPECT_TRUE(h["cells"].is_number_integer());
  EXPECT_EQ(h["cells"], 64);
  ASSERT_TRUE(h["steps"].is_number_integer()) << h.dump(2);
  EXPECT_GT(h["steps"].get<long long>(), 0);
  EXPECT_EQ(h["unstable_modes"], 79) << "K = 4e-4, q = 0.01 has 79 unstable modes (the paper)";
  EXPECT_TRUE(h.contains("singularity_time"));
  EXPECT_TRUE(h["singularity_time"].is_null() || h["singularity_time"].is_number());
  if (status == "ok") {
    EXPECT_TRUE(h["singularity_time"].is_null()) << h.dump(2);
  }

  ASSERT_TRUE(h["peak_density_times"].is_object()) << h.dump(2);
  std::set<std::string> keys;
  for (const auto& [key, value] : h["peak_density_times"].items()) {
    keys.insert(key);
    EXPECT_TRUE(value.is_null() || value.is_number()) << key << ": " << value;
  }
  EXPECT_EQ(keys, (std::set<std::string>{"10", "100", "1000", "1e6"}));

  ASSERT_TRUE(h["snapshots"].is_array()) << h.dump(2);
  ASSERT_EQ(h["snapshots"].size(), 1u) << "one snapshot per output time (0.25)";
  json& snap = h["snapshots"][0];
  for (const char* field : {"t", "n_max", "T_min", "energy", "energy_thermal", "energy_kinetic"}) {
    EXPECT_TRUE(snap.contains(field) && snap[field].is_number()) << field << " in " << snap.dump();
  }
  EXPECT_DOUBLE_EQ(snap.value("t", NAN), 0.25);
  EXPECT_GE(snap.value("n_max", NAN), 1.0);
  EXPECT_GT(snap.value("T_min", NAN), 0.0);
  // value(key, NAN) would read a float (NAN is one): the energies as the doubles they are.
  EXPECT_NEAR(snap["energy"].get<double>(),
              snap["energy_thermal"].get<double>() + snap["energy_kinetic"].get<double>() +
                  snap.value("energy_kinetic_y", 0.0),
              1e-12 * std::abs(snap["energy"].get<double>()));
}

// The derived numbers and verdicts the report reads instead of recomputing them.
TEST_F(CliSmallRun, SummaryJsonCarriesTheReportsThresholdsAndVerdicts) {
  ASSERT_EQ(result().exit_code, 0) << describe(result());
  json h = summary()["hydro"];
  ASSERT_TRUE(h.is_object());
  // Paper: pi k K < sqrt(q), K = 4e-4, q = 0.01: k_c = 0.1 / (pi 4e-4) = 79.577...
  EXPECT_NEAR(h["clustering_cutoff_mode"].get<double>(), 0.1 / (std::acos(-1.0) * 4e-4), 1e-12);
  EXPECT_EQ(h["collapse_tolerance"].get<double>(), 0.015) << "analysis.collapse_tolerance default";
  EXPECT_EQ(h["singularity_time_tolerance"].get<double>(), 0.02) << "paper Fig. 4a: within 2 %";
  const json& snap = h["snapshots"].at(0);
  ASSERT_TRUE(snap["collapse_error"].is_number()) << snap.dump();
  const double error = snap["collapse_error"];
  EXPECT_EQ(h["collapse_error_max"].get<double>(), error) << "one snapshot";
  EXPECT_EQ(snap["collapse_within_tolerance"], error <= 0.015);
  EXPECT_EQ(h["collapse_within_tolerance"], error <= 0.015);
  if (h["singularity_time_deviation"].is_null()) {
    EXPECT_TRUE(h["singularity_time_within_tolerance"].is_null()) << "nothing to judge";
  }
}

TEST(CliCollapseTolerance, TheCaseToleranceDecidesTheCollapseVerdict) {
  ScratchFolder scratch("collapse-tolerance");
  const fs::path out = scratch.path / "run";
  // A tolerance below any discrete collapse error: the same run now fails the collapse.
  const CliStreams r = run_cli_streams("run single_mode --quiet --no-report --out " + q(out) + " " +
                                       kSmall + " --set analysis.collapse_tolerance=1e-12");
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  json s = json::parse(read_text(out / "summary.json"), nullptr, false);
  ASSERT_TRUE(s["hydro"].is_object()) << s.dump(2);
  EXPECT_EQ(s["hydro"]["collapse_tolerance"].get<double>(), 1e-12);
  EXPECT_EQ(s["hydro"]["collapse_within_tolerance"], false);
  EXPECT_EQ(s["hydro"]["snapshots"].at(0)["collapse_within_tolerance"], false);
}

TEST_F(CliSmallRun, StderrHasProgressStopReasonAndThroughput) {
  ASSERT_EQ(result().exit_code, 0) << describe(result());
  const std::string& err = result().err;
  EXPECT_TRUE(contains(err, "step ")) << "no progress line:\n" << err;
  EXPECT_TRUE(contains(err, "hydro stopped: end time reached")) << err;
  EXPECT_TRUE(contains(err, "cell-steps/s")) << err;
  // No log line at error level (the resolved case's comments may use the word itself).
  EXPECT_FALSE(contains(err, "\nerror: ") || err.rfind("error: ", 0) == 0) << err;
}

TEST_F(CliSmallRun, RunLogRecordsTheRun) {
  ASSERT_EQ(result().exit_code, 0) << describe(result());
  const std::string log = read_text(dir() / "run.log");
  EXPECT_TRUE(contains(log, "running case 'single_mode'")) << log;
  EXPECT_TRUE(contains(log, "hydro stopped:")) << log;
  EXPECT_TRUE(contains(log, "cell-steps/s")) << log;
  EXPECT_TRUE(contains(log, "cells = 64")) << "the resolved case is logged";
}

TEST_F(CliSmallRun, ResolvedCaseFileRunsAgain) {
  ASSERT_EQ(result().exit_code, 0) << describe(result());
  const std::string written = read_text(dir() / "case.toml");
  EXPECT_TRUE(contains(written, "cells = 64")) << written;
  EXPECT_TRUE(contains(written, "--set hydro.cells=64")) << "the overrides are recorded";
  const CliStreams again = run_cli_streams("run " + q(dir() / "case.toml") + " --dry-run");
  ASSERT_EQ(again.exit_code, 0) << describe(again);
  // Resolving the resolved case changes nothing (only the header comment differs).
  EXPECT_EQ(parse_toml(again.out, "re-resolved case"), parse_toml(written, "case.toml"))
      << "--- case.toml ---\n"
      << written << "--- resolved again ---\n"
      << again.out;
}

TEST(CliQuiet, QuietRunWritesNothingOnStderr) {
  ScratchFolder scratch("quiet");
  const fs::path out = scratch.path / "run";
  const CliStreams r =
      run_cli_streams("run single_mode --quiet --no-report --out " + q(out) + " " + kSmall);
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.err, "") << "--quiet still printed on stderr";
  EXPECT_TRUE(fs::is_regular_file(out / "summary.json"));
  EXPECT_TRUE(contains(read_text(out / "run.log"), "hydro stopped:"))
      << "--quiet silences the console, not the log";
}

// ---------------------------------------------------------------------------------------------
// 5. The report (the one test that runs scripts/report.py)
// ---------------------------------------------------------------------------------------------
std::vector<std::string> image_sources(const std::string& html) {
  static const std::regex img(R"(<img\b[^>]*?\bsrc\s*=\s*["']([^"']*)["'])", std::regex::icase);
  std::vector<std::string> sources;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), img); it != std::sregex_iterator();
       ++it) {
    sources.push_back((*it)[1].str());
  }
  return sources;
}

TEST(CliReport, SmallRunReportReferencesExistingFigures) {
  ScratchFolder scratch("report");
  const fs::path out = scratch.path / "single_mode";
  const CliStreams r = run_cli_streams("run single_mode --quiet --out " + q(out) + " " + kSmall);
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  ASSERT_TRUE(fs::is_regular_file(out / "report.html")) << describe(r);

  const auto check_report = [&] {
    const std::string html = read_text(out / "report.html");
    const auto sources = image_sources(html);
    EXPECT_FALSE(sources.empty()) << "report.html has no <img>";
    for (const std::string& src : sources) {
      SCOPED_TRACE(src);
      EXPECT_TRUE(starts_with(src, "figures/")) << "figures are referenced relative to the folder";
      EXPECT_EQ(fs::path(src).extension(), ".png");
      EXPECT_TRUE(fs::is_regular_file(out / src)) << src << " referenced but missing";
      EXPECT_TRUE(has_signature(out / src, kPngMagic)) << src << " is not a PNG";
    }
  };
  check_report();

  // `granvv report DIR` rebuilds the report from results.h5.
  fs::remove(out / "report.html");
  const CliStreams rebuilt = run_cli_streams("report " + q(out));
  EXPECT_EQ(rebuilt.exit_code, 0) << describe(rebuilt);
  ASSERT_TRUE(fs::is_regular_file(out / "report.html")) << describe(rebuilt);
  check_report();
}

// ---------------------------------------------------------------------------------------------
// 6. `granvv run` with no case: the embedded quickstart
// ---------------------------------------------------------------------------------------------
TEST(CliDefaultScene, RunWithoutCaseRunsTheEmbeddedQuickstart) {
  ScratchFolder scratch("default-scene");
  const fs::path out = scratch.path / "run";
  const fs::path no_cases = scratch.path / "empty-cases";
  fs::create_directories(no_cases);
  // With an empty scene catalog, the quickstart must still come from the binary itself.
  ::setenv("GRANVV_CASES_DIR", no_cases.c_str(), 1);
  // The quickstart is a side-by-side scene; a narrower channel, one seed and a shorter run
  // keep this test to seconds (the full scene runs in the slow suite).
  const CliStreams r = run_cli_streams(
      "run --quiet --no-report --set hydro.cells=64 --set md.box_width=6 --set md.ensemble=1 "
      "--set md.t_end=40 --set 'md.output_times=[0, 20, 40]' --out " +
          q(out),
      scratch.path);
  ::unsetenv("GRANVV_CASES_DIR");
  ASSERT_EQ(r.exit_code, 0) << describe(r);

  json s = json::parse(read_text(out / "summary.json"), nullptr, false);
  ASSERT_TRUE(s.is_object()) << read_text(out / "summary.json");
  EXPECT_EQ(s.value("case", ""), "quickstart");
  const std::string status = s.value("status", "");
  EXPECT_TRUE(status == "ok" || status == "singularity") << status;
  EXPECT_EQ(s["hydro"]["cells"], 64);
  // Both engines ran and were compared at the particles' three snapshot times.
  ASSERT_TRUE(s["md"].is_object()) << s.dump(2);
  EXPECT_EQ(s["md"]["status"], "ok");
  ASSERT_TRUE(s["compare"].is_object()) << s.dump(2);
  EXPECT_EQ(s["compare"]["times"].size(), 3u);
  // Snapshots land on the nearest MD step (dt well below 0.1 here).
  EXPECT_NEAR(s["compare"]["times_md"][2].get<double>(), 40.0, 0.1);
  for (const char* field : {"n", "v_x", "T"}) {
    ASSERT_TRUE(s["compare"]["fields"].contains(field)) << field;
    EXPECT_EQ(s["compare"]["fields"][field]["l2"].size(), 3u) << field;
  }
  EXPECT_TRUE(s["compare"]["verdict"].is_string());
  // The verdict rule is written beside the verdict (compare/verdict.hpp): its offset threshold
  // is the case's compare.sigmas, its signal-to-noise threshold 3.
  const std::string kind = s["compare"].value("disagreement", "");
  EXPECT_TRUE(kind == "none" || kind == "model" || kind == "noise") << kind;
  EXPECT_EQ(s["compare"]["verdict_rule"]["signal_to_noise_min"], 3.0);
  EXPECT_EQ(s["compare"]["verdict_rule"]["offset_sigmas"], s["compare"]["sigmas"]);
  EXPECT_GT(s["compare"]["cost"]["md"]["atom_steps"].get<double>(), 0.0);
  EXPECT_TRUE(contains(read_text(out / "case.toml"), "embedded:cases/quickstart.toml"));
  ASSERT_TRUE(fs::is_regular_file(out / "results.h5"));
  EXPECT_FALSE(fs::exists(scratch.path / "out")) << "--out was ignored";

  // Both engines' fields are FieldSeries in the one layout (docs/outputs.md). Known answers:
  // each hydro cell's density times its width (from /hydro/lagrangian's nodes) is its mass, and
  // the particles' bins hold every disk (each member's counts add up to N, so does their mean).
  H5::H5File h5((out / "results.h5").string(), H5F_ACC_RDONLY);
  const fields::FieldSeries hydro = fields::read_field_series(h5.openGroup("/hydro/fields"));
  const fields::FieldSeries md = fields::read_field_series(h5.openGroup("/md/fields"));
  const H5::Group lagrangian = h5.openGroup("/hydro/lagrangian");
  const auto node_x = h5::read_doubles(lagrangian, "node_x");
  const auto mass = h5::read_doubles(lagrangian, "cell_mass").values;
  EXPECT_EQ(hydro.geometry, fields::Geometry::cells);
  ASSERT_EQ(node_x.shape.at(0), hydro.snapshots.size());
  for (std::size_t k = 0; k < hydro.snapshots.size(); ++k) {
    const auto& snap = hydro.snapshots[k];
    ASSERT_EQ(snap.n.size(), 64u);
    for (std::size_t i = 0; i < 64; ++i) {
      const double left = node_x.values[k * 64 + i];
      const double right = i + 1 < 64 ? node_x.values[k * 64 + i + 1] : node_x.values[k * 64] + 1;
      EXPECT_NEAR(snap.n[i] * (right - left), mass[i], 1e-12) << "t = " << snap.t << ", cell " << i;
    }
  }
  EXPECT_EQ(md.geometry, fields::Geometry::bins);
  ASSERT_EQ(md.snapshots.size(), 3u);
  const double particles = s["md"]["particles"].get<double>();
  for (const auto& snap : md.snapshots) {
    ASSERT_EQ(snap.count.size(), md.bin_edges.size() - 1);
    double total = 0.0;
    for (double c : snap.count) total += c;
    EXPECT_NEAR(total, particles, 1e-9 * particles) << "t = " << snap.t;
    EXPECT_EQ(snap.n_stderr.size(), snap.n.size()) << "the ensemble's error of the mean";
  }
}

// A particle-only scene (hydro.enabled = false, as md_cooling_sweep) runs no hydro: its summary
// has "hydro": null, results.h5 has no /hydro group, and the status is the particles'.
TEST(CliParticlesOnly, SceneWithoutHydroRunsOnlyTheParticles) {
  ScratchFolder scratch("particles-only");
  const fs::path out = scratch.path / "run";
  const CliStreams r = run_cli_streams(
      "run md_cooling_sweep --quiet --no-report --set md.ensemble=1 --set md.t_end=0.05 "
      "--set md.particles=200 --set md.box_width=60 --out " +
      q(out));
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const json s = json::parse(read_text(out / "summary.json"));
  EXPECT_TRUE(s["hydro"].is_null()) << s.dump(2);
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["md"]["status"], "ok");
  H5::H5File h5((out / "results.h5").string(), H5F_ACC_RDONLY);
  EXPECT_FALSE(h5.nameExists("/hydro"));
  EXPECT_TRUE(h5.nameExists("/md/fields"));
  EXPECT_TRUE(contains(read_text(out / "run.log"), "hydro: not run (hydro.enabled = false)"));
}

TEST(CliDefaultScene, DefaultOutputFolderIsOutSlashCaseName) {
  ScratchFolder scratch("default-out");
  const CliStreams r =
      run_cli_streams("run single_mode --quiet --no-report " + kSmall, scratch.path);
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const fs::path out = scratch.path / "out" / "single_mode";
  for (const char* file : {"results.h5", "summary.json", "run.log", "case.toml"}) {
    EXPECT_TRUE(fs::is_regular_file(out / file)) << file << " missing in " << out;
  }
}

}  // namespace
}  // namespace granvv::testing
