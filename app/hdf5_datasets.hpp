#pragma once
// Small writers for results.h5: 1D and row-major 2D double datasets, string datasets and
// scalar attributes, shared by the hydro and particle outputs.
#include <H5Cpp.h>

#include <string>
#include <vector>

namespace granvv::app {

void write_vector(H5::Group& g, const std::string& name, const std::vector<double>& v);
// rows x (v.size() / rows), row-major
void write_matrix(H5::Group& g, const std::string& name, const std::vector<double>& v,
                  hsize_t rows);
void write_strings(H5::Group& g, const std::string& name, const std::vector<std::string>& v);
void write_attribute(H5::H5Object& o, const std::string& name, const std::string& value);
void write_attribute(H5::H5Object& o, const std::string& name, double value);

}  // namespace granvv::app
