#include "app/hdf5_datasets.hpp"

namespace granvv::app {

void write_vector(H5::Group& g, const std::string& name, const std::vector<double>& v) {
  const hsize_t dims[1] = {v.size()};
  auto ds = g.createDataSet(name, H5::PredType::NATIVE_DOUBLE, H5::DataSpace(1, dims));
  if (!v.empty()) ds.write(v.data(), H5::PredType::NATIVE_DOUBLE);
}

void write_matrix(H5::Group& g, const std::string& name, const std::vector<double>& v,
                  hsize_t rows) {
  const hsize_t dims[2] = {rows, rows ? v.size() / rows : 0};
  auto ds = g.createDataSet(name, H5::PredType::NATIVE_DOUBLE, H5::DataSpace(2, dims));
  if (!v.empty()) ds.write(v.data(), H5::PredType::NATIVE_DOUBLE);
}

void write_strings(H5::Group& g, const std::string& name, const std::vector<std::string>& v) {
  H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
  const hsize_t dims[1] = {v.size()};
  std::vector<const char*> ptrs;
  for (const auto& s : v) ptrs.push_back(s.c_str());
  g.createDataSet(name, type, H5::DataSpace(1, dims)).write(ptrs.data(), type);
}

void write_attribute(H5::H5Object& o, const std::string& name, const std::string& value) {
  H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
  const char* p = value.c_str();
  o.createAttribute(name, type, H5::DataSpace(H5S_SCALAR)).write(type, &p);
}

void write_attribute(H5::H5Object& o, const std::string& name, double value) {
  o.createAttribute(name, H5::PredType::NATIVE_DOUBLE, H5::DataSpace(H5S_SCALAR))
      .write(H5::PredType::NATIVE_DOUBLE, &value);
}

}  // namespace granvv::app
