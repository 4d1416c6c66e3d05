// A previous run's state: the fields of its results.h5 at initial.time, from the hydro
// (/hydro/fields, on its cells) or from the particles (/md/fields, the ensemble mean on the
// bins, MD units scaled by Lx and n0 = N/(Lx Ly): docs/physics.md §4). The values become a
// periodic table through the cell or bin centres (hydro/profile_table.hpp), so the run
// continues a hydro, starts a hydro from particles, or starts particles from a hydro state.
#include <H5Cpp.h>

#include <cmath>
#include <sstream>

#include "fields/field_series_file.hpp"
#include "fields/hdf5_datasets.hpp"
#include "hydro/field_integrals.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "hydro/profile_table.hpp"

namespace granvv::hydro {
namespace {

// A snapshot matches initial.time within this, relative to max(1, |time|): the particles'
// snapshots fall on the nearest MD step (1e-6 relative in the shipped scenes).
constexpr double kTimeTolerance = 1e-4;

struct SnapshotProblem : std::runtime_error {
  SnapshotProblem(std::string parameter, const std::string& reason)
      : std::runtime_error(reason), parameter(std::move(parameter)) {}
  std::string parameter;
};

std::string number(double x) {
  std::ostringstream os;
  os.precision(10);
  os << x;
  return os.str();
}

// A snapshot's columns x, n, v_x, T (v_y optional) must have one value per position.
std::optional<std::string> snapshot_shape_problem(const fields::FieldSnapshot& s) {
  if (s.x.empty()) return std::string("it has no positions x");
  const std::pair<const char*, const std::vector<double>*> columns[] = {
      {"n", &s.n}, {"v_x", &s.v_x}, {"v_y", &s.v_y}, {"T", &s.T}};
  for (const auto& [name, values] : columns) {
    if (values->empty() && std::string(name) == "v_y") continue;
    if (values->size() != s.x.size()) {
      return "column " + std::string(name) + " has " + std::to_string(values->size()) +
             " values for " + std::to_string(s.x.size()) + " positions x";
    }
  }
  return std::nullopt;
}

// The times and the columns x, n, v_x, v_y, T of a FieldSeries group (fields/field_series_file),
// numbers only: its labels and geometry, variable-length strings that the HDF5 library reads
// without bounds checks in a damaged file, are not needed here.
fields::FieldSeries snapshot_fields(const H5::Group& g) {
  fields::FieldSeries series;
  for (const double t : h5::read_doubles(g, "t").values) {
    series.snapshots.emplace_back();
    series.snapshots.back().t = t;
  }
  const std::pair<const char*, std::vector<double> fields::FieldSnapshot::*> columns[] = {
      {"x", &fields::FieldSnapshot::x},
      {"n", &fields::FieldSnapshot::n},
      {"v_x", &fields::FieldSnapshot::v_x},
      {"v_y", &fields::FieldSnapshot::v_y},
      {"T", &fields::FieldSnapshot::T}};
  for (const auto& [name, column] : columns) {
    if (!g.nameExists(name)) continue;
    const h5::DoubleArray a = h5::read_doubles(g, name);
    if (a.shape.size() != 2 || a.shape[0] != series.snapshots.size()) {
      throw std::runtime_error("dataset " + std::string(name) + " is not [" +
                               std::to_string(series.snapshots.size()) + " x N]");
    }
    const std::size_t width = a.shape[1];
    for (std::size_t k = 0; k < series.snapshots.size(); ++k) {
      const auto row = a.values.begin() + static_cast<std::ptrdiff_t>(k * width);
      (series.snapshots[k].*column).assign(row, row + static_cast<std::ptrdiff_t>(width));
    }
  }
  return series;
}

ProfileTable read_snapshot(const ParameterSet& p) {
  const std::string path = p.text("from"), source = p.text("source");
  const double time = p.real("time");
  const std::string group_name = "/" + source + "/fields";
  H5::Exception::dontPrint();
  fields::FieldSeries series;
  double length = 1.0, density = 1.0;  // the units of the file's x and n
  try {
    const H5::H5File file(path, H5F_ACC_RDONLY);
    if (!file.nameExists("/" + source) || !file.nameExists(group_name)) {
      throw SnapshotProblem("source", path + " has no " + group_name + ": it is not a run with " +
                                          (source == "md" ? "md.enabled" : "hydro.enabled") +
                                          " (allowed: a source the file has)");
    }
    series = snapshot_fields(file.openGroup(group_name));
    if (source == "md") {
      const H5::Group md = file.openGroup("/md");
      length = h5::read_double_attribute(md, "box_length");
      density = h5::read_double_attribute(md, "particles") /
                (length * h5::read_double_attribute(md, "box_width"));
    }
  } catch (const H5::Exception&) {
    const std::string why = h5::hdf5_open_problem(path);
    throw SnapshotProblem("from",
                          why.empty() ? "cannot read " + path + " as a granvv results.h5" : why);
  } catch (const std::runtime_error& e) {
    if (const auto* problem = dynamic_cast<const SnapshotProblem*>(&e)) throw *problem;
    throw SnapshotProblem("from", path + ": " + e.what());
  }
  const fields::FieldSnapshot* found = nullptr;
  std::string times;
  for (const auto& s : series.snapshots) {
    times += (times.empty() ? "" : ", ") + number(s.t);
    if (std::abs(s.t - time) <= kTimeTolerance * std::max(1.0, std::abs(time))) found = &s;
  }
  if (!found) {
    throw SnapshotProblem("time", "t = " + number(time) + " is not in " + path + group_name +
                                      " (its times: " + (times.empty() ? "none" : times) + ")");
  }
  if (const auto why = snapshot_shape_problem(*found)) {
    throw SnapshotProblem("from", path + group_name + " at t = " + number(found->t) + ": " + *why);
  }
  ProfileTable t;
  for (std::size_t i = 0; i < found->x.size(); ++i) {
    t.x.push_back(found->x[i] / length);
    t.n.push_back(found->n[i] / density);
  }
  t.v_x = found->v_x;
  t.v_y = found->v_y;
  t.T = found->T;
  return wrapped_into_period(std::move(t));
}

}  // namespace

InitialConditionType snapshot_initial_condition() {
  InitialConditionType type;
  type.name = "snapshot";
  type.parameters = {
      initial_file_parameter(),
      {"time", 0.0, ParameterRange::at_least(0),
       "the snapshot time in the file (source = \"md\": MD units, as md.output_times)"},
      {"source", std::string("hydro"), ParameterRange::one_of({"hydro", "md"}),
       "whose fields: the hydro's (/hydro/fields) or the particles' (/md/fields)"},
      initial_interpolation_parameter(),
  };
  type.problem = [](const ParameterSet& p) -> std::optional<ParameterProblem> {
    if (auto missing = missing_file_problem(p.text("from"))) return missing;
    try {
      const ProfileTable table = read_snapshot(p);
      if (const auto why = profile_table_problem(table)) {
        return ParameterProblem{"from", "the snapshot's fields: " + *why};
      }
      // Interpolated between uneven cells (a steep state's), the density may hold another mass
      // than the run it came from: refused as a table with that mean is.
      const double mean =
          mean_density(profile_fields(table, interpolation_from_name(p.text("interpolation"))));
      if (std::abs(mean - 1.0) > kMeanDensityTolerance) {
        return ParameterProblem{
            "from", "the snapshot's density, interpolated (initial.interpolation = \"" +
                        p.text("interpolation") + "\") between its " +
                        std::to_string(table.x.size()) + " positions, holds a mean density of " +
                        number(mean) + " where the run holds 1 (allowed: within " +
                        number(kMeanDensityTolerance) +
                        "): its cells are too uneven to continue from; choose an earlier "
                        "initial.time"};
      }
    } catch (const SnapshotProblem& e) {
      return ParameterProblem{e.parameter, e.what()};
    }
    return std::nullopt;
  };
  type.generate = [](const ParameterSet& p, const Closure&) {
    return profile_fields(read_snapshot(p), interpolation_from_name(p.text("interpolation")));
  };
  type.files = [](const ParameterSet& p) { return std::vector<std::string>{p.text("from")}; };
  type.field_parameters = {"from", "from", "from", "from"};
  type.has_transverse_velocity = [](const ParameterSet& p) {
    return carries_transverse_velocity(read_snapshot(p));
  };
  return type;
}

}  // namespace granvv::hydro
