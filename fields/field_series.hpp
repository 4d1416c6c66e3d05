#pragma once
// FieldSeries: the one notion of "fields over time" that every model of a scene produces and
// compare/ consumes (docs/architecture.md). Snapshots (times) x positions x {n, v_x, v_y, T},
// optional standard errors and counts, and the geometry the values live on:
//   cells: a Lagrangian mesh; x are the cell centres of each snapshot (they move with the flow);
//   bins:  a fixed periodic grid; x are the bin centres, bin_edges its B + 1 edges.
// Units are the model's own (scaled for the hydro, sigma and sqrt(T0/m) for particles); the
// comparison converts (md_bridge/scaled_fields.hpp). The file layout, shared by /hydro/fields and
// /md/fields, is in docs/outputs.md.
#include <string>
#include <vector>

namespace granvv::fields {

enum class Geometry { cells, bins };
std::string to_string(Geometry g);
Geometry geometry_from_string(const std::string& name);  // throws std::invalid_argument

struct FieldSnapshot {
  double t = 0.0;
  std::string label;  // the hydro's "initial" / "output" / "final"; "output" for particles
  std::vector<double> x;
  std::vector<double> n, v_x, v_y, T;  // v_y empty when the model carries no transverse flow
  // Standard errors of the values (empty when the model has none) and, for particles, the
  // kernel-weighted particle count per bin with its error.
  std::vector<double> n_stderr, v_x_stderr, v_y_stderr, T_stderr;
  std::vector<double> count, count_stderr;
  // Particles only: the pressure tensor's diagonal (kinetic plus contact, md_bridge/
  // coarse_grainer.hpp), empty for a model without it.
  std::vector<double> P_xx, P_yy, P_xx_stderr, P_yy_stderr;
  // Particles only, in the box frame (no flow removed; md_bridge/coarse_grainer.hpp): the kinetic
  // energy density (1/2) sum m |v|^2 and its flux along x (1/2) sum m |v|^2 v_x, per unit area.
  std::vector<double> kinetic_energy, energy_flux_x, kinetic_energy_stderr, energy_flux_x_stderr;
  // Particles only: the contact (collisional) transfer of energy along x per unit area, box
  // frame, NaN where the engine does not measure it.
  std::vector<double> contact_energy_flux_x, contact_energy_flux_x_stderr;
};

// Two snapshots are at the same time when their times differ by at most kSameTimeTolerance
// max(1, |reference|): one time, written in one model's units and read in another's, differs
// only by the rounding of the unit conversion (sigma sqrt(m/T0) to Lx / sqrt(T0/m)). A time that
// is the nearest step of an engine is another matter (its engine's time resolution).
inline constexpr double kSameTimeTolerance = 1e-9;
bool same_time(double t, double reference);

struct FieldSeries {
  Geometry geometry = Geometry::cells;
  std::vector<double> bin_edges;  // bins only: B + 1 edges of the periodic grid
  std::vector<FieldSnapshot> snapshots;

  // Uniform bins on [x_lo, x_lo + length): edges set, no snapshots yet.
  static FieldSeries on_bins(double x_lo, double length, int bins);
};

// The per-position columns of a snapshot, each with its standard-error column (nullptr for
// none), in the order of the file. One list for the writer, the reader and the ensemble.
struct FieldColumn {
  const char* name;
  std::vector<double> FieldSnapshot::*values;
  std::vector<double> FieldSnapshot::*standard_error;
  bool hydrodynamic = false;  // one of the hydrodynamic fields (below)
};
const std::vector<FieldColumn>& field_columns();
// The names of the hydrodynamic fields n, v_x, v_y, T (in the order of field_columns()): the
// fields the hydro and the particles both carry (v_y where the model has transverse flow), that
// a comparison weighs and whose errors the ensemble calibrates.
const std::vector<std::string>& hydrodynamic_fields();
// The column called name ("n", "v_x", ...); throws std::invalid_argument for another name.
const FieldColumn& field_column(const std::string& name);

}  // namespace granvv::fields
