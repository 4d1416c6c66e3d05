// The recorded engine (md.engine = "recorded", docs/recorded.md) through the real CLI: a round
// trip (an event-driven run writing its frames, read back from its particles.h5 and from the
// same frames written as LAMMPS dumps by scripts/h5md_to_lammps_dump.py, gives the original's
// coarse-grained fields, hydro and verdict), and every refusal of a file that is not what it
// claims (exit 2, one line naming the file and the problem).
#include <H5Cpp.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "fields/field_series_file.hpp"
#include "support/cli_runner.hpp"

namespace granvv {
namespace {

namespace fs = std::filesystem;
using testing::run_cli;
using testing::shell_quote;

// The fields of the replayed frames are the original's summed in another order (ID order
// against the engine's): round-off of sums of ~10^2 terms, ~1e-14 relative; 1e-12 leaves room.
constexpr double kRoundOff = 1e-12;

void write(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

fields::FieldSeries read_fields(const fs::path& results, const std::string& group) {
  H5::H5File file(results.string(), H5F_ACC_RDONLY);
  return fields::read_field_series(file.openGroup(group));
}

nlohmann::json summary_of(const fs::path& dir) {
  return nlohmann::json::parse(testing::read_text(dir / "summary.json"));
}

// Every snapshot's hydrodynamic fields and their errors agree to round-off.
void expect_same_fields(const fields::FieldSeries& a, const fields::FieldSeries& b,
                        const std::string& what) {
  ASSERT_EQ(a.snapshots.size(), b.snapshots.size()) << what;
  for (std::size_t s = 0; s < a.snapshots.size(); ++s) {
    const auto& x = a.snapshots[s];
    const auto& y = b.snapshots[s];
    EXPECT_NEAR(x.t, y.t, kRoundOff * std::max(1.0, std::abs(x.t))) << what;
    const std::vector<std::pair<const std::vector<double>*, const std::vector<double>*>> columns = {
        {&x.n, &y.n}, {&x.v_x, &y.v_x}, {&x.v_y, &y.v_y}, {&x.T, &y.T}};
    for (const auto& [p, q] : columns) {
      ASSERT_EQ(p->size(), q->size()) << what;
      for (std::size_t i = 0; i < p->size(); ++i) {
        EXPECT_NEAR((*p)[i], (*q)[i], kRoundOff * std::max(1.0, std::abs((*p)[i])))
            << what << " snapshot " << s << " position " << i;
      }
    }
  }
}

constexpr const char* kScene = R"([case]
name = "round_trip"
[physics]
K = 0.05
q = 0.05
[initial]
type = "single_mode"
velocity_amplitude = -0.25
[hydro]
cells = 100
[compare]
enabled = true
hydro_initial = "md"
[md]
enabled = true
sample_interval = 5.0
output_times = [0.0, 50.0, 100.0]
bins = 16
)";

TEST(RecordedEngine, ReplaysItsOwnFramesFromH5mdAndLammpsDumpsToRoundOff) {
  const fs::path dir = testing::fresh_directory("recorded_round_trip");
  write(dir / "original.toml", std::string(kScene) + R"(engine = "event_driven"
area_fraction = 0.05
box_width = 10.0
seed = 1
ensemble = 2
t_end = 100.0
snapshot_interval = 5.0
)");
  auto run = run_cli("run " + shell_quote((dir / "original.toml").string()) + " --out " +
                     shell_quote((dir / "original").string()) + " --quiet --no-report");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const fs::path m0 = dir / "original" / "particles_m0.h5",
                 m1 = dir / "original" / "particles_m1.h5";
  ASSERT_TRUE(fs::exists(m0) && fs::exists(m1));

  // The same frames as LAMMPS text dumps, a step being 0.5 of time.
  for (const auto& [h5, dump] : {std::pair{m0, dir / "m0.dump"}, std::pair{m1, dir / "m1.dump"}}) {
    const auto converted = testing::run_shell(
        "/usr/bin/python3 " +
        shell_quote(std::string(GRANVV_SOURCE_DIR) + "/scripts/h5md_to_lammps_dump.py") + " " +
        shell_quote(h5.string()) + " " + shell_quote(dump.string()) + " --timestep 0.5");
    ASSERT_EQ(converted.exit_code, 0) << converted.output;
  }
  write(dir / "from_h5md.toml", std::string(kScene) + "engine = \"recorded\"\nrecorded.files = [" +
                                    shell_quote(m0.string()) + ", " + shell_quote(m1.string()) +
                                    "]\n");
  write(dir / "from_dump.toml", std::string(kScene) +
                                    "engine = \"recorded\"\nrecorded.timestep = 0.5\n"
                                    "recorded.files = [" +
                                    shell_quote((dir / "m0.dump").string()) + ", " +
                                    shell_quote((dir / "m1.dump").string()) + "]\n");
  const auto original = summary_of(dir / "original");
  const auto md_original = read_fields(dir / "original" / "results.h5", "/md/fields");
  const auto hydro_original = read_fields(dir / "original" / "results.h5", "/hydro/fields");
  for (const std::string name : {"from_h5md", "from_dump"}) {
    SCOPED_TRACE(name);
    run = run_cli("run " + shell_quote((dir / (name + ".toml")).string()) + " --out " +
                  shell_quote((dir / name).string()) + " --quiet --no-report");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const auto replayed = summary_of(dir / name);
    EXPECT_EQ(replayed["md"]["engine"], "recorded");
    EXPECT_EQ(replayed["md"]["ensemble"], 2);
    EXPECT_EQ(replayed["md"]["particles"], original["md"]["particles"]);
    EXPECT_EQ(replayed["compare"]["verdict"], original["compare"]["verdict"]);
    expect_same_fields(md_original, read_fields(dir / name / "results.h5", "/md/fields"), "md");
    // The hydro starts from the replayed t = 0 fields: the same hydro.
    expect_same_fields(hydro_original, read_fields(dir / name / "results.h5", "/hydro/fields"),
                       "hydro");
    // Each file's fingerprint.
    ASSERT_EQ(replayed["md"]["input_files"].size(), 2u);
    EXPECT_EQ(replayed["md"]["input_files"][0]["sha256"].get<std::string>().size(), 64u);
  }
}

// ---------------------------------------------------------------------------------------------
// Refusals: a file that is not what it claims.
// ---------------------------------------------------------------------------------------------

struct DumpFrame {
  long long step = 0;
  std::string columns = "id x y vx vy";
  std::vector<std::string> rows = {"1 -4 -2 0.5 0.1", "2 -1 3 -0.2 0.3", "3 2 -1 0.1 -0.4",
                                   "4 5 2 -0.4 0.0"};
  std::string box = "-10 10\n-5 5\n-0.5 0.5\n";
};

std::string dump_text(const std::vector<DumpFrame>& frames) {
  std::ostringstream out;
  for (const DumpFrame& f : frames) {
    out << "ITEM: TIMESTEP\n"
        << f.step << "\nITEM: NUMBER OF ATOMS\n"
        << f.rows.size() << "\nITEM: BOX BOUNDS pp pp pp\n"
        << f.box << "ITEM: ATOMS " << f.columns << "\n";
    for (const auto& r : f.rows) out << r << "\n";
  }
  return out.str();
}

// `granvv run` of the recorded files `files` (a TOML list) with --dry-run: everything is checked
// before anything runs.
testing::CliResult dry_run(const fs::path& dir, const std::string& files,
                           const std::string& extra = "") {
  write(dir / "case.toml", std::string(R"([physics]
K = 0.05
q = 0.05
[md]
enabled = true
engine = "recorded"
bins = 4
recorded.timestep = 0.1
)") + "recorded.files = " + files +
                               "\n" + extra);
  return run_cli("run " + shell_quote((dir / "case.toml").string()) + " --out " +
                 shell_quote((dir / "out").string()) + " --dry-run");
}

void expect_refused(const testing::CliResult& r, const std::string& file,
                    const std::string& problem) {
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(file), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(problem), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

TEST(RecordedEngine, AcceptsAGoodDumpAndRefusesEveryFileThatIsNotWhatItClaims) {
  const fs::path dir = testing::fresh_directory("recorded_refusals");
  const fs::path file = dir / "frames.dump";
  const std::string files = "[" + shell_quote(file.string()) + "]";
  DumpFrame a, b;
  b.step = 10;
  write(file, dump_text({a, b}));
  const auto good = dry_run(dir, files);
  ASSERT_EQ(good.exit_code, 0) << good.output;

  DumpFrame no_vx = b;
  no_vx.columns = "id x y vy vz";
  write(file, dump_text({a, no_vx}));
  expect_refused(dry_run(dir, files), file.string(), "has no column vx");

  DumpFrame moving = b;
  moving.columns = "id x y z vx vy vz";
  moving.rows = {"1 -4 -2 0 0.5 0.1 0", "2 -1 3 0 -0.2 0.3 0.25", "3 2 -1 0 0.1 -0.4 0",
                 "4 5 2 0 -0.4 0.0 0"};
  write(file, dump_text({a, moving}));
  expect_refused(dry_run(dir, files), file.string(), "3D motion");

  DumpFrame again = b;
  again.step = 0;
  write(file, dump_text({a, again}));
  expect_refused(dry_run(dir, files), file.string(), "does not come after");

  DumpFrame wider = b;
  wider.box = "-12 12\n-5 5\n-0.5 0.5\n";
  write(file, dump_text({a, wider}));
  expect_refused(dry_run(dir, files), file.string(), "the box changes");

  DumpFrame fewer = b;
  fewer.rows.pop_back();
  write(file, dump_text({a, fewer}));
  expect_refused(dry_run(dir, files), file.string(), "number of atoms changes");

  DumpFrame nan = b;
  nan.rows[2] = "3 2 nan 0.1 -0.4";
  write(file, dump_text({a, nan}));
  expect_refused(dry_run(dir, files), file.string(), "not finite");

  write(file, dump_text({a, b}));
  expect_refused(dry_run(dir, "[" + shell_quote((dir / "absent*.dump").string()) + "]"),
                 (dir / "absent*.dump").string(), "no such file");
  expect_refused(dry_run(dir, files, "output_times = [0.0, 0.55]\n"), "md.output_times",
                 "is not a recorded frame time");
  // Two runs under one glob are one run whose frames go back.
  write(dir / "frames_2.dump", dump_text({a, b}));
  expect_refused(dry_run(dir, "[" + shell_quote((dir / "frames*.dump").string()) + "]"),
                 (dir / "frames_2.dump").string(), "does not come after");
}

// An H5MD file of a 3D run whose disks move along z is refused.
TEST(RecordedEngine, RefusesAnH5mdFileWithMotionAlongZ) {
  const fs::path dir = testing::fresh_directory("recorded_h5md_3d");
  const fs::path file = dir / "frames.h5";
  {
    H5::H5File h5(file.string(), H5F_ACC_TRUNC);
    H5::Group g = h5.createGroup("/particles");
    g = h5.createGroup("/particles/all");
    H5::Group box = h5.createGroup("/particles/all/box");
    const hsize_t three = 3;
    const double edges[3] = {20.0, 10.0, 10.0};
    box.createDataSet("edges", H5::PredType::NATIVE_DOUBLE, H5::DataSpace(1, &three))
        .write(edges, H5::PredType::NATIVE_DOUBLE);
    const hsize_t dims[3] = {2, 2, 3}, frames = 2;
    const double x[12] = {-4, -2, 0, 3, 1, 0, -4, -2, 0.5, 3, 1, 0};
    const double v[12] = {0.5, 0.1, 0, -0.2, 0.3, 0, 0.5, 0.1, 0, -0.2, 0.3, 0};
    const double t[2] = {0.0, 1.0};
    for (const auto& [name, values] : {std::pair{"position", x}, std::pair{"velocity", v}}) {
      H5::Group e = h5.createGroup(std::string("/particles/all/") + name);
      e.createDataSet("value", H5::PredType::NATIVE_DOUBLE, H5::DataSpace(3, dims))
          .write(values, H5::PredType::NATIVE_DOUBLE);
      e.createDataSet("time", H5::PredType::NATIVE_DOUBLE, H5::DataSpace(1, &frames))
          .write(t, H5::PredType::NATIVE_DOUBLE);
    }
  }
  expect_refused(dry_run(dir, "[" + shell_quote(file.string()) + "]"), file.string(),
                 "moves along z");
}

}  // namespace
}  // namespace granvv
