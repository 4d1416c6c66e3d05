// The user's own profiles as a table: columns x, n, v_x, (v_y), T from a CSV file or the 1D
// datasets of an HDF5 group (hydro/profile_table.hpp), x on [-1/2, 1/2), interpolated
// periodically (linear or monotone cubic). The hydro's cells take exact averages of the
// interpolant (hydro/initial_conditions.hpp: mass by quadrature, T mass-weighted), so its mass
// and energy are the interpolant's to quadrature accuracy.
#include <filesystem>

#include "hydro/field_integrals.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "hydro/profile_table.hpp"

namespace granvv::hydro {

// Shared with snapshot (hydro/initial_snapshot.cpp): declared identically.
ParameterSpec initial_file_parameter() {
  return {"from", std::string(""), ParameterRange::any(),
          "the file to start from: a CSV or HDF5 table (table), a previous run's results.h5 "
          "(snapshot)"};
}
ParameterSpec initial_interpolation_parameter() {
  return {"interpolation", std::string("cubic"), ParameterRange::one_of(interpolation_names()),
          "periodic interpolation between the rows or cells: \"linear\" or monotone \"cubic\""};
}

// A file that is not there, one line.
std::optional<ParameterProblem> missing_file_problem(const std::string& path) {
  std::error_code ec;
  if (path.empty()) return ParameterProblem{"from", "needs a file name"};
  if (!std::filesystem::is_regular_file(path, ec)) {
    return ParameterProblem{"from", "file '" + path + "' does not exist"};
  }
  return std::nullopt;
}

InitialConditionType table_initial_condition() {
  InitialConditionType type;
  type.name = "table";
  type.parameters = {
      initial_file_parameter(),
      {"dataset", std::string("/"), ParameterRange::any(),
       "the HDF5 group holding the 1D datasets x, n, v_x, (v_y), T of an .h5 table"},
      initial_interpolation_parameter(),
  };
  type.problem = [](const ParameterSet& p) -> std::optional<ParameterProblem> {
    if (auto missing = missing_file_problem(p.text("from"))) return missing;
    try {
      const auto table = read_profile_table(p.text("from"), p.text("dataset"));
      if (const auto why = profile_table_problem(table)) {
        return ParameterProblem{"from", "the table " + *why};
      }
      const auto fields = profile_fields(table, interpolation_from_name(p.text("interpolation")));
      if (const auto why = mean_density_problem(mean_density(fields))) {
        return ParameterProblem{"from", "the table " + *why};
      }
    } catch (const std::runtime_error& e) {
      return ParameterProblem{"from", e.what()};
    }
    return std::nullopt;
  };
  type.generate = [](const ParameterSet& p, const Closure&) {
    return profile_fields(read_profile_table(p.text("from"), p.text("dataset")),
                          interpolation_from_name(p.text("interpolation")));
  };
  type.files = [](const ParameterSet& p) { return std::vector<std::string>{p.text("from")}; };
  type.field_parameters = {"from", "from", "from", "from"};
  type.has_transverse_velocity = [](const ParameterSet& p) {
    return carries_transverse_velocity(read_profile_table(p.text("from"), p.text("dataset")));
  };
  return type;
}

}  // namespace granvv::hydro
