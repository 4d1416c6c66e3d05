#include "md_bridge/h5md_writer.hpp"

#include <H5Cpp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <stdexcept>
#include <utility>

#include "fields/hdf5_datasets.hpp"
#include "md_bridge/particle_scene.hpp"

namespace granvv::md {
namespace {

constexpr hsize_t kSeriesChunk = 1024;            // frames per chunk of a 1D series
constexpr hsize_t kMaxParticlesPerChunk = 65536;  // 1 MiB chunks of [1][n][2] doubles

// Fixed-length, null-terminated ASCII string type holding strings up to `length` characters.
H5::StrType fixed_string_type(size_t length) {
  H5::StrType type(H5::PredType::C_S1, length + 1);
  type.setStrpad(H5T_STR_NULLTERM);
  type.setCset(H5T_CSET_ASCII);
  return type;
}

void string_attribute(H5::H5Object& object, const std::string& name, const std::string& value) {
  const auto type = fixed_string_type(value.size());
  object.createAttribute(name, type, H5::DataSpace(H5S_SCALAR)).write(type, value.c_str());
}

void string_array_attribute(H5::H5Object& object, const std::string& name,
                            const std::vector<std::string>& values) {
  size_t length = 0;
  for (const auto& v : values) length = std::max(length, v.size());
  std::vector<char> buffer(values.size() * (length + 1), '\0');
  for (size_t i = 0; i < values.size(); ++i) values[i].copy(&buffer[i * (length + 1)], length);
  const auto type = fixed_string_type(length);
  const hsize_t dims[1] = {values.size()};
  object.createAttribute(name, type, H5::DataSpace(1, dims)).write(type, buffer.data());
}

// One time-dependent H5MD element: step, time and value, extended together frame by frame.
struct Series {
  H5::DataSet step, time, value;
  std::vector<hsize_t> frame_shape;  // shape of one sample: {} for scalars, {N, 2} for vectors
  hsize_t frames = 0;
  bool owns_step_time = true;  // false where step and time are hard links to another element

