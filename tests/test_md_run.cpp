// The particle engine on small systems with the real LAMMPS library: conservation,
// cooling against Haff's law, adaptive stiffness, and refusal of impossible scenes through
// the real CLI (exit 2, nothing written).
#include <H5Cpp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <variant>

#include "md_bridge/disk_overlap.hpp"
#include "md_bridge/lammps_engine.hpp"
#include "md_bridge/md_run.hpp"
#include "md_bridge/particle_blocks.hpp"
#include "support/cli_runner.hpp"

namespace granvv::md {
namespace {

MdRunSpec small_cooling_gas(double t_end) {
  MdRunSpec spec;
  spec.scene = scene_from_particles(600, 0.05, 60.0, 0.9);
  spec.fields = hydro::uniform_fields();
  spec.t_end = t_end;
  spec.sample_interval = t_end / 10;
  spec.bins = 10;
  spec.kernel = "bin";
  spec.seed = 1;
  spec.output_times = {0.0, t_end};
  return spec;
}

LammpsEngineOptions engine_options(const MdRunSpec& spec) {
  LammpsEngineOptions o;
  o.restitution = spec.scene.restitution;
  o.box_length = spec.scene.box_length;
  o.box_width = spec.scene.box_width;
  o.particles = spec.scene.particles;
  o.max_overlap = 0.01;  // the case schema's defaults of md.max_overlap, md.steps_per_contact
  o.steps_per_contact = 30;
  o.adaptive_stiffness = true;
  return o;
}

TEST(MdRun, SmallCoolingGasConservesMomentumAndParticlesAndCools) {
  const MdRunSpec spec = small_cooling_gas(8.0);
  LammpsEngine engine(engine_options(spec));
  const MdRunResult r = run_md(spec, engine, nullptr);
  ASSERT_EQ(r.status, "ok");
  const auto& s = r.series;
  ASSERT_EQ(s.t.size(), 11u);
  for (size_t i = 0; i < s.t.size(); ++i) {
    // Momentum: pairwise forces; round-off ~1e-16 per force over 1e5 steps.
    EXPECT_LT(std::abs(s.momentum_x[i]), 1e-9);
    EXPECT_LT(std::abs(s.momentum_y[i]), 1e-9);
    if (i > 0) {
      EXPECT_LT(s.energy_total[i], s.energy_total[i - 1]);  // inelastic: E falls
    }
  }
  // Haff with the Enskog factor: t0 = 86 here, T(8) / T(0) = 0.84. The sampled T(0) and the
  // thermal noise of 600 disks (sqrt(2/N) = 6 %) limit the check to 10 %.
  const double t0 = haff_time_md(small_cooling_gas(8.0).scene, enskog_chi(0.05));
  const double haff = 1.0 / std::pow(1.0 + 8.0 / t0, 2);
  EXPECT_NEAR(s.T.back() / s.T.front(), haff, 0.1 * haff);
  // Coarse-grained snapshots: integral of n over the box is the number of disks.
  ASSERT_EQ(r.fields.snapshots.size(), 2u);
  for (const auto& snap : r.fields.snapshots) {
    double total = 0.0;
    const double bin_area = 60.0 * small_cooling_gas(8).scene.box_length / 10;
    for (double n : snap.n) total += n * bin_area;
    EXPECT_NEAR(total, 600.0, 1e-9);
  }
  EXPECT_EQ(r.fields.snapshots.front().t, 0.0);
  EXPECT_NEAR(r.fields.snapshots.back().t, 8.0, engine.contact().dt);
  // The engine's own series: kn and dt at every sample.
  ASSERT_EQ(r.series.engine.size(), 2u);
  EXPECT_EQ(r.series.engine[0].first, "kn");
  EXPECT_EQ(r.series.engine[1].first, "dt");
  EXPECT_EQ(r.series.engine[1].second.size(), s.t.size());
  EXPECT_EQ(r.series.engine[1].second.back(), engine.contact().dt);
  // Cost: particles x time steps.
  const EngineCost cost = engine.cost();
  EXPECT_EQ(cost.work_unit, "atom_steps");
  EXPECT_EQ(cost.work, 600.0 * double(r.steps));
  EXPECT_GT(cost.wall_seconds, 0.0);
}

// A checkpoint (docs/outputs.md, "Checkpoints and resume") taken halfway and continued by a
// fresh engine gives the run the uninterrupted engine gives: the samples before the checkpoint
// are the saved ones, bit for bit. After it, one thing differs by construction: LAMMPS
// computes the forces anew when a run is set up, and the contact damping of the pairs that
// touch at that moment then sees the full-step velocities where the uninterrupted velocity
// Verlet used the half-step ones, an O(dt) change of those few collisions (physics.md §10).
// Measured here: the total energy jumps by 3e-7 of itself in the first segment, then stays
// that far apart; the bounds (1e-5 of the box energy and temperature, 1e-4 in a bin) allow
// for several pairs in contact and stay far below the thermal noise of 600 disks (6 %).
TEST(MdRun, ARunContinuedFromItsCheckpointMatchesTheUninterruptedOne) {
  MdRunSpec spec = small_cooling_gas(8.0);
  spec.scene.restitution = 0.5;  // cools fast, so that the contact is softened on the way
  LammpsEngineOptions options = engine_options(spec);
  options.adapt_below = 0.9;
  std::optional<MdRunState> saved;
  MdCheckpoints checkpoints;
  checkpoints.due = [&] { return !saved; };
  checkpoints.save = [&](const MdRunState& state) {
    if (state.t >= 4.0 - 1e-9) saved = state;
  };
  LammpsEngine whole(options);
  const MdRunResult uninterrupted = run_md(spec, whole, nullptr, checkpoints);
  ASSERT_TRUE(saved);
  ASSERT_GT(whole.stiffness_changes(), 0);
  // Under mpirun -np P (tests/CMakeLists.txt runs this test on 2 ranks too) each rank saved
  // only its block of IDs, and the restore below sends them to their subdomains.
  int ranks = 1, rank = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  EXPECT_EQ(saved->engine.particle_blocks, ranks);
  EXPECT_EQ(saved->engine.first_row, id_block(spec.scene.particles, ranks, rank).first);
  EXPECT_EQ(saved->engine.particles.x.size(),
            3 * std::size_t(id_block(spec.scene.particles, ranks, rank).count));

  LammpsEngine fresh(options);
  MdCheckpoints resume;
  resume.resume_from = &*saved;
  const MdRunResult continued = run_md(spec, fresh, nullptr, resume);
  ASSERT_EQ(continued.status, "ok");
  EXPECT_EQ(continued.steps, uninterrupted.steps);
  EXPECT_EQ(fresh.cost().work, whole.cost().work);
  EXPECT_EQ(fresh.contact().kn, whole.contact().kn);
  EXPECT_EQ(fresh.stiffness_changes(), whole.stiffness_changes());
  const auto& a = uninterrupted.series;
  const auto& b = continued.series;
  ASSERT_EQ(b.t.size(), a.t.size());
  const std::size_t at_checkpoint = saved->so_far.series.t.size();
  for (std::size_t i = 0; i < a.t.size(); ++i) {
    EXPECT_EQ(b.t[i], a.t[i]);
    if (i < at_checkpoint) {
      EXPECT_EQ(b.energy_total[i], a.energy_total[i]) << i;
    } else {
      EXPECT_NEAR(b.energy_total[i], a.energy_total[i], 1e-5 * a.energy_total[i]) << i;
      EXPECT_NEAR(b.T[i], a.T[i], 1e-5 * a.T[i]) << i;
    }
  }
  ASSERT_EQ(continued.fields.snapshots.size(), uninterrupted.fields.snapshots.size());
  for (std::size_t k = 0; k < uninterrupted.fields.snapshots.size(); ++k) {
    const auto& x = uninterrupted.fields.snapshots[k];
    const auto& y = continued.fields.snapshots[k];
    EXPECT_EQ(y.t, x.t);
    for (std::size_t j = 0; j < x.n.size(); ++j) EXPECT_NEAR(y.T[j], x.T[j], 1e-4 * x.T[j]);
  }
  // A state of another scene is refused.
  EngineState wrong = saved->engine;
  wrong.particles.x.resize(3);
  wrong.particles.v.resize(3);
  EXPECT_THROW(fresh.restore_state(wrong), std::invalid_argument);
}

// A resume asks the engine whether it would continue a saved state (scene/md_checkpoint.hpp).
// Every state a cooling run saves passes, with its disks never pressed deeper than the contact
// makes them (md.max_overlap at the fastest relative speed present; measured here: under 1 x);
// a state whose disks are pressed kDamagedOverlap times deeper, or onto one spot, is refused
// with the disks named, and so is one without its numbers.
TEST(MdRun, AStateWithDisksPressedDeeperThanAnyCollisionIsRefused) {
  MdRunSpec spec = small_cooling_gas(8.0);
  spec.scene.restitution = 0.5;
  const LammpsEngineOptions options = engine_options(spec);
  std::vector<MdRunState> saved;
  MdCheckpoints checkpoints;
  checkpoints.due = [] { return true; };
  checkpoints.save = [&](const MdRunState& state) { saved.push_back(state); };
  LammpsEngine engine(options);
  ASSERT_EQ(run_md(spec, engine, nullptr, checkpoints).status, "ok");
  ASSERT_GE(saved.size(), 5u);
  if (saved.front().engine.particle_blocks > 1) GTEST_SKIP() << "blocks: checked whole by a resume";
  double deepest = 0.0;
  for (const auto& state : saved) {
    EXPECT_EQ(engine.state_problem(state.engine), "") << "t = " << state.t;
    deepest = std::max(
        deepest,
        deepest_overlap(state.engine.particles.x, options.box_length, options.box_width).depth);
  }
  EXPECT_LT(deepest, options.max_overlap);
  EXPECT_GT(deepest, 0.0);  // disks in contact were saved

  // Disks 1 and 2 moved to a spot with no other disk within 3 sigma, `depth` into each other.
  const EngineState& good = saved.back().engine;
  const auto pressed = [&](double depth) {
    EngineState s = good;
    auto& x = s.particles.x;
    for (double cx = -0.5 * options.box_length + 3; cx < 0.5 * options.box_length - 3; cx += 1) {
      for (double cy = -0.5 * options.box_width + 3; cy < 0.5 * options.box_width - 3; cy += 1) {
        bool empty = true;
        for (std::size_t i = 6; i < x.size() && empty; i += 3)
          empty = std::hypot(x[i] - cx, x[i + 1] - cy) > 3.0;
        if (!empty) continue;
        x[0] = cx, x[1] = cy, x[3] = cx + 1.0 - depth, x[4] = cy;
        return s;
      }
    }
    ADD_FAILURE() << "no empty spot";
    return s;
  };
  EXPECT_EQ(
      engine.state_problem(pressed(0.8 * LammpsEngine::kDamagedOverlap * options.max_overlap)), "");
  const std::string deep =
      engine.state_problem(pressed(1.2 * LammpsEngine::kDamagedOverlap * options.max_overlap));
  EXPECT_NE(deep.find("disks 1 and 2 overlap by 0.06 sigma"), std::string::npos) << deep;
  EXPECT_NE(deep.find("md.max_overlap"), std::string::npos) << deep;
  const std::string one_spot = engine.state_problem(pressed(1.0));
  EXPECT_NE(one_spot.find("disks 1 and 2 overlap by 1 sigma"), std::string::npos) << one_spot;
  EngineState without = good;
  without.numbers.erase(without.numbers.begin());
  EXPECT_NE(engine.state_problem(without).find("without a finite 't'"), std::string::npos);
  EngineState fewer = good;
  fewer.particles.x.resize(fewer.particles.x.size() - 3);
  EXPECT_NE(engine.state_problem(fewer).find("599 particles"), std::string::npos);
}

TEST(MdRun, AdaptiveStiffnessSoftensAtFixedRestitution) {
  // r = 0.5 cools fast (t0 = 22): by t = 15 T ~ 0.35, the fastest pair ~0.6 of its start.
  MdRunSpec spec = small_cooling_gas(15.0);
  spec.scene.restitution = 0.5;
  LammpsEngineOptions options = engine_options(spec);
  options.adapt_below = 0.7;
  LammpsEngine engine(options);
  const MdRunResult r = run_md(spec, engine, nullptr);
  ASSERT_EQ(r.status, "ok");
  EXPECT_GT(engine.stiffness_changes(), 0);
  // The details name the first and last contact of the run.
  std::map<std::string, double> d;
  for (const auto& detail : engine.details()) {
    if (const double* v = std::get_if<double>(&detail.value)) d[detail.key] = *v;
    if (const long long* v = std::get_if<long long>(&detail.value)) d[detail.key] = double(*v);
  }
  EXPECT_EQ(d.at("stiffness_changes"), engine.stiffness_changes());
  EXPECT_LT(d.at("contact_final.kn"), d.at("contact_initial.kn"));
  EXPECT_GT(d.at("contact_final.dt"), d.at("contact_initial.dt"));
  EXPECT_EQ(d.at("contact_final.kn"), engine.contact().kn);
  EXPECT_EQ(d.at("contact_initial.kn"), r.series.engine[0].second.front());
  // kn ~ u^2, dt ~ 1/sqrt(kn), gamma_n ~ sqrt(kn): the discrete contact is the same map.
  EXPECT_NEAR(d.at("contact_final.gamma_n") * d.at("contact_final.dt"),
              d.at("contact_initial.gamma_n") * d.at("contact_initial.dt"), 1e-9);
  EXPECT_LT(std::abs(r.series.momentum_x.back()), 1e-9);
}

TEST(MdCli, ImpossibleParticleScenesAreRefusedBeforeLammps) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--set md.area_fraction=0.6", "md.area_fraction = 0.6"},
      {"--set md.box_width=2", "md.box_width = 2"},
      {"--set md.restitution=1.2", "md.restitution = 1.2"},
      {"--set md.kernel=gaussian", "md.kernel_width"},
      {"--set md.steps_per_contact=3", "md.steps_per_contact = 3"},
      {"--set md.engine=hard_disks", "md.engine = \"hard_disks\""},
      {"--set md.area_fraction=0.45 --set initial.type=single_mode --set "
       "initial.velocity_amplitude=0 --set initial.type=random_modes --set "
       "initial.random_modes=2 --set initial.random_amplitude=0.5",
       "local area fraction above 0.5"},
  };
  for (const auto& [args, expected] : cases) {
    const auto dir = granvv::testing::fresh_directory("md-bad") / "out";
    const auto r = granvv::testing::run_cli("run md_haff " + args + " --out " + dir.string());
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << args << "\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir)) << args;
  }
}

