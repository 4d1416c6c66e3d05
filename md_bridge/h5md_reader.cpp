#include "md_bridge/h5md_reader.hpp"

#include <H5Cpp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

#include "md_bridge/particle_scene.hpp"

namespace granvv::md {
namespace {

class H5mdParser {
 public:
  H5mdParser(const std::string& path, bool particles) : path_(path), particles_(particles) {}

  RecordedTrajectory read() {
    H5::Exception::dontPrint();
    try {
      return read_file();
    } catch (const H5::Exception& e) {
      fail("not a readable H5MD file (" + e.getFuncName() + ": " + e.getDetailMsg() + ")");
    }
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw RecordedFileError(path_, problem);
  }

  // A dataset's dimensions.
  static std::vector<hsize_t> dims_of(const H5::DataSet& d) {
    const H5::DataSpace space = d.getSpace();
    std::vector<hsize_t> dims(std::size_t(space.getSimpleExtentNdims()));
    space.getSimpleExtentDims(dims.data());
    return dims;
  }

  template <typename T>
  static std::vector<T> read_all(const H5::DataSet& d, const H5::PredType& type) {
    const std::vector<hsize_t> dims = dims_of(d);
    const hsize_t count =
        std::accumulate(dims.begin(), dims.end(), hsize_t(1), std::multiplies<hsize_t>());
    std::vector<T> out(count);
    if (count > 0) d.read(out.data(), type);
    return out;
  }

  std::string group_name(const H5::Group& particles) const {
    std::vector<std::string> names;
    for (hsize_t i = 0; i < particles.getNumObjs(); ++i) {
      names.push_back(particles.getObjnameByIdx(i));
    }
    if (names.size() == 1) return names.front();
    if (std::find(names.begin(), names.end(), "all") != names.end()) return "all";
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    fail("/particles holds " + std::to_string(names.size()) + " groups (" +
         (list.empty() ? "none" : list) + "); granvv reads one, or the one named all");
  }

  // The box: its edges, fixed or unchanging in time, and its lower corner.
  void read_box(const H5::Group& g) {
    if (!g.nameExists("box")) fail(where_ + " has no box");
    const H5::Group box = g.openGroup("box");
    if (box.attrExists("dimension")) {
      int dimension = 0;
      box.openAttribute("dimension").read(H5::PredType::NATIVE_INT, &dimension);
      dimension_ = dimension;
    }
    if (!box.nameExists("edges")) fail(where_ + "/box has no edges");
    std::vector<double> edges;
    std::size_t dim = 0;
    if (box.childObjType("edges") == H5O_TYPE_DATASET) {
      edges = read_all<double>(box.openDataSet("edges"), H5::PredType::NATIVE_DOUBLE);
      dim = edges.size();
    } else {
      const H5::DataSet value = box.openGroup("edges").openDataSet("value");
      const auto dims = dims_of(value);
      if (dims.size() != 2 || dims[0] < 1) fail(where_ + "/box/edges/value is not [frames][dim]");
      edges = read_all<double>(value, H5::PredType::NATIVE_DOUBLE);
      dim = std::size_t(dims[1]);
      for (std::size_t f = 1; f < std::size_t(dims[0]); ++f) {
        if (!std::equal(edges.begin(), edges.begin() + std::ptrdiff_t(dim),
                        edges.begin() + std::ptrdiff_t(f * dim))) {
          fail("the box changes at frame " + std::to_string(f) + " (granvv needs a fixed box)");
        }
      }
      edges.resize(dim);
    }
    if (dim != 2 && dim != 3)
      fail(where_ + "/box/edges has " + std::to_string(dim) +
           " entries (a cubic box per axis of 2 or 3 dimensions)");
    if (dimension_ != 0 && std::size_t(dimension_) != dim) {
      fail(where_ + "/box dimension " + std::to_string(dimension_) + " but " + std::to_string(dim) +
           " edges");
    }
    dimension_ = int(dim);
    check_finite(path_, edges, where_ + "/box/edges");
    if (!(edges[0] > 0.0 && edges[1] > 0.0)) fail(where_ + "/box/edges are not positive");
    lengths_ = {edges[0], edges[1]};
    centre_ = {0.0, 0.0};
    if (box.nameExists("offset")) {
      const std::vector<double> offset =
          read_all<double>(box.openDataSet("offset"), H5::PredType::NATIVE_DOUBLE);
      if (offset.size() < 2) fail(where_ + "/box/offset has fewer than two entries");
      check_finite(path_, offset, where_ + "/box/offset");
      centre_ = {offset[0] + 0.5 * edges[0], offset[1] + 0.5 * edges[1]};
    }
  }

