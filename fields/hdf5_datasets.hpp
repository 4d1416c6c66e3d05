#pragma once
// Small HDF5 readers and writers for results.h5: 1D and row-major 2D double datasets, string
// datasets and scalar attributes, shared by every output group.
#include <H5Cpp.h>

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace granvv::h5 {

// Debian's HDF5 is built without thread safety: code that may run beside other threads of the
// process (ensemble members in threads, scene/md_members.hpp) holds this around every HDF5 call.
std::recursive_mutex& library_mutex();

void write_vector(H5::Group& g, const std::string& name, const std::vector<double>& v);
// rows x (v.size() / rows), row-major
void write_matrix(H5::Group& g, const std::string& name, const std::vector<double>& v,
                  hsize_t rows);
void write_strings(H5::Group& g, const std::string& name, const std::vector<std::string>& v);
void write_attribute(H5::H5Object& o, const std::string& name, const std::string& value);
void write_attribute(H5::H5Object& o, const std::string& name, double value);

// A dataset holds at most this many values per byte of its file: a file's datasets compress
// by less than this (deflate's limit is about 1032:1), so a dataset that declares more values,
// a chunked or sparse one whose extent far exceeds what the file holds, is refused before any
// memory is taken for it.
inline constexpr std::uint64_t kMaxValuesPerFileByte = 1024;
// ... and never more than this many values (8 GB of doubles), whatever the file's size.
inline constexpr std::uint64_t kMaxDatasetValues = std::uint64_t(1) << 30;

// Why `path` cannot be opened as an HDF5 file, one line: it does not exist, is not HDF5 (no
// signature), or another process holds it open for writing (its HDF5 file lock is taken);
// empty if none of these explains it.
std::string hdf5_open_problem(const std::string& path);

// A numeric (integer or floating-point) dataset of rank 1 or 2, read as doubles, flattened
// row-major, with its shape. Throws std::runtime_error (one line, naming the dataset) for
// another type or rank, or for an extent beyond the limits above.
struct DoubleArray {
  std::vector<hsize_t> shape;
  std::vector<double> values;
};
DoubleArray read_doubles(const H5::Group& g, const std::string& name);
// A 1D string dataset (the same extent limits).
std::vector<std::string> read_strings(const H5::Group& g, const std::string& name);
std::string read_string_attribute(const H5::H5Object& o, const std::string& name);
double read_double_attribute(const H5::H5Object& o, const std::string& name);

}  // namespace granvv::h5
