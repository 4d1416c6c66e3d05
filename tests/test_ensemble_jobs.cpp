// Ensemble members in threads (granvv run --jobs, scene/md_members.hpp) through the real CLI:
// the outputs of --jobs 2 are those of --jobs 1 bit for bit (member m samples with md.seed + m
// whatever runs it, and the ensemble is reduced in member order), wall times aside.
#include <H5Cpp.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/cli_runner.hpp"

namespace granvv {
namespace {

namespace fs = std::filesystem;

// A key whose value is a wall time, a rate per wall second, or names the run or its folder.
bool depends_on_the_clock(const std::string& key) {
  for (const char* part : {"wall", "per_second", "run_id", "output_dir", "seconds"}) {
    if (key.find(part) != std::string::npos) return true;
  }
  return false;
}

// The leaves of a summary by their path, clock-dependent ones left out.
void leaves(const nlohmann::json& j, const std::string& path,
            std::map<std::string, nlohmann::json>& out) {
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) {
      if (!depends_on_the_clock(key)) leaves(value, path + "/" + key, out);
    }
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) leaves(j[i], path + "/" + std::to_string(i), out);
  } else {
    out[path] = j;
  }
}

// Every numeric dataset of an HDF5 file, as doubles, by its path (clock-dependent ones left out).
std::map<std::string, std::vector<double>> numeric_datasets(const fs::path& file) {
  std::map<std::string, std::vector<double>> out;
  const H5::H5File h5(file.string(), H5F_ACC_RDONLY);
  const auto visit = [](hid_t object, const char* name, const H5O_info_t* info, void* data) {
    if (info->type != H5O_TYPE_DATASET || depends_on_the_clock(name)) return herr_t(0);
    const H5::DataSet set(H5Dopen2(object, name, H5P_DEFAULT));
    const H5T_class_t type = set.getTypeClass();
    if (type != H5T_FLOAT && type != H5T_INTEGER) return herr_t(0);
    std::vector<double> values(std::size_t(set.getSpace().getSimpleExtentNpoints()));
    if (!values.empty()) set.read(values.data(), H5::PredType::NATIVE_DOUBLE);
    (*static_cast<std::map<std::string, std::vector<double>>*>(data))[name] = values;
    return herr_t(0);
  };
  H5Ovisit(h5.getId(), H5_INDEX_NAME, H5_ITER_NATIVE, visit, &out);
  return out;
}

// The same doubles bit for bit (a NaN where the other has the same NaN: a missing value).
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

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

// The summary's leaves and the numeric datasets of results.h5 and of every member's particle
// file are the same in both folders (wall times aside).
void expect_same_outputs(const fs::path& one, const fs::path& two, int members) {
  std::map<std::string, nlohmann::json> s1, s2;
  leaves(nlohmann::json::parse(testing::read_text(one / "summary.json")), "", s1);
  leaves(nlohmann::json::parse(testing::read_text(two / "summary.json")), "", s2);
  EXPECT_EQ(s1.at("/md/ensemble"), members);
  EXPECT_GT(s1.at("/md/collisions").get<double>(), 1e3);
  ASSERT_EQ(s1.size(), s2.size());
  for (const auto& [path, value] : s1) EXPECT_EQ(value, s2.at(path)) << path;

  const auto h1 = numeric_datasets(one / "results.h5"), h2 = numeric_datasets(two / "results.h5");
  EXPECT_GT(h1.size(), 20u);
  ASSERT_EQ(h1.size(), h2.size());
  for (const auto& [path, values] : h1) EXPECT_TRUE(same_bits(values, h2.at(path))) << path;

  // Each member's particle frames, written while another member ran.
  for (int m = 0; m < members; ++m) {
    const std::string name = "particles_m" + std::to_string(m) + ".h5";
    const auto f1 = numeric_datasets(one / name), f2 = numeric_datasets(two / name);
    EXPECT_FALSE(f1.empty()) << name;
    for (const auto& [path, values] : f1)
      EXPECT_TRUE(same_bits(values, f2.at(path))) << name << path;
  }
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