  // An element's step and time: datasets [frames], or scalars (every frame that much later).
  void read_clock(const H5::Group& element, hsize_t frames, std::vector<long long>& steps,
                  std::vector<double>& times) const {
    steps.assign(frames, 0);
    times.assign(frames, std::numeric_limits<double>::quiet_NaN());
    if (element.nameExists("step")) {
      const std::vector<long long> s =
          read_all<long long>(element.openDataSet("step"), H5::PredType::NATIVE_LLONG);
      if (s.size() == frames) {
        steps = s;
      } else if (s.size() == 1) {
        for (hsize_t f = 0; f < frames; ++f) steps[f] = (long long)f * s[0];
      } else {
        fail(where_ + "/position/step has " + std::to_string(s.size()) + " entries for " +
             std::to_string(frames) + " frames");
      }
    } else {
      for (hsize_t f = 0; f < frames; ++f) steps[f] = (long long)f;
    }
    if (element.nameExists("time")) {
      const std::vector<double> t =
          read_all<double>(element.openDataSet("time"), H5::PredType::NATIVE_DOUBLE);
      check_finite(path_, t, where_ + "/position/time");
      if (t.size() == frames) {
        times = t;
      } else if (t.size() == 1) {
        for (hsize_t f = 0; f < frames; ++f) times[f] = double(f) * t[0];
      } else {
        fail(where_ + "/position/time has " + std::to_string(t.size()) + " entries for " +
             std::to_string(frames) + " frames");
      }
    }
  }

