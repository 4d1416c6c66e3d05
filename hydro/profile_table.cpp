#include "hydro/profile_table.hpp"

#include <H5Cpp.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "fields/hdf5_datasets.hpp"

namespace granvv::hydro {
namespace {

constexpr std::size_t kMinRows = 4;  // the monotone cubic needs two secants on each side
const std::string kUtf8Bom = "\xEF\xBB\xBF";
constexpr std::size_t kQuotedCharacters = 40;  // of a cell quoted in a message

// A cell as a message quotes it: at most kQuotedCharacters, control bytes as '?'.
std::string quoted(const std::string& cell) {
  std::string out = cell.substr(0, kQuotedCharacters);
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  if (cell.size() > kQuotedCharacters)
    out += "... (" + std::to_string(cell.size()) + " characters)";
  return "'" + out + "'";
}

std::string number(double x) {
  std::ostringstream os;
  os.precision(10);
  os << x;
  return os.str();
}

// The column called name (nullptr for another name), const or not with the table.
template <typename Table>
auto column(Table& t, const std::string& name) -> decltype(&t.x) {
  if (name == "x") return &t.x;
  if (name == "n") return &t.n;
  if (name == "v_x") return &t.v_x;
  if (name == "v_y") return &t.v_y;
  if (name == "T") return &t.T;
  return nullptr;
}

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(trimmed(cell));
  return out;
}

void require_columns(const ProfileTable& t, const std::string& where) {
  for (const char* name : {"x", "n", "v_x", "T"}) {
    if (column(t, name)->empty()) {
      throw std::runtime_error(where + " has no column " + name +
                               " (needed: x, n, v_x, T; optional: v_y)");
    }
  }
}

ProfileTable read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  ProfileTable t;
  std::vector<std::vector<double>*> order;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (line_number == 1) {
      // Spreadsheet programs save "CSV UTF-8" with a byte-order mark: not part of the header.
      if (line.rfind(kUtf8Bom, 0) == 0) line.erase(0, kUtf8Bom.size());
      if (line.rfind("\xFF\xFE", 0) == 0 || line.rfind("\xFE\xFF", 0) == 0) {
        throw std::runtime_error(path +
                                 " is UTF-16 text (allowed: UTF-8 or ASCII; save it as "
                                 "\"CSV UTF-8\" or plain CSV)");
      }
    }
    const std::string text = trimmed(line.substr(0, line.find('#')));
    if (text.empty()) continue;
    const auto cells = split_commas(text);
    if (order.empty()) {  // the header
      for (const auto& name : cells) {
        auto* c = column(t, name);
        if (!c) {
          throw std::runtime_error(path + ":" + std::to_string(line_number) + ": column " +
                                   quoted(name) + " is not one of x, n, v_x, v_y, T");
        }
        if (std::find(order.begin(), order.end(), c) != order.end()) {
          throw std::runtime_error(path + ":" + std::to_string(line_number) + ": column '" + name +
                                   "' appears twice");
        }
        order.push_back(c);
      }
      continue;
    }
    if (cells.size() != order.size()) {
      throw std::runtime_error(path + ":" + std::to_string(line_number) + ": " +
                               std::to_string(cells.size()) + " values for " +
                               std::to_string(order.size()) + " columns");
    }
    for (std::size_t i = 0; i < cells.size(); ++i) {
      char* end = nullptr;
      const double v = std::strtod(cells[i].c_str(), &end);
      if (cells[i].empty() || *end != '\0') {
        throw std::runtime_error(path + ":" + std::to_string(line_number) + ": " +
                                 quoted(cells[i]) + " is not a number");
      }
      order[i]->push_back(v);
    }
  }
  if (order.empty()) throw std::runtime_error(path + " is empty (expected a header x, n, v_x, T)");
  require_columns(t, path);
  return t;
}

