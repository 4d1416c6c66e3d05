#include "fields/hdf5_datasets.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
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

namespace {

// The number of values of a dataset of this shape, refused beyond what its file can hold.
std::uint64_t checked_extent(const H5::DataSet& ds, const std::string& name,
                             const std::vector<hsize_t>& shape) {
  std::uint64_t size = 1;
  bool overflow = false;
  for (const hsize_t d : shape) {
    if (d != 0 && size > kMaxDatasetValues / d) overflow = true;
    size = overflow ? kMaxDatasetValues + 1 : size * d;
  }
  std::error_code ec;
  const std::uint64_t file_bytes = std::filesystem::file_size(ds.getFileName(), ec);
  const std::uint64_t allowed = std::min<std::uint64_t>(
      kMaxDatasetValues,
      ec ? kMaxDatasetValues : std::max<std::uint64_t>(file_bytes, 1024) * kMaxValuesPerFileByte);
  if (size > allowed) {
    std::string extent;
    for (const hsize_t d : shape) extent += (extent.empty() ? "" : " x ") + std::to_string(d);
    throw std::runtime_error("dataset " + name + " declares " + extent + " values, more than " +
                             (ec ? std::string("the limit of ") + std::to_string(allowed)
                                 : "a file of " + std::to_string(file_bytes) + " bytes holds") +
                             " (allowed: at most " + std::to_string(allowed) + " values)");
  }
  return size;
}

}  // namespace

std::string hdf5_open_problem(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return path + " is not a file";
  // The signature is at offset 0, or after a user block at 512, 1024, 2048, ... bytes.
  std::ifstream in(path, std::ios::binary);
  bool signed_file = false;
  for (std::streamoff at = 0; !signed_file && at <= (std::streamoff(1) << 24);
       at = at == 0 ? 512 : 2 * at) {
    char signature[8] = {};
    in.clear();
    in.seekg(at);
    if (!in.read(signature, sizeof signature)) break;
    signed_file = std::memcmp(signature, "\x89HDF\r\n\x1a\n", sizeof signature) == 0;
  }
  if (!signed_file) return path + " is not an HDF5 file (it lacks the HDF5 signature)";
  // HDF5 takes flock(LOCK_EX) on a file it opens for writing (HDF5 file locking).
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return "cannot open " + path + ": " + std::strerror(errno);
  const bool locked = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);
  if (locked) {
    return path +
           " is open for writing in another process (its HDF5 file lock is held): wait "
           "until that process has finished writing it";
  }
  return "";
}

DoubleArray read_doubles(const H5::Group& g, const std::string& name) {
  const H5::DataSet ds = g.openDataSet(name);
  const H5T_class_t type = ds.getTypeClass();
  if (type != H5T_FLOAT && type != H5T_INTEGER) {
    throw std::runtime_error("dataset " + name +
                             " does not hold numbers (allowed: an integer or "
                             "floating-point dataset)");
  }
  const H5::DataSpace space = ds.getSpace();
  const int rank = space.getSimpleExtentNdims();
  if (rank < 1 || rank > 2) {
    throw std::runtime_error("dataset " + name + " has rank " + std::to_string(rank) +
                             ", expected 1 or 2");
  }
  DoubleArray a;
  a.shape.resize(rank);
  space.getSimpleExtentDims(a.shape.data());
  const std::uint64_t size = checked_extent(ds, name, a.shape);
  a.values.resize(size);
  if (size > 0) ds.read(a.values.data(), H5::PredType::NATIVE_DOUBLE);
  return a;
}

std::vector<std::string> read_strings(const H5::Group& g, const std::string& name) {
  const H5::DataSet ds = g.openDataSet(name);
  const H5::DataSpace space = ds.getSpace();
  if (ds.getTypeClass() != H5T_STRING || space.getSimpleExtentNdims() != 1) {
    throw std::runtime_error("dataset " + name + " is not a 1D dataset of strings");
  }
  hsize_t size = 0;
  space.getSimpleExtentDims(&size);
  checked_extent(ds, name, {size});
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
  if (a.getTypeClass() != H5T_STRING || a.getSpace().getSimpleExtentNpoints() != 1)
    throw std::runtime_error("attribute " + name + " is not one string");
  std::string value;
  a.read(a.getStrType(), value);
  return value;
}

double read_double_attribute(const H5::H5Object& o, const std::string& name) {
  double value = 0.0;
  const H5::Attribute a = o.openAttribute(name);
  const H5T_class_t type = a.getTypeClass();
  // One value (the read would write as many as the attribute holds), of a number type.
  if ((type != H5T_FLOAT && type != H5T_INTEGER) || a.getSpace().getSimpleExtentNpoints() != 1)
    throw std::runtime_error("attribute " + name + " is not one number");
  a.read(H5::PredType::NATIVE_DOUBLE, &value);
  return value;
}

}  // namespace granvv::h5
