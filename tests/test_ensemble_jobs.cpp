// Ensemble members in threads (granvv run --jobs, scene/md_members.hpp) through the real CLI:
// the outputs of --jobs 2 are those of --jobs 1 bit for bit (member m samples with md.seed + m
// whatever runs it, and the ensemble is reduced in member order), wall times aside.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/cli_runner.hpp"
#include "support/same_outputs.hpp"

namespace granvv {
namespace {

namespace fs = std::filesystem;

// A small event-driven ensemble: 4 members of 1000 disks, with particle frames and checkpoints at
// every sample (HDF5 writes from every member while the others run).
const char* const kSmallEnsemble =
    "run md_haff --quiet --no-report --set md.engine=event_driven --set md.particles=1000 "
    "--set md.box_width=125 --set md.ensemble=4 --set md.t_end=8 --set md.sample_interval=1 "
    "--set 'md.output_times=[0, 4, 8]' --set md.snapshot_interval=4 "
    "--set md.checkpoint_interval=1e-6";

testing::CliResult run_with_jobs(int jobs, const fs::path& dir) {
  return testing::run_cli(std::string(kSmallEnsemble) + " --jobs " + std::to_string(jobs) +
                          " --out " + dir.string());
}

// The outputs of both folders are the same bit for bit (support/same_outputs.hpp), and the
// members collided.
void expect_same_outputs(const fs::path& one, const fs::path& two, int members) {
  const auto summary = testing::expect_same_outputs(one, two, members);
  EXPECT_GT(summary.at("/md/collisions").get<double>(), 1e3);
}

TEST(EnsembleJobs, TwoJobsGiveTheOutputsOfOneBitForBit) {
  const fs::path one = testing::fresh_directory("ensemble-jobs-1");
  const fs::path two = testing::fresh_directory("ensemble-jobs-2");
  const auto r1 = run_with_jobs(1, one);
  ASSERT_EQ(r1.exit_code, 0) << r1.output;
  const auto r2 = run_with_jobs(2, two);
  ASSERT_EQ(r2.exit_code, 0) << r2.output;

  expect_same_outputs(one, two, 4);
  fs::remove_all(one);
  fs::remove_all(two);
}

// Under mpirun -np 2 each rank runs its members (m = rank mod 2) and rank 0 writes them all: the
// outputs of one rank, bit for bit.
TEST(EnsembleJobs, TwoMpiRanksGiveTheOutputsOfOneBitForBit) {
  const fs::path one = testing::fresh_directory("ensemble-ranks-1");
  const fs::path two = testing::fresh_directory("ensemble-ranks-2");
  const auto r1 = run_with_jobs(1, one);
  ASSERT_EQ(r1.exit_code, 0) << r1.output;
  const auto r2 = testing::run_shell("mpirun --allow-run-as-root --oversubscribe -np 2 " +
                                     std::string(GRANVV_BINARY) + " " + kSmallEnsemble +
                                     " --jobs 1 --out " + two.string());
  ASSERT_EQ(r2.exit_code, 0) << r2.output;
  expect_same_outputs(one, two, 4);
  fs::remove_all(one);
  fs::remove_all(two);
}

// A bad --jobs: one line naming it, exit 2 (CLI11's own check), nothing run.
TEST(EnsembleJobs, ANonPositiveJobCountIsRefused) {
  const auto r = testing::run_cli("run md_haff --dry-run --jobs 0");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--jobs"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace granvv
