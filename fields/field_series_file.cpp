#include "fields/field_series_file.hpp"

#include <stdexcept>

#include "fields/hdf5_datasets.hpp"

namespace granvv::fields {
namespace {

// The column of every snapshot, row-major, or empty if no snapshot carries it.
std::vector<double> stacked(const FieldSeries& s, std::vector<double> FieldSnapshot::*column,
                            const std::string& name) {
  const auto& snaps = s.snapshots;
  const std::size_t width = (snaps.front().*column).size();
  std::vector<double> all;
  for (const auto& snap : snaps) {
    const auto& v = snap.*column;
    if (v.size() != width) {
      throw std::invalid_argument(
          "FieldSeries: column " + name + " has " + std::to_string(v.size()) +
          " values at t = " + std::to_string(snap.t) + " but " + std::to_string(width) +
          " at t = " + std::to_string(snaps.front().t));
    }
    all.insert(all.end(), v.begin(), v.end());
  }
  return all;
}

void write_column(H5::Group& g, const FieldSeries& s, std::vector<double> FieldSnapshot::*column,
                  const std::string& name) {
  const std::vector<double> all = stacked(s, column, name);
  if (!all.empty()) h5::write_matrix(g, name, all, s.snapshots.size());
}

// Row k of a [ns x N] dataset into every snapshot's column; absent datasets leave it empty.
void read_column(const H5::Group& g, FieldSeries& s, std::vector<double> FieldSnapshot::*column,
                 const std::string& name) {
  if (!g.nameExists(name)) return;
  const h5::DoubleArray a = h5::read_doubles(g, name);
  if (a.shape.size() != 2 || a.shape[0] != s.snapshots.size()) {
    throw std::runtime_error("FieldSeries: dataset " + name + " is not [" +
                             std::to_string(s.snapshots.size()) + " x N]");
  }
  const std::size_t width = a.shape[1];
  for (std::size_t k = 0; k < s.snapshots.size(); ++k) {
    const auto row = a.values.begin() + static_cast<std::ptrdiff_t>(k * width);
    (s.snapshots[k].*column).assign(row, row + static_cast<std::ptrdiff_t>(width));
  }
}

}  // namespace

void write_field_series(H5::Group& g, const FieldSeries& s) {
  h5::write_attribute(g, "geometry", to_string(s.geometry));
  std::vector<double> t;
  std::vector<std::string> labels;
  for (const auto& snap : s.snapshots) {
    t.push_back(snap.t);
    labels.push_back(snap.label);
  }
  h5::write_vector(g, "t", t);
  h5::write_strings(g, "label", labels);
  if (s.geometry == Geometry::bins) h5::write_vector(g, "bin_edges", s.bin_edges);
  if (s.snapshots.empty()) return;
  for (const FieldColumn& c : field_columns()) {
    write_column(g, s, c.values, c.name);
    if (c.standard_error) write_column(g, s, c.standard_error, std::string(c.name) + "_stderr");
  }
}

FieldSeries read_field_series(const H5::Group& g) {
  FieldSeries s;
  try {
    s.geometry = geometry_from_string(h5::read_string_attribute(g, "geometry"));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  const h5::DoubleArray t = h5::read_doubles(g, "t");
  const std::vector<std::string> labels = h5::read_strings(g, "label");
  if (labels.size() != t.values.size()) {
    throw std::runtime_error("FieldSeries: " + std::to_string(labels.size()) + " labels for " +
                             std::to_string(t.values.size()) + " times");
  }
  for (std::size_t k = 0; k < labels.size(); ++k) {
    FieldSnapshot snap;
    snap.t = t.values[k];
    snap.label = labels[k];
    s.snapshots.push_back(std::move(snap));
  }
  if (s.geometry == Geometry::bins) s.bin_edges = h5::read_doubles(g, "bin_edges").values;
  for (const FieldColumn& c : field_columns()) {
    read_column(g, s, c.values, c.name);
    if (c.standard_error) read_column(g, s, c.standard_error, std::string(c.name) + "_stderr");
  }
  return s;
}

}  // namespace granvv::fields
