#pragma once
// Tabulated initial profiles: columns x, n, v_x, (v_y), T on x in [-1/2, 1/2), read from a CSV
// file or an HDF5 group, or taken from a previous run's results.h5 (initial.type = "table",
// "snapshot": hydro/initial_table.cpp, hydro/initial_snapshot.cpp), checked, and interpolated
// periodically into the continuous fields the hydro and the particle sampler take.
#include <optional>
#include <string>
#include <vector>

#include "hydro/initial_conditions.hpp"
#include "hydro/periodic_interpolation.hpp"

namespace granvv::hydro {

struct ProfileTable {
  std::vector<double> x, n, v_x, v_y, T;  // v_y empty when the table has none
};

// The column names, in this order; v_y is optional.
const std::vector<std::string>& profile_table_columns();

// The first problem, one line: fewer than 4 rows, a value that is not finite, x outside
// [-1/2, 1/2] or not strictly increasing, n <= 0 or T <= 0 in a row, or a table that does not
// span the period (the gap x_0 + 1 - x_last more than twice the largest spacing of the rows).
std::optional<std::string> profile_table_problem(const ProfileTable& table);

// True if the table has a v_y column with a value other than 0.
bool carries_transverse_velocity(const ProfileTable& table);

// n is in units of the mean density n0 (docs/physics.md §1): the reason why a profile whose
// mean density is `mean` is refused, or nullopt if it is 1 within kMeanDensityTolerance. The
// mean is the integral of the density the run uses (the table's interpolant, the formula):
// mean_density(fields), hydro/field_integrals.hpp.
inline constexpr double kMeanDensityTolerance = 1e-3;
std::optional<std::string> mean_density_problem(double mean);

// The table with x wrapped into [-1/2, 1/2) and the rows sorted by x (a Lagrangian mesh's cell
// centres run past 1/2).
ProfileTable wrapped_into_period(ProfileTable table);

// Periodic interpolants of every column (profile_table_problem must have found nothing).
InitialFields profile_fields(const ProfileTable& table, Interpolation interpolation);

// Reads the columns of a CSV file (a header line naming the columns in any order, '#' comments)
// or, for a file ending in .h5 or .hdf5, the 1D datasets of `group`. Throws std::runtime_error
// with a one-line reason.
ProfileTable read_profile_table(const std::string& path, const std::string& group);

// The parameters both file-reading types declare (initial.from, initial.interpolation), and the
// refusal of a file name that is empty or names no file (parameter "from").
ParameterSpec initial_file_parameter();
ParameterSpec initial_interpolation_parameter();
std::optional<ParameterProblem> missing_file_problem(const std::string& path);

}  // namespace granvv::hydro