  RecordedTrajectory read_file() {
    const H5::H5File file(path_, H5F_ACC_RDONLY);
    if (!file.nameExists("particles")) fail("has no /particles group: not an H5MD file");
    const H5::Group all = file.openGroup("particles");
    where_ = "/particles/" + group_name(all);
    const H5::Group g = all.openGroup(where_.substr(11));
    read_box(g);
    for (const char* element : {"position", "velocity"}) {
      if (!g.nameExists(element) || g.childObjType(element) != H5O_TYPE_GROUP ||
          !g.openGroup(element).nameExists("value")) {
        fail(where_ + " has no " + element + "/value");
      }
    }
    const H5::DataSet position = g.openGroup("position").openDataSet("value");
    const H5::DataSet velocity = g.openGroup("velocity").openDataSet("value");
    const std::vector<hsize_t> dims = dims_of(position);
    if (dims.size() != 3 || dims[2] != hsize_t(dimension_) || dims[1] < 1) {
      fail(where_ + "/position/value is not [frames][N][" + std::to_string(dimension_) + "]");
    }
    if (dims_of(velocity) != dims) {
      fail(where_ + "/velocity/value is not shaped as position/value");
    }
    const hsize_t frames = dims[0], n = dims[1], d = dims[2];
    if (particles_) check_recorded_size(path_, double(frames), double(n));
    std::vector<long long> steps, vsteps;
    std::vector<double> times, vtimes;
    read_clock(g.openGroup("position"), frames, steps, times);
    read_clock(g.openGroup("velocity"), frames, vsteps, vtimes);
    for (hsize_t f = 0; f < frames; ++f) {
      if (vsteps[f] != steps[f] ||
          !(vtimes[f] == times[f] || (std::isnan(vtimes[f]) && std::isnan(times[f])))) {
        fail("velocity frame " + std::to_string(f) + " is not at the step and time of position's");
      }
    }
    // Row order: by id where the file has one.
    std::vector<long long> fixed_ids;
    std::optional<H5::DataSet> moving_ids;
    if (g.nameExists("id")) {
      if (g.childObjType("id") == H5O_TYPE_DATASET) {
        fixed_ids = read_all<long long>(g.openDataSet("id"), H5::PredType::NATIVE_LLONG);
        if (fixed_ids.size() != n)
          fail(where_ + "/id has " + std::to_string(fixed_ids.size()) + " entries for " +
               std::to_string(n) + " particles");
      } else {
        moving_ids = g.openGroup("id").openDataSet("value");
        if (dims_of(*moving_ids) != std::vector<hsize_t>{frames, n})
          fail(where_ + "/id/value is not [frames][N]");
      }
    }

    RecordedTrajectory out;
    out.files = {path_};
    out.particles = (long long)n;
    out.box_length = lengths_[0];
    out.box_width = lengths_[1];
    std::vector<double> x(n * d), v(n * d), z0;
    std::vector<long long> ids = fixed_ids, first_ids;
    for (hsize_t f = 0; f < frames; ++f) {
      read_frame(position, f, n, d, x);
      read_frame(velocity, f, n, d, v);
      const std::string at =
          "frame " + std::to_string(f) + " (step " + std::to_string(steps[f]) + ")";
      check_finite(path_, x, where_ + "/position/value at " + at);
      check_finite(path_, v, where_ + "/velocity/value at " + at);
      if (moving_ids) {
        ids.assign(n, 0);
        const hsize_t start[2] = {f, 0}, count[2] = {1, n};
        H5::DataSpace space = moving_ids->getSpace();
        space.selectHyperslab(H5S_SELECT_SET, count, start);
        const H5::DataSpace memory(2, count);
        moving_ids->read(ids.data(), H5::PredType::NATIVE_LLONG, memory, space);
      }
      std::vector<std::size_t> order(n);
      std::iota(order.begin(), order.end(), std::size_t(0));
      if (!ids.empty()) {
        std::sort(order.begin(), order.end(),
                  [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
        std::vector<long long> sorted(n);
        for (std::size_t i = 0; i < n; ++i) sorted[i] = ids[order[i]];
        if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
          fail(where_ + "/id holds an ID twice at " + at);
        if (first_ids.empty())
          first_ids = sorted;
        else if (sorted != first_ids)
          fail("the particle IDs of " + at + " differ from the first frame's");
      }
      if (d == 3) {  // z frozen: each particle keeps its z, and its z velocity is 0
        std::vector<double> z(n);
        for (std::size_t i = 0; i < n; ++i) {
          z[i] = x[order[i] * d + 2];
          if (std::abs(v[order[i] * d + 2]) > kFrozenZTolerance) {
            fail("3D motion: a z velocity " + std::to_string(v[order[i] * d + 2]) + " at " + at +
                 " (granvv reads 2D runs, or 3D with z frozen)");
          }
        }
        if (z0.empty()) z0 = z;
        for (std::size_t i = 0; i < n; ++i) {
          if (std::abs(z[i] - z0[i]) > kFrozenZTolerance) {
            fail("3D motion: particle row " + std::to_string(i) + " moves along z at " + at +
                 " (granvv reads 2D runs, or 3D with z frozen)");
          }
        }
      }
      RecordedFrame frame;
      frame.step = steps[f];
      frame.time = times[f];
      if (particles_) {
        frame.x.assign(3 * n, 0.0);
        frame.v.assign(3 * n, 0.0);
        for (std::size_t i = 0; i < n; ++i) {
          const std::size_t row = order[i] * d;
          frame.x[3 * i] = periodic_image(x[row] - centre_[0], lengths_[0]);
          frame.x[3 * i + 1] = periodic_image(x[row + 1] - centre_[1], lengths_[1]);
          frame.v[3 * i] = v[row];
          frame.v[3 * i + 1] = v[row + 1];
        }
      }
      out.frames.push_back(std::move(frame));
    }
    return out;
  }

  static void read_frame(const H5::DataSet& value, hsize_t f, hsize_t n, hsize_t d,
                         std::vector<double>& out) {
    const hsize_t start[3] = {f, 0, 0}, count[3] = {1, n, d};
    H5::DataSpace space = value.getSpace();
    space.selectHyperslab(H5S_SELECT_SET, count, start);
    const H5::DataSpace memory(3, count);
    value.read(out.data(), H5::PredType::NATIVE_DOUBLE, memory, space);
  }

  std::string path_;
  bool particles_;
  std::string where_;
  int dimension_ = 0;
  std::vector<double> lengths_, centre_;
};

}  // namespace

RecordedTrajectory read_h5md(const std::string& path, bool particles) {
  return H5mdParser(path, particles).read();
}

}  // namespace granvv::md