ProfileTable read_hdf5(const std::string& path, const std::string& group_name) {
  ProfileTable t;
  try {
    H5::Exception::dontPrint();
    const H5::H5File file(path, H5F_ACC_RDONLY);
    const H5::Group group = file.openGroup(group_name);
    for (const auto& name : profile_table_columns()) {
      if (!group.nameExists(name)) continue;
      h5::DoubleArray a;
      try {
        a = h5::read_doubles(group, name);
      } catch (const std::runtime_error& e) {
        throw std::runtime_error(path + ":" + group_name + ": " + e.what());
      }
      if (a.shape.size() != 1) {
        throw std::runtime_error(path + ":" + group_name + "/" + name + " is not 1D");
      }
      *column(t, name) = a.values;
    }
  } catch (const H5::Exception& e) {
    const std::string why = h5::hdf5_open_problem(path);
    throw std::runtime_error(
        why.empty() ? "cannot read group " + group_name + " of " + path + " as HDF5" : why);
  }
  require_columns(t, path + ":" + group_name);
  return t;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

const std::vector<std::string>& profile_table_columns() {
  static const std::vector<std::string> names = {"x", "n", "v_x", "v_y", "T"};
  return names;
}

std::optional<std::string> profile_table_problem(const ProfileTable& t) {
  const std::size_t rows = t.x.size();
  if (rows < kMinRows) {
    return "has " + std::to_string(rows) + " rows; at least " + std::to_string(kMinRows) +
           " are needed";
  }
  for (const auto& name : profile_table_columns()) {
    const auto& c = *column(t, name);
    if (c.empty() && name == "v_y") continue;
    if (c.size() != rows) {
      return "column " + name + " has " + std::to_string(c.size()) + " values for " +
             std::to_string(rows) + " rows";
    }
    for (std::size_t i = 0; i < rows; ++i) {
      const std::string row = "row " + std::to_string(i + 1) + ": ";
      if (!std::isfinite(c[i])) return row + name + " = " + number(c[i]) + " is not finite";
      if ((name == "n" || name == "T") && !(c[i] > 0.0)) {
        return row + name + " = " + number(c[i]) + " must be > 0";
      }
      if (name == "x" && (c[i] < -0.5 || c[i] > 0.5)) {
        return row + "x = " + number(c[i]) + " is outside the period [-1/2, 1/2]";
      }
      if (name == "x" && i > 0 && !(c[i] > c[i - 1])) {
        return row + "x = " + number(c[i]) +
               " does not exceed the previous row's x = " + number(c[i - 1]) +
               " (rows must be in increasing x)";
      }
    }
  }
  double spacing = 0.0;
  for (std::size_t i = 1; i < rows; ++i) spacing = std::max(spacing, t.x[i] - t.x[i - 1]);
  const double gap = t.x.front() + 1.0 - t.x.back();
  if (!(gap > 0.0) || gap > 2.0 * spacing) {
    return "does not span the period: x runs from " + number(t.x.front()) + " to " +
           number(t.x.back()) + ", leaving " + number(gap) +
           " across x = +-1/2 (allowed: more than 0 and at most twice the largest spacing of "
           "the rows, " +
           number(spacing) + ")";
  }
  return std::nullopt;
}

bool carries_transverse_velocity(const ProfileTable& t) {
  return std::any_of(t.v_y.begin(), t.v_y.end(), [](double v) { return v != 0.0; });
}

std::optional<std::string> mean_density_problem(double mean) {
  if (std::abs(mean - 1.0) <= kMeanDensityTolerance) return std::nullopt;
  return "has a mean density of " + number(mean) +
         " over the box; n is in units of the mean density n0, so its mean must be 1 (within " +
         number(kMeanDensityTolerance) + "): divide n by " + number(mean);
}

ProfileTable wrapped_into_period(ProfileTable t) {
  std::vector<std::size_t> order(t.x.size());
  std::iota(order.begin(), order.end(), 0);
  for (double& x : t.x) x -= std::floor(x + 0.5);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return t.x[a] < t.x[b]; });
  ProfileTable out;
  for (const auto& name : profile_table_columns()) {
    const auto& from = *column(t, name);
    auto& to = *column(out, name);
    if (from.size() != order.size()) {
      to = from;
      continue;
    }
    for (const std::size_t i : order) to.push_back(from[i]);
  }
  return out;
}

InitialFields profile_fields(const ProfileTable& t, Interpolation interpolation) {
  InitialFields f;
  f.n = periodic_interpolant(t.x, t.n, interpolation);
  f.v = periodic_interpolant(t.x, t.v_x, interpolation);
  f.T = periodic_interpolant(t.x, t.T, interpolation);
  f.breaks = t.x;
  f.vy = t.v_y.empty() ? std::function<double(double)>([](double) { return 0.0; })
                       : periodic_interpolant(t.x, t.v_y, interpolation);
  return f;
}

ProfileTable read_profile_table(const std::string& path, const std::string& group) {
  if (ends_with(path, ".csv")) return read_csv(path);
  if (ends_with(path, ".h5") || ends_with(path, ".hdf5")) return read_hdf5(path, group);
  throw std::runtime_error("'" + path + "' must end in .csv, .h5 or .hdf5");
}

}  // namespace granvv::hydro