  long long last_step = 0;
  double last_time = 0.0;
};

H5::DataSet extendible_dataset(H5::Group& group, const std::string& name,
                               const H5::DataType& file_type,
                               const std::vector<hsize_t>& frame_shape,
                               const std::vector<hsize_t>& chunk_frame_shape,
                               hsize_t chunk_frames) {
  std::vector<hsize_t> dims{0}, max_dims{H5S_UNLIMITED}, chunk{chunk_frames};
  for (size_t d = 0; d < frame_shape.size(); ++d) {
    dims.push_back(frame_shape[d]);
    max_dims.push_back(frame_shape[d]);
    chunk.push_back(chunk_frame_shape[d]);
  }
  H5::DSetCreatPropList props;
  props.setChunk(static_cast<int>(chunk.size()), chunk.data());
  const H5::DataSpace space(static_cast<int>(dims.size()), dims.data(), max_dims.data());
  return group.createDataSet(name, file_type, space, props);
}

// Creates <parent>/<name>/{step,time,value}. With `shared` given, step and time are hard links
// to those of `shared` (H5MD: elements sampled at equal times may share them).
// With `virtual_value` given, value is made by it (a joined file's virtual dataset).
Series create_series(H5::Group& parent, const std::string& name,
                     const std::vector<hsize_t>& frame_shape,
                     const std::vector<hsize_t>& chunk_frame_shape, hsize_t chunk_frames,
                     const Series* shared = nullptr,
                     const std::function<H5::DataSet(H5::Group&)>& virtual_value = {}) {
  Series s;
  s.frame_shape = frame_shape;
  H5::Group group = parent.createGroup(name);
  if (shared) {
    const hid_t g = group.getId();
    if (H5Lcreate_hard(shared->step.getId(), ".", g, "step", H5P_DEFAULT, H5P_DEFAULT) < 0 ||
        H5Lcreate_hard(shared->time.getId(), ".", g, "time", H5P_DEFAULT, H5P_DEFAULT) < 0)
      throw std::runtime_error("cannot link step and time of " + name);
    s.step = shared->step;
    s.time = shared->time;
    s.owns_step_time = false;
  } else {
    s.step = extendible_dataset(group, "step", H5::PredType::STD_I64LE, {}, {}, kSeriesChunk);
    s.time = extendible_dataset(group, "time", H5::PredType::IEEE_F64LE, {}, {}, kSeriesChunk);
  }
  s.value = virtual_value ? virtual_value(group)
                          : extendible_dataset(group, "value", H5::PredType::IEEE_F64LE,
                                               frame_shape, chunk_frame_shape, chunk_frames);
  return s;
}

// hsize_t arrays as the C API takes them.
hid_t selected(hid_t space, const std::vector<hsize_t>& start, const std::vector<hsize_t>& count,
               const std::vector<hsize_t>& block) {
  const std::vector<hsize_t> stride(start.size(), 1);
  if (H5Sselect_hyperslab(space, H5S_SELECT_SET, start.data(), stride.data(), count.data(),
                          block.data()) < 0)
    throw std::runtime_error("cannot select the rows of a block");
  return space;
}

// A virtual dataset `name` in `group` of the rows of every block: the dataset `source` of each
// block file, of shape [rows] (framed false) or [frames][rows][2] (framed true, along an
// unlimited frame axis), placed at rows [first, first + count) of [N] or [frames][N][2].
H5::DataSet virtual_rows(H5::Group& group, const std::string& name, const H5::DataType& type,
                         bool framed, hsize_t n, const std::vector<H5mdBlock>& blocks,
                         const std::string& source) {
  H5::DSetCreatPropList props;
  if (framed) {
    const double nan = std::nan("");
    props.setFillValue(H5::PredType::NATIVE_DOUBLE, &nan);
  }
  const std::vector<hsize_t> dims =
      framed ? std::vector<hsize_t>{0, n, 2} : std::vector<hsize_t>{n};
  std::vector<hsize_t> max_dims = dims;
  if (framed) max_dims[0] = H5S_UNLIMITED;
  for (const auto& b : blocks) {
    const hsize_t first = hsize_t(b.first), count = hsize_t(b.count);
    std::vector<hsize_t> source_dims{count}, source_max{count};
    if (framed) source_dims = {0, count, 2}, source_max = {H5S_UNLIMITED, count, 2};
    const H5::DataSpace whole(int(dims.size()), dims.data(), max_dims.data());
    const H5::DataSpace part(int(source_dims.size()), source_dims.data(), source_max.data());
    const hid_t v =
        framed ? selected(whole.getId(), {0, first, 0}, {H5S_UNLIMITED, 1, 1}, {1, count, 2})
               : selected(whole.getId(), {first}, {1}, {count});
    const hid_t src = framed
                          ? selected(part.getId(), {0, 0, 0}, {H5S_UNLIMITED, 1, 1}, {1, count, 2})
                          : selected(part.getId(), {0}, {1}, {count});
    if (H5Pset_virtual(props.getId(), v, b.file.c_str(), source.c_str(), src) < 0)
      throw std::runtime_error("cannot map " + b.file + " into " + name);
  }
  const H5::DataSpace space(int(dims.size()), dims.data(), max_dims.data());
  return group.createDataSet(name, type, space, props);
}

// Writes one sample at row `row` of an extendible dataset, growing it to row + 1 rows.
void write_row(H5::DataSet& dataset, hsize_t row, const std::vector<hsize_t>& frame_shape,
               const H5::PredType& memory_type, const void* data) {
  std::vector<hsize_t> dims{row + 1}, start{row}, count{1};
  for (const auto d : frame_shape) dims.push_back(d), start.push_back(0), count.push_back(d);
  dataset.extend(dims.data());
  H5::DataSpace file_space = dataset.getSpace();
  file_space.selectHyperslab(H5S_SELECT_SET, count.data(), start.data());
  const H5::DataSpace memory_space(static_cast<int>(count.size()), count.data());
  dataset.write(data, memory_type, memory_space, file_space);
}

void check_order(const Series& s, const std::string& what, long long step, double time) {
  if (!std::isfinite(time))
    throw std::invalid_argument(what + ": time " + std::to_string(time) + " is not finite");
  if (s.frames > 0 && step <= s.last_step)
    throw std::invalid_argument(what + ": step " + std::to_string(step) +
                                " does not follow the last step " + std::to_string(s.last_step) +
                                " (steps must increase)");
  if (s.frames > 0 && time < s.last_time)
    throw std::invalid_argument(what + ": time " + std::to_string(time) +
                                " precedes the last time " + std::to_string(s.last_time));
}

// Appends value (and, where the element owns them, step and time) at the next row. The value
// goes first and step last, so that a reader never sees a step without its data.
// Without a value (a joined file, whose values are the block files'), step and time only.
void append(Series& s, long long step, double time, const double* value) {
  if (value) write_row(s.value, s.frames, s.frame_shape, H5::PredType::NATIVE_DOUBLE, value);
  if (s.owns_step_time) {
    const std::int64_t step64 = step;
    write_row(s.time, s.frames, {}, H5::PredType::NATIVE_DOUBLE, &time);
    write_row(s.step, s.frames, {}, H5::PredType::NATIVE_INT64, &step64);
  }
  ++s.frames;
  s.last_step = step;
  s.last_time = time;
}

std::string default_author() {
  for (const char* variable : {"USER", "LOGNAME"}) {
    const char* value = std::getenv(variable);
    if (value && *value) return value;
  }
  return "unknown";
}

bool valid_element_name(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos;
}

}  // namespace

struct H5mdWriter::Layout {
  enum class Kind { whole, block, joined } kind = Kind::whole;
  long long n = 0;                // particles in a frame of the run
  H5mdBlock rows;                 // the rows this file holds (whole and joined: all N)
  std::vector<H5mdBlock> blocks;  // joined: the block files