TEST(MdCli, SmallHaffSceneThroughTheCli) {
  const auto dir = granvv::testing::fresh_directory("md-haff");
  const auto r = granvv::testing::run_cli(
      "run md_haff --quiet --no-report --set md.particles=600 --set md.box_width=97 "
      "--set md.t_end=6 --set md.sample_interval=1 --set md.ensemble=2 --set md.seed=5 "
      "--set md.restitution=0.8 --set 'md.output_times=[0, 3, 6]' --out " +
      dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = nlohmann::json::parse(granvv::testing::read_text(dir / "summary.json"));
  // md_haff compares with the hydro of the same K, q (compare.hydro_initial = "case"): a
  // homogeneous hydro, so the density and flow agree with the particles within their noise.
  const auto& c = s["compare"];
  ASSERT_TRUE(c.is_object()) << s.dump(2);
  EXPECT_EQ(c["hydro_initial"], "case");
  EXPECT_EQ(c["times"].size(), 3u);
  EXPECT_GE(c["fields"]["n"]["fraction_within"][0].get<double>(), 0.9);
  EXPECT_GE(c["fields"]["v_x"]["fraction_within"][2].get<double>(), 0.9);
  EXPECT_DOUBLE_EQ(c["haff"]["t0_theory_enskog"].get<double>(),
                   s["md"]["haff_t0_theory"].get<double>());
  EXPECT_GT(c["cost"]["hydro"]["cell_steps"].get<double>(), 0.0);
  const auto& md = s["md"];
  EXPECT_EQ(md["status"], "ok");
  EXPECT_EQ(md["particles"], 600);
  EXPECT_EQ(md["ensemble"], 2);
  EXPECT_EQ(md["seed"], 5);
  EXPECT_DOUBLE_EQ(md["restitution"].get<double>(), 0.8);
  EXPECT_NEAR(md["restitution_measured"].get<double>(), 0.8, 1e-3);
  for (const char* key : {"wall_seconds", "box_length", "box_width", "area_fraction", "K", "q",
                          "atom_steps_per_second", "haff_t0_measured", "haff_t0_measured_error",
                          "haff_t0_theory", "haff_t0_theory_dilute"}) {
    EXPECT_TRUE(md[key].is_number()) << key;
  }
  // q = (1 - r)/2 and the theory's t0 = 2 / (sqrt(pi) (1 - r^2) chi n0 sigma).
  EXPECT_NEAR(md["q"].get<double>(), 0.1, 1e-12);
  const double n0 = 4 * 0.05 / M_PI;
  EXPECT_NEAR(md["haff_t0_theory_dilute"].get<double>(), 2 / (std::sqrt(M_PI) * 0.36 * n0), 1e-6);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace granvv::md

namespace granvv::md {
namespace {

// The staging folder a killed run left in dir (docs/outputs.md, "The output protocol").
std::filesystem::path staging_folder_of(const std::filesystem::path& dir) {
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().filename().string().rfind(".granvv-staging-", 0) == 0) return e.path();
  }
  return {};
}

// The Debian LAMMPS ends the process on an error inside a command. A process that dies in
// the particle run (here: killed) has, in its staging folder, a summary saying so and the
// hydro results readable; the folder itself shows no result of that run.
TEST(MdCli, ProcessEndingInsideTheParticleRunLeavesReadableOutputs) {
  const auto dir = granvv::testing::fresh_directory("md-killed");
  const std::string command = "timeout -s KILL 4 " + std::string(GRANVV_BINARY) +
                              " run md_haff --quiet --no-report --set md.t_end=1e4 "
                              "--set compare.enabled=false --out " +
                              dir.string() + " > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_NE(status, 0);
  EXPECT_FALSE(std::filesystem::exists(dir / "summary.json"));
  const auto staging = staging_folder_of(dir);
  ASSERT_FALSE(staging.empty());
  const auto s = nlohmann::json::parse(granvv::testing::read_text(staging / "summary.json"));
  EXPECT_EQ(s["status"], "failed");
  EXPECT_EQ(s["md"]["status"], "failed");
  EXPECT_NE(s["md"]["error"].get<std::string>().find("log.lammps"), std::string::npos);
  EXPECT_EQ(s["hydro"]["status"], "ok");  // the hydro part had finished and is kept
  EXPECT_TRUE(std::filesystem::exists(staging / "results.h5"));
  EXPECT_TRUE(std::filesystem::exists(staging / "log.lammps"));
  std::filesystem::remove_all(dir);
}

// In a comparison the particles run first (the hydro starts from their fields): a process
// ending inside them leaves a summary that says so, and nothing half-written.
TEST(MdCli, ProcessEndingInsideTheParticleRunOfAComparisonSaysSo) {
  const auto dir = granvv::testing::fresh_directory("md-killed-compare");
  const std::string command = "timeout -s KILL 4 " + std::string(GRANVV_BINARY) +
                              " run md_haff --quiet --no-report --set md.t_end=1e4 --out " +
                              dir.string() + " > /dev/null 2>&1";
  ASSERT_NE(std::system(command.c_str()), 0);
  const auto staging = staging_folder_of(dir);
  ASSERT_FALSE(staging.empty());
  const auto s = nlohmann::json::parse(granvv::testing::read_text(staging / "summary.json"));
  EXPECT_EQ(s["status"], "failed");
  EXPECT_EQ(s["md"]["status"], "failed");
  EXPECT_TRUE(s["compare"].is_null());
  EXPECT_TRUE(std::filesystem::exists(staging / "case.toml"));
  EXPECT_TRUE(std::filesystem::exists(staging / "log.lammps"));
  EXPECT_FALSE(std::filesystem::exists(staging / "results.h5.partial"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace granvv::md

namespace granvv::md {
namespace {

// `granvv` + args + one, and under mpirun -np 2 the same + two; true if both exit 0.
bool run_on_one_and_two_ranks(const std::string& args, const std::filesystem::path& one,
                              const std::filesystem::path& two) {
  const std::string quiet = " > /dev/null 2>&1";
  const std::string mpirun = "mpirun --allow-run-as-root --oversubscribe -np 2 ";
  return std::system((std::string(GRANVV_BINARY) + args + one.string() + quiet).c_str()) == 0 &&
         std::system((mpirun + GRANVV_BINARY + args + two.string() + quiet).c_str()) == 0;
}

// Two MPI ranks: LAMMPS splits the box, the coarse-grainer reduces moments over the ranks,
// rank 0 writes. The same seed gives the same statistics as one rank (the initial sample is
// the same on every rank; collisions are summed in another order, so agreement is to
// round-off growing through the chaotic dynamics: checked to 1e-6 over a short run).
TEST(MdCli, TwoMpiRanksGiveTheStatisticsOfOne) {
  const std::string args =
      " run md_haff --quiet --no-report --set md.particles=800 --set md.box_width=112 "
      "--set md.t_end=2 --set md.sample_interval=0.5 --set md.ensemble=1 "
      "--set 'md.output_times=[0, 1, 2]' --out ";
  const auto one = granvv::testing::fresh_directory("mpi-one");
  const auto two = granvv::testing::fresh_directory("mpi-two");
  ASSERT_TRUE(run_on_one_and_two_ranks(args, one, two));
  const auto a = nlohmann::json::parse(granvv::testing::read_text(one / "summary.json"))["md"];
  const auto b = nlohmann::json::parse(granvv::testing::read_text(two / "summary.json"))["md"];
  EXPECT_EQ(a["steps"], b["steps"]);
  EXPECT_NEAR(a["haff_t0_measured"].get<double>(), b["haff_t0_measured"].get<double>(),
              1e-6 * a["haff_t0_measured"].get<double>());
  EXPECT_EQ(a["restitution_measured"], b["restitution_measured"]);
  std::filesystem::remove_all(one);
  std::filesystem::remove_all(two);
}

}  // namespace
}  // namespace granvv::md

namespace granvv::md {
namespace {

// An H5MD dataset [frames, N, 2] (read through its virtual mapping where it has one), flattened,
// with its shape.
std::vector<double> all_frames(const std::filesystem::path& file, const std::string& path,
                               hsize_t (&dims)[3]) {
  H5::H5File h5(file.string(), H5F_ACC_RDONLY);
  H5::DataSet set = h5.openDataSet(path);
  set.getSpace().getSimpleExtentDims(dims);
  std::vector<double> all(std::size_t(dims[0] * dims[1] * dims[2]));
  set.read(all.data(), H5::PredType::NATIVE_DOUBLE);
  return all;
}

// Issue 15: 100 001 disks are two strips (particle_sampler.hpp). Under mpirun -np 2 LAMMPS
// cuts the box (15 708 x 100 sigma) along x; each rank samples the strips over its half and
// creates the disks of its subdomain, with the strips' IDs. The particles of the first H5MD
// frame (t = 0) are those of one rank bit for bit. The frames are written without a gather
// (h5md_frames.hpp): each rank sends its particles to the owner of their ID block, which writes
// its 50 000 or 50 001 rows to particles.rank000k.h5; particles.h5 joins them by virtual
// datasets, read here by ID as one [frames][N][2] array, by HDF5 and by h5py.
TEST(MdCli, TwoRanksSampleTheParticlesOfOneBitForBit) {
  const std::string args =
      " run md_cooling_sweep --quiet --no-report --set md.particles=100001 "
      "--set md.box_width=100 --set md.time_unit='\"md\"' --set md.t_end=0.01 "
      "--set md.sample_interval=0.01 --set md.snapshot_interval=0.01 --set md.ensemble=1 "
      "--set md.checkpoint_interval=0 --out ";
  const auto one = granvv::testing::fresh_directory("strips-one");
  const auto two = granvv::testing::fresh_directory("strips-two");
  ASSERT_TRUE(run_on_one_and_two_ranks(args, one, two));
  constexpr hsize_t kN = 100001;
  EXPECT_FALSE(std::filesystem::exists(one / "particles.rank0000.h5"));  // one rank: one file
  for (const char* name : {"position", "velocity"}) {
    const std::string path = std::string("/particles/all/") + name + "/value";
    hsize_t da[3], db[3];
    const auto a = all_frames(one / "particles.h5", path, da);
    const auto b = all_frames(two / "particles.h5", path, db);
    ASSERT_EQ(da[0], 2u) << name;  // t = 0 and t = 0.01
    ASSERT_EQ(da[1], kN) << name;
    ASSERT_EQ(std::vector<hsize_t>(da, da + 3), std::vector<hsize_t>(db, db + 3)) << name;
    std::size_t differ = 0;
    for (std::size_t i = 0; i < 2 * kN; ++i) differ += a[i] != b[i];
    EXPECT_EQ(differ, 0u) << name;
    // The later frame: every row filled (a missing block reads NaN) and each ID where one rank
    // has it. The ranks sum the forces in another order, so the two runs agree to round-off,
    // grown by the few collisions of 0.01 time units: 1e-9 sigma is far below any permutation
    // (neighbouring IDs lie ~1 sigma apart), far above round-off.
    const double edge[2] = {15708.0, 100.0};
    double worst = 0.0;
    std::size_t missing = 0;
    for (std::size_t i = 2 * kN; i < 4 * kN; ++i) {
      missing += !std::isfinite(b[i]);
      double d = std::abs(a[i] - b[i]);
      if (name == std::string("position")) d = std::min(d, std::abs(d - edge[i % 2]));
      worst = std::max(worst, d);
    }
    EXPECT_EQ(missing, 0u) << name;
    EXPECT_LT(worst, 1e-9) << name;
  }
  // Each rank's block file holds its own rows only: no rank allocated a frame of all N.
  for (int k = 0; k < 2; ++k) {
    const auto file = two / ("particles.rank000" + std::to_string(k) + ".h5");
    hsize_t dims[3];
    all_frames(file, "/particles/all/position/value", dims);
    EXPECT_EQ(dims[1], k == 0 ? 50000u : 50001u) << file;
  }
  const std::string h5py =
      "/usr/bin/python3 -c \"import h5py, numpy; f = h5py.File('" +
      (two / "particles.h5").string() +
      "', 'r'); v = f['particles/all/velocity/value']; assert v.is_virtual and v.shape == (2, " +
      std::to_string(kN) + ", 2) and numpy.isfinite(v[()]).all()\"";
  EXPECT_EQ(std::system(h5py.c_str()), 0) << h5py;
  std::filesystem::remove_all(one);
  std::filesystem::remove_all(two);
}

}  // namespace
}  // namespace granvv::md
