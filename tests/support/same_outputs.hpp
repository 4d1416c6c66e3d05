#pragma once
// Two output folders of the same case compared bit for bit, wall times aside: what a run whose
// members ran elsewhere (other threads, ranks or groups of ranks) must equal.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace granvv::testing {

// A key whose value is a wall time, a rate per wall second, or names the run or its folder.
bool depends_on_the_clock(const std::string& key);

// The leaves of a summary by their path, clock-dependent ones left out.
std::map<std::string, nlohmann::json> summary_leaves(const std::filesystem::path& summary);

// Every numeric dataset of an HDF5 file, as doubles, by its path (clock-dependent ones left out).
std::map<std::string, std::vector<double>> numeric_datasets(const std::filesystem::path& file);

// The same doubles bit for bit (a NaN where the other has the same NaN: a missing value).
bool same_bits(const std::vector<double>& a, const std::vector<double>& b);

// The summary's leaves (but those whose path contains one of `differing`: a key the two runs set
// differently), the numeric datasets of results.h5 and of every member's particle file
// (particles_m<m>.h5) are the same in both folders. Returns the first folder's summary leaves.
std::map<std::string, nlohmann::json> expect_same_outputs(
    const std::filesystem::path& one, const std::filesystem::path& two, int members,
    const std::vector<std::string>& differing = {});

}  // namespace granvv::testing
