#include "support/same_outputs.hpp"

#include <H5Cpp.h>
#include <gtest/gtest.h>

#include <cstring>
#include <nlohmann/json.hpp>

#include "support/cli_runner.hpp"

namespace granvv::testing {

namespace fs = std::filesystem;

namespace {

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

bool names_one_of(const std::string& path, const std::vector<std::string>& keys) {
  for (const std::string& key : keys) {
    if (path.find(key) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

bool depends_on_the_clock(const std::string& key) {
  for (const char* part : {"wall", "per_second", "run_id", "output_dir", "seconds"}) {
    if (key.find(part) != std::string::npos) return true;
  }
  return false;
}

std::map<std::string, nlohmann::json> summary_leaves(const fs::path& summary) {
  std::map<std::string, nlohmann::json> out;
  leaves(nlohmann::json::parse(read_text(summary)), "", out);
  return out;
}

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

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

std::map<std::string, nlohmann::json> expect_same_outputs(
    const fs::path& one, const fs::path& two, int members,
    const std::vector<std::string>& differing) {
  auto s1 = summary_leaves(one / "summary.json"), s2 = summary_leaves(two / "summary.json");
  EXPECT_EQ(s1.at("/md/ensemble"), members);
  EXPECT_EQ(s1.size(), s2.size());
  for (const auto& [path, value] : s1) {
    if (names_one_of(path, differing)) continue;
    const auto other = s2.find(path);
    if (other == s2.end()) {
      ADD_FAILURE() << path << " only in " << one;
      continue;
    }
    EXPECT_EQ(value, other->second) << path;
  }

  const auto h1 = numeric_datasets(one / "results.h5"), h2 = numeric_datasets(two / "results.h5");
  EXPECT_GT(h1.size(), 20u);
  EXPECT_EQ(h1.size(), h2.size());
  for (const auto& [path, values] : h1) {
    const auto other = h2.find(path);
    if (other == h2.end()) {
      ADD_FAILURE() << path << " only in " << one / "results.h5";
      continue;
    }
    EXPECT_TRUE(same_bits(values, other->second)) << path;
  }

  // Each member's particle frames, written while another member ran.
  for (int m = 0; m < members; ++m) {
    const std::string name = "particles_m" + std::to_string(m) + ".h5";
    const auto f1 = numeric_datasets(one / name), f2 = numeric_datasets(two / name);
    EXPECT_FALSE(f1.empty()) << name;
    for (const auto& [path, values] : f1) {
      const auto other = f2.find(path);
      if (other == f2.end()) {
        ADD_FAILURE() << path << " only in " << one / name;
        continue;
      }
      EXPECT_TRUE(same_bits(values, other->second)) << name << path;
    }
  }
  return s1;
}

}  // namespace granvv::testing
