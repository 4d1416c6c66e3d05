#include "fields/hdf5_datasets.hpp"

#include <stdexcept>

namespace granvv::h5 {

std::recursive_mutex& library_mutex() {
  static std::recursive_mutex mutex;
  return mutex;
}

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

DoubleArray read_doubles(const H5::Group& g, const std::string& name) {
  const H5::DataSet ds = g.openDataSet(name);
  const H5::DataSpace space = ds.getSpace();
  const int rank = space.getSimpleExtentNdims();
  if (rank < 1 || rank > 2) {
    throw std::runtime_error("dataset " + name + " has rank " + std::to_string(rank) +
                             ", expected 1 or 2");
  }
  DoubleArray a;
  a.shape.resize(rank);
  space.getSimpleExtentDims(a.shape.data());
  hsize_t size = 1;
  for (hsize_t d : a.shape) size *= d;
  a.values.resize(size);
  if (size > 0) ds.read(a.values.data(), H5::PredType::NATIVE_DOUBLE);
  return a;
}

std::vector<std::string> read_strings(const H5::Group& g, const std::string& name) {
  const H5::DataSet ds = g.openDataSet(name);
  hsize_t size = 0;
  ds.getSpace().getSimpleExtentDims(&size);
  H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
  std::vector<char*> ptrs(size, nullptr);
  if (size > 0) ds.read(ptrs.data(), type);
  std::vector<std::string> out;
  for (char* p : ptrs) out.emplace_back(p ? p : "");
  if (size > 0) H5Dvlen_reclaim(type.getId(), ds.getSpace().getId(), H5P_DEFAULT, ptrs.data());
  return out;
}

std::string read_string_attribute(const H5::H5Object& o, const std::string& name) {
  const H5::Attribute a = o.openAttribute(name);
  std::string value;
  a.read(a.getStrType(), value);
  return value;
}

double read_double_attribute(const H5::H5Object& o, const std::string& name) {
  double value = 0.0;
  o.openAttribute(name).read(H5::PredType::NATIVE_DOUBLE, &value);
  return value;
}

}  // namespace granvv::h5
