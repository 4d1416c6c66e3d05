#pragma once
// Small HDF5 readers and writers for results.h5: 1D and row-major 2D double datasets, string
// datasets and scalar attributes, shared by every output group.
#include <H5Cpp.h>

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

// A double dataset of rank 1 or 2, flattened row-major, with its shape.
struct DoubleArray {
  std::vector<hsize_t> shape;
  std::vector<double> values;
};
DoubleArray read_doubles(const H5::Group& g, const std::string& name);
std::vector<std::string> read_strings(const H5::Group& g, const std::string& name);
std::string read_string_attribute(const H5::H5Object& o, const std::string& name);
double read_double_attribute(const H5::H5Object& o, const std::string& name);

}  // namespace granvv::h5