  static Layout whole(long long n) { return {Kind::whole, n, H5mdBlock{std::string(), 0, n}, {}}; }
  static Layout block(long long n, const H5mdBlock& rows) { return {Kind::block, n, rows, {}}; }
  static Layout joined(long long n, const std::vector<H5mdBlock>& blocks) {
    return {Kind::joined, n, H5mdBlock{std::string(), 0, n}, blocks};
  }
};

struct H5mdWriter::Impl {
  std::string path;
  Layout layout;
  long long n = 0;  // rows of a frame in this file
  double lx = 0.0, ly = 0.0;
  H5::H5File file;
  H5::Group observables;
  Series position, velocity;
  std::map<std::string, Series> observable;
  std::vector<double> buffer;  // one frame of [N][2] values
  bool open = false;

  [[noreturn]] void fail(const std::string& what, const H5::Exception& e) const {
    throw std::runtime_error("H5MD file " + path + ": " + what + ": " + e.getDetailMsg());
  }
  void require_open(const char* what) const {
    if (!open) throw std::logic_error("H5MD file " + path + ": " + what + " after close()");
  }
};

const std::vector<std::string>& H5mdWriter::standard_observables() {
  static const std::vector<std::string> names{"thermal_energy", "kinetic_energy_x",
                                              "kinetic_energy_y", "total_energy"};
  return names;
}

namespace {

// The layout's problem, or "".
std::string layout_problem(long long n, const H5mdBlock& rows, const std::vector<H5mdBlock>& blocks,
                           bool joined) {
  if (n < 1) return "n_particles = " + std::to_string(n) + ", must be >= 1";
  if (rows.count < 1 || rows.first < 0 || rows.first + rows.count > n)
    return "rows " + std::to_string(rows.first) + " + " + std::to_string(rows.count) +
           " do not lie within the " + std::to_string(n) + " particles";
  if (!joined) return "";
  long long next = 0;
  for (const auto& b : blocks) {
    if (b.first != next || b.count < 1 || b.file.empty())
      return "the block files do not cover the particles once, in order";
    next += b.count;
  }
  return next == n ? "" : "the block files do not cover the particles once, in order";
}

}  // namespace

H5mdWriter::H5mdWriter(const std::string& path, long long n_particles, double box_length,
                       double box_width, const std::string& creator_version,
                       const std::string& author)
    : H5mdWriter(path, Layout::whole(n_particles), box_length, box_width, creator_version, author) {
}

H5mdWriter H5mdWriter::block_file(const std::string& path, long long n_particles,
                                  const H5mdBlock& block, double box_length, double box_width,
                                  const std::string& creator_version) {
  return H5mdWriter(path, Layout::block(n_particles, block), box_length, box_width, creator_version,
                    "");
}

H5mdWriter H5mdWriter::joined_file(const std::string& path, long long n_particles,
                                   const std::vector<H5mdBlock>& blocks, double box_length,
                                   double box_width, const std::string& creator_version) {
  return H5mdWriter(path, Layout::joined(n_particles, blocks), box_length, box_width,
                    creator_version, "");
}

H5mdWriter::H5mdWriter(const std::string& path, const Layout& layout, double box_length,
                       double box_width, const std::string& creator_version,
                       const std::string& author)
    : impl_(std::make_unique<Impl>()) {
  auto& m = *impl_;
  m.path = path;
  m.layout = layout;
  using Kind = Layout::Kind;
  const std::string problem =
      layout_problem(layout.n, layout.rows, layout.blocks, layout.kind == Kind::joined);
  if (!problem.empty()) throw std::invalid_argument("H5MD file " + path + ": " + problem);
  const long long n_particles = layout.rows.count;
  if (!(std::isfinite(box_length) && box_length > 0 && std::isfinite(box_width) && box_width > 0))
    throw std::invalid_argument("H5MD file " + path + ": box " + std::to_string(box_length) +
                                " x " + std::to_string(box_width) +
                                ", both edges must be finite and > 0");
  m.n = n_particles;
  m.lx = box_length;
  m.ly = box_width;
  if (layout.kind != Kind::joined) m.buffer.resize(static_cast<size_t>(2 * n_particles));

  H5::Exception::dontPrint();
  try {
    H5::FileAccPropList access;
    // HDF5 1.8 format (superblock 2), as H5MD recommends; it carries no consistency flags, so
    // a file left by a killed process opens without h5clear.
    // A joined file's virtual datasets need the 1.10 layout message; its superblock stays 2.
    access.setLibverBounds(H5F_LIBVER_V18,
                           layout.kind == Kind::joined ? H5F_LIBVER_V110 : H5F_LIBVER_V18);
    // No file lock, so that other processes can read the file during the run.
    if (H5Pset_file_locking(access.getId(), false, true) < 0)
      throw std::runtime_error("H5MD file " + path + ": cannot disable file locking");
    m.file = H5::H5File(path, H5F_ACC_TRUNC, H5::FileCreatPropList::DEFAULT, access);
    m.open = true;

    H5::Group h5md = m.file.createGroup("h5md");
    const int version[2] = {1, 1};
    const hsize_t two[1] = {2};
    h5md.createAttribute("version", H5::PredType::STD_I32LE, H5::DataSpace(1, two))
        .write(H5::PredType::NATIVE_INT, version);
    H5::Group author_group = h5md.createGroup("author");
    string_attribute(author_group, "name", author.empty() ? default_author() : author);
    H5::Group creator = h5md.createGroup("creator");
    string_attribute(creator, "name", "granvv");
    string_attribute(creator, "version", creator_version);

    H5::Group all = m.file.createGroup("particles").createGroup("all");
    H5::Group box = all.createGroup("box");
    const int dimension = 2;
    box.createAttribute("dimension", H5::PredType::STD_I32LE, H5::DataSpace(H5S_SCALAR))
        .write(H5::PredType::NATIVE_INT, &dimension);
    string_array_attribute(box, "boundary", {"periodic", "periodic"});
    const double edges[2] = {box_length, box_width};
    box.createDataSet("edges", H5::PredType::IEEE_F64LE, H5::DataSpace(1, two))
        .write(edges, H5::PredType::NATIVE_DOUBLE);

    const hsize_t n = static_cast<hsize_t>(n_particles);
    const std::vector<hsize_t> frame{n, 2}, chunk{std::min(n, kMaxParticlesPerChunk), 2};
    if (layout.kind == Kind::joined) {
      virtual_rows(all, "id", H5::PredType::STD_I64LE, false, n, layout.blocks,
                   "/particles/all/id");
      auto values_of = [&](const std::string& element) {
        return [&, element](H5::Group& g) {
          return virtual_rows(g, "value", H5::PredType::IEEE_F64LE, true, n, layout.blocks,
                              "/particles/all/" + element + "/value");
        };
      };
      m.position = create_series(all, "position", frame, chunk, 1, nullptr, values_of("position"));
      m.velocity =
          create_series(all, "velocity", frame, chunk, 1, &m.position, values_of("velocity"));
    } else {
      std::vector<std::int64_t> ids(n);
      for (hsize_t i = 0; i < n; ++i)
        ids[i] = static_cast<std::int64_t>(hsize_t(layout.rows.first) + i + 1);
      const hsize_t id_dims[1] = {n};
      all.createDataSet("id", H5::PredType::STD_I64LE, H5::DataSpace(1, id_dims))
          .write(ids.data(), H5::PredType::NATIVE_INT64);
      m.position = create_series(all, "position", frame, chunk, 1);
      m.velocity = create_series(all, "velocity", frame, chunk, 1, &m.position);
    }

    if (layout.kind != Kind::block) {
      m.observables = m.file.createGroup("observables");
      for (const auto& name : standard_observables())
        m.observable.emplace(name, create_series(m.observables, name, {}, {}, kSeriesChunk));
    }
    m.file.flush(H5F_SCOPE_LOCAL);
  } catch (const H5::Exception& e) {
    m.fail("cannot create", e);
  }
}

namespace {

// Rows of an element's step dataset, as written (int64).
std::vector<std::int64_t> read_steps(const H5::Group& element) {
  const H5::DataSet ds = element.openDataSet("step");
  hsize_t rows = 0;
  ds.getSpace().getSimpleExtentDims(&rows);
  std::vector<std::int64_t> steps(rows);
  if (rows > 0) ds.read(steps.data(), H5::PredType::NATIVE_INT64);
  return steps;
}

// Row `row` of a [frames][N][2] value dataset, as xyz triplets with z = 0.
std::vector<double> read_frame(const H5::DataSet& value, hsize_t row, hsize_t n) {
  std::vector<double> xy(2 * n), xyz(3 * n, 0.0);
  const hsize_t start[3] = {row, 0, 0}, count[3] = {1, n, 2};
  H5::DataSpace file_space = value.getSpace();
  file_space.selectHyperslab(H5S_SELECT_SET, count, start);
  const H5::DataSpace memory_space(3, count);
  value.read(xy.data(), H5::PredType::NATIVE_DOUBLE, memory_space, file_space);
  for (hsize_t i = 0; i < n; ++i) xyz[3 * i] = xy[2 * i], xyz[3 * i + 1] = xy[2 * i + 1];
  return xyz;
}

}  // namespace

H5mdWriter H5mdWriter::continue_file(const std::string& path, long long last_step,
                                     long long n_particles, double box_length, double box_width,
                                     const std::string& creator_version) {
  return continue_layout(path, last_step, Layout::whole(n_particles), box_length, box_width,
                         creator_version);
}

H5mdWriter H5mdWriter::continue_block_file(const std::string& path, long long last_step,
                                           long long n_particles, const H5mdBlock& block,
                                           double box_length, double box_width,
                                           const std::string& creator_version) {
  return continue_layout(path, last_step, Layout::block(n_particles, block), box_length, box_width,
                         creator_version);
}

H5mdWriter H5mdWriter::continue_joined_file(const std::string& path, long long last_step,
                                            long long n_particles,
                                            const std::vector<H5mdBlock>& blocks, double box_length,
                                            double box_width, const std::string& creator_version) {
  return continue_layout(path, last_step, Layout::joined(n_particles, blocks), box_length,
                         box_width, creator_version);
}

namespace {

H5::FileAccPropList unlocked_access() {
  H5::FileAccPropList access;
  if (H5Pset_file_locking(access.getId(), false, true) < 0)
    throw std::runtime_error("cannot disable file locking");
  return access;
}

}  // namespace

H5mdWriter H5mdWriter::continue_layout(const std::string& path, long long last_step,
                                       const Layout& layout, double box_length, double box_width,
                                       const std::string& creator_version) {
  const std::string before = path + ".before-resume";
  if (std::rename(path.c_str(), before.c_str()) != 0)
    throw std::runtime_error("H5MD file " + path + ": cannot continue it (missing or not movable)");
  H5::Exception::dontPrint();
  try {
    const H5::H5File old(before, H5F_ACC_RDONLY, H5::FileCreatPropList::DEFAULT, unlocked_access());
    H5mdWriter writer(path, layout, box_length, box_width, creator_version, "");
    const hsize_t rows = hsize_t(layout.rows.count);
    const H5::Group position = old.openGroup("particles/all/position");
    const std::vector<std::int64_t> steps = read_steps(position);
    const std::vector<double> times = h5::read_doubles(position, "time").values;
    if (layout.kind == Layout::Kind::joined) {  // the values are the block files'
      for (std::size_t row = 0; row < steps.size() && steps[row] <= last_step; ++row)
        writer.append_joined_frame(steps[row], times[row]);
    } else {
      const H5::Group velocity = old.openGroup("particles/all/velocity");
      const H5::DataSet x = position.openDataSet("value"), v = velocity.openDataSet("value");
      for (std::size_t row = 0; row < steps.size() && steps[row] <= last_step; ++row) {
        writer.append_particles(steps[row], times[row], read_frame(x, row, rows),
                                read_frame(v, row, rows));
      }
    }
    if (layout.kind != Layout::Kind::block) {
      const H5::Group observables = old.openGroup("observables");
      for (hsize_t k = 0; k < observables.getNumObjs(); ++k) {
        const std::string name = observables.getObjnameByIdx(k);
        const H5::Group element = observables.openGroup(name);
        const std::vector<std::int64_t> obs_steps = read_steps(element);
        const std::vector<double> obs_times = h5::read_doubles(element, "time").values;
        const std::vector<double> values = h5::read_doubles(element, "value").values;
        for (std::size_t row = 0; row < obs_steps.size() && obs_steps[row] <= last_step; ++row) {
          writer.append_observable(name, obs_steps[row], obs_times[row], values[row]);
        }
      }
    }
    std::remove(before.c_str());
    return writer;
  } catch (const H5::Exception& e) {
    std::rename(before.c_str(), path.c_str());
    throw std::runtime_error("H5MD file " + path + ": cannot continue it: " + e.getDetailMsg());
  } catch (const std::exception& e) {
    std::rename(before.c_str(), path.c_str());
    throw std::runtime_error("H5MD file " + path + ": cannot continue it: " + e.what());
  }
}

std::vector<std::string> H5mdWriter::joined_block_files(const std::string& path) {
  H5::Exception::dontPrint();
  try {
    const H5::H5File file(path, H5F_ACC_RDONLY, H5::FileCreatPropList::DEFAULT, unlocked_access());
    const H5::DataSet value = file.openDataSet("particles/all/position/value");
    const H5::DSetCreatPropList props = value.getCreatePlist();
    std::vector<std::string> files;
    if (H5Pget_layout(props.getId()) != H5D_VIRTUAL) return files;
    size_t count = 0;
    if (H5Pget_virtual_count(props.getId(), &count) < 0)
      throw std::runtime_error("cannot read its virtual mappings");
    for (size_t k = 0; k < count; ++k) {
      const ssize_t length = H5Pget_virtual_filename(props.getId(), k, nullptr, 0);
      if (length < 0) throw std::runtime_error("cannot read its virtual mappings");
      std::string name(std::size_t(length) + 1, '\0');
      H5Pget_virtual_filename(props.getId(), k, name.data(), name.size());
      name.resize(std::size_t(length));
      files.push_back(name);
    }
    return files;
  } catch (const H5::Exception& e) {
    throw std::runtime_error("H5MD file " + path + ": cannot read it: " + e.getDetailMsg());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("H5MD file " + path + ": " + e.what());
  }
}

H5mdWriter::~H5mdWriter() {
  try {
    close();
  } catch (...) {  // a destructor must not throw; close() has flushed all it could
  }
}

H5mdWriter::H5mdWriter(H5mdWriter&&) noexcept = default;
H5mdWriter& H5mdWriter::operator=(H5mdWriter&& other) noexcept {
  if (this != &other) {
    try {
      close();
    } catch (...) {  // as in the destructor
    }
    impl_ = std::move(other.impl_);
  }
  return *this;
}

H5mdWriter::Impl& H5mdWriter::impl() const {
  if (!impl_) throw std::logic_error("H5mdWriter used after being moved from");
  return *impl_;
}

void H5mdWriter::append_particles(long long step, double time, const std::vector<double>& x_xyz,
                                  const std::vector<double>& v_xyz) {
  auto& m = impl();
  m.require_open("append_particles");
  const std::string what = "H5MD file " + m.path + ": particles";
  if (m.layout.kind == Layout::Kind::joined)
    throw std::logic_error(what +
                           ": a joined file's rows are its block files' (append_joined_frame)");
  const size_t values = static_cast<size_t>(3 * m.n);
  if (x_xyz.size() != values || v_xyz.size() != values)
    throw std::invalid_argument(what + ": got " + std::to_string(x_xyz.size()) + " positions and " +
                                std::to_string(v_xyz.size()) +
                                " velocities, need 3 N = " + std::to_string(values) + " each");
  check_order(m.position, what, step, time);
  try {
    // Velocity first: its step and time are the position's, which append() writes last.
    for (long long i = 0; i < m.n; ++i) {
      m.buffer[2 * i] = v_xyz[3 * i];
      m.buffer[2 * i + 1] = v_xyz[3 * i + 1];
    }
    append(m.velocity, step, time, m.buffer.data());
    for (long long i = 0; i < m.n; ++i) {
      m.buffer[2 * i] = wrap(x_xyz[3 * i], m.lx);
      m.buffer[2 * i + 1] = wrap(x_xyz[3 * i + 1], m.ly);
    }
    append(m.position, step, time, m.buffer.data());
    m.file.flush(H5F_SCOPE_LOCAL);
  } catch (const H5::Exception& e) {
    m.fail("cannot append particle frame at step " + std::to_string(step), e);
  }
}

void H5mdWriter::append_joined_frame(long long step, double time) {
  auto& m = impl();
  m.require_open("append_joined_frame");
  const std::string what = "H5MD file " + m.path + ": particles";
  if (m.layout.kind != Layout::Kind::joined)
    throw std::logic_error(what + ": append_joined_frame is for a joined file");
  check_order(m.position, what, step, time);
  try {
    append(m.position, step, time, nullptr);
    m.velocity.frames = m.position.frames;
    m.file.flush(H5F_SCOPE_LOCAL);
  } catch (const H5::Exception& e) {
    m.fail("cannot append particle frame at step " + std::to_string(step), e);
  }
}

void H5mdWriter::append_observable(const std::string& name, long long step, double time,
                                   double value) {
  auto& m = impl();
  m.require_open("append_observable");
  const std::string what = "H5MD file " + m.path + ": observable '" + name + "'";
  if (!valid_element_name(name))
    throw std::invalid_argument(what + ": not a valid name (non-empty, no '/', not . or ..)");
  try {
    if (m.layout.kind == Layout::Kind::block)
      throw std::logic_error(what + ": a block file holds no observables");
    auto it = m.observable.find(name);
    if (it == m.observable.end()) {
      it = m.observable.emplace(name, create_series(m.observables, name, {}, {}, kSeriesChunk))
               .first;
    }
    check_order(it->second, what, step, time);
    append(it->second, step, time, &value);
    m.file.flush(H5F_SCOPE_LOCAL);
  } catch (const H5::Exception& e) {
    m.fail("cannot append observable '" + name + "' at step " + std::to_string(step), e);
  }
}

void H5mdWriter::flush() {
  auto& m = impl();
  m.require_open("flush");
  try {
    m.file.flush(H5F_SCOPE_LOCAL);
  } catch (const H5::Exception& e) {
    m.fail("cannot flush", e);
  }
}

void H5mdWriter::close() {
  if (!impl_ || !impl_->open) return;
  auto& m = *impl_;
  m.open = false;
  try {
    m.file.flush(H5F_SCOPE_LOCAL);
    m.observable.clear();
    m.position = Series{};
    m.velocity = Series{};
    m.observables.close();
    m.file.close();
  } catch (const H5::Exception& e) {
    m.fail("cannot close", e);
  }
}

const std::string& H5mdWriter::path() const {
  return impl().path;
}
long long H5mdWriter::n_particles() const {
  return impl().n;
}
long long H5mdWriter::particle_frames() const {
  return static_cast<long long>(impl().position.frames);
}
long long H5mdWriter::observable_frames(const std::string& name) const {
  const auto& m = impl();
  const auto it = m.observable.find(name);
  return it == m.observable.end() ? 0 : static_cast<long long>(it->second.frames);
}

double H5mdWriter::wrap(double x, double length) {
  return periodic_image(x, length);
}

}  // namespace granvv::md
