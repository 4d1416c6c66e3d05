#include "app/results_file.hpp"

#include <H5Cpp.h>

#include <cmath>
#include <limits>

#include "fields/field_series_file.hpp"
#include "fields/hdf5_datasets.hpp"
#include "hydro/haff.hpp"
#include "hydro/linear_stability.hpp"
#include "hydro/time_series.hpp"

namespace granvv::app {
namespace {

using h5::write_attribute;
using h5::write_matrix;
using h5::write_vector;

// One dataset per column of hydro/time_series.hpp, in its order; a column the run did not
// record (the area fraction without phi0) is left out.
void write_time_series(H5::Group g, const hydro::TimeSeries& ts) {
  for (const auto& column : hydro::time_series_columns()) {
    if (!(ts.*column.values).empty()) write_vector(g, column.name, ts.*column.values);
  }
}

// The hydro's native Lagrangian arrays of its snapshots.
void write_lagrangian(H5::Group g, const HydroOutcome& out) {
  const auto& snaps = out.run.snapshots;
  const hsize_t rows = snaps.size();
  std::vector<double> node_x, node_v, xi, v0;
  for (size_t k = 0; k < snaps.size(); ++k) {
    const auto& s = snaps[k].state;
    node_x.insert(node_x.end(), s.node_x.begin(), s.node_x.end());
    node_v.insert(node_v.end(), s.node_v.begin(), s.node_v.end());
    xi.insert(xi.end(), out.snapshots[k].xi.begin(), out.snapshots[k].xi.end());
    v0.insert(v0.end(), out.snapshots[k].inertia_v0.begin(), out.snapshots[k].inertia_v0.end());
  }
  write_matrix(g, "node_x", node_x, rows);
  write_matrix(g, "node_v_x", node_v, rows);
  write_matrix(g, "xi", xi, rows);
  write_matrix(g, "inertia_v0", v0, rows);
  write_vector(g, "cell_mass", snaps.front().state.cell_mass);
}

void write_theory(H5::Group g, const HydroScene& scene, const HydroOutcome& out) {
  const auto& p = scene.physics;
  const auto closure = make_hydro_closure(scene);
  const int kmax = std::clamp(2 * out.shear_unstable_modes, 20, 10000);  // at most 240 kB
  std::vector<double> k, clustering, shear;
  for (int m = 1; m <= kmax; ++m) {
    k.push_back(m);
    clustering.push_back(hydro::hcs_modes(*closure, m)[0].rate.real());
    shear.push_back(hydro::shear_rate(*closure, m));
  }
  write_vector(g, "mode_k", k);
  write_vector(g, "clustering_rate", clustering);
  write_vector(g, "shear_rate", shear);
  // The physics the hydro ran with (in a comparison, the particle scene's K and q).
  write_attribute(g, "K", p.K);
  write_attribute(g, "q", p.q);
  write_attribute(g, "t0", hydro::haff_time_scale(*closure));
  write_attribute(g, "closure", scene.closure);
  write_attribute(g, "cooling", hydro::to_string(scene.cooling));
  write_attribute(g, "area_fraction", scene.area_fraction);
  write_attribute(g, "unstable_modes", double(out.unstable_modes));
  write_attribute(g, "shear_unstable_modes", double(out.shear_unstable_modes));
  write_attribute(g, "inertia_tau",
                  out.inertia_tau.value_or(std::numeric_limits<double>::quiet_NaN()));
}

void write_convergence(H5::Group g, const hydro::ConvergenceStudy& c) {
  std::vector<double> cells(c.cells.begin(), c.cells.end());
  write_vector(g, "cells", cells);
  write_vector(g, "error_x", c.error_x);
  write_vector(g, "error_v", c.error_v);
  write_vector(g, "error_n", c.error_n);
  write_vector(g, "error_T", c.error_T);
  write_attribute(g, "t", c.t);
  write_attribute(g, "order_x", c.order_x.back());
  write_attribute(g, "order_v", c.order_v.back());
  write_attribute(g, "order_n", c.order_n.back());
  write_attribute(g, "order_T", c.order_T.back());
}

}  // namespace

void create_results_file(const std::filesystem::path& file, const RunMetadata& meta) {
  H5::Exception::dontPrint();
  H5::H5File h5(file.string(), H5F_ACC_TRUNC);
  H5::Group root = h5.openGroup("/");
  write_attribute(root, "granvv_version", meta.version);
  write_attribute(root, "case", meta.case_name);
  write_attribute(root, "config_toml", meta.config_toml);
  for (const auto& [key, value] : meta.config) write_attribute(root, key, value);
}

void write_hydro_results(const std::filesystem::path& file, const HydroScene& scene,
                         const HydroOutcome& out, const std::string& root) {
  H5::Exception::dontPrint();
  H5::H5File h5(file.string(), H5F_ACC_RDWR);
  H5::Group hydro_group = h5.createGroup(root);
  write_time_series(h5.createGroup(root + "/timeseries"), out.run.series);
  H5::Group fields = h5.createGroup(root + "/fields");
  fields::write_field_series(fields, out.cell_fields);
  write_lagrangian(h5.createGroup(root + "/lagrangian"), out);
  write_theory(h5.createGroup(root + "/theory"), scene, out);
  if (out.convergence) write_convergence(h5.createGroup(root + "/convergence"), *out.convergence);
}

void create_group(const std::filesystem::path& file, const std::string& path) {
  H5::Exception::dontPrint();
  H5::H5File h5(file.string(), H5F_ACC_RDWR);
  h5.createGroup(path);
}

}  // namespace granvv::app
