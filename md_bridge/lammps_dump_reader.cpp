#include "md_bridge/lammps_dump_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>

#include "md_bridge/particle_scene.hpp"

namespace granvv::md {
namespace {

// The shortest row a dump can hold per atom: five numbers of one digit with their separators.
constexpr double kShortestRowBytes = 10.0;

struct Column {
  int index = -1;
  std::string name;
  bool scaled = false;  // xs, ys, zs: fractions of the box
};

// The first of `names` among the header's columns.
Column find_column(const std::map<std::string, int>& columns,
                   std::initializer_list<const char*> names) {
  for (const char* name : names) {
    const auto found = columns.find(name);
    if (found != columns.end()) {
      const std::string n = name;
      return {found->second, n, n.size() == 2 && n[1] == 's'};
    }
  }
  return {};
}

class DumpParser {
 public:
  DumpParser(const std::string& path, const RecordedOptions& options, bool particles)
      : path_(path), options_(options), particles_(particles), in_(path) {
    if (!in_) throw RecordedFileError(path, "cannot be read");
    std::error_code ec;
    file_bytes_ = double(std::filesystem::file_size(path, ec));
  }

  RecordedTrajectory read() {
    RecordedTrajectory out;
    out.files = {path_};
    std::string line;
    double time = std::numeric_limits<double>::quiet_NaN();
    std::optional<long long> step;
    long long n = -1;
    while (next_line(line)) {
      if (line.empty()) continue;
      if (line.rfind("ITEM: UNITS", 0) == 0) {
        expect_line(line, "ITEM: UNITS");
      } else if (line.rfind("ITEM: TIMESTEP", 0) == 0) {
        step = parse_integer(expect_line(line, "ITEM: TIMESTEP"), "ITEM: TIMESTEP");
      } else if (line.rfind("ITEM: TIME", 0) == 0) {
        time = parse_real(expect_line(line, "ITEM: TIME"), "ITEM: TIME");
      } else if (line.rfind("ITEM: NUMBER OF ATOMS", 0) == 0) {
        n = parse_integer(expect_line(line, "ITEM: NUMBER OF ATOMS"), "ITEM: NUMBER OF ATOMS");
        if (n < 1 || double(n) * kShortestRowBytes > file_bytes_) {
          fail("ITEM: NUMBER OF ATOMS " + std::to_string(n) + " is not a count this file can hold");
        }
        if (particles_) check_recorded_size(path_, double(out.frames.size() + 1), double(n));
      } else if (line.rfind("ITEM: BOX BOUNDS", 0) == 0) {
        read_box(line);
      } else if (line.rfind("ITEM: ATOMS", 0) == 0) {
        if (!step) fail("ITEM: ATOMS before ITEM: TIMESTEP");
        if (n < 0) fail("ITEM: ATOMS before ITEM: NUMBER OF ATOMS");
        if (!box_) fail("ITEM: ATOMS before ITEM: BOX BOUNDS");
        if (!out.frames.empty() && n != out.particles) {
          fail("the number of atoms changes from " + std::to_string(out.particles) + " to " +
               std::to_string(n) + " at step " + std::to_string(*step));
        }
        out.particles = n;
        out.box_length = lengths_[0];
        out.box_width = lengths_[1];
        RecordedFrame frame = read_atoms(line, n, *step);
        frame.step = *step;
        frame.time = time;
        out.frames.push_back(std::move(frame));
        step.reset();
        time = std::numeric_limits<double>::quiet_NaN();
        box_.reset();
      } else {
        fail("line " + std::to_string(line_number_) + " (\"" + line.substr(0, 40) +
             "\") is not a LAMMPS dump item");
      }
    }
    if (step) fail("ends inside the frame of step " + std::to_string(*step));
    if (out.frames.empty()) fail("holds no frame (no ITEM: ATOMS)");
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw RecordedFileError(path_, problem);
  }

  bool next_line(std::string& line) {
    if (!std::getline(in_, line)) return false;
    ++line_number_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  }

  std::string expect_line(const std::string&, const std::string& item) {
    std::string value;
    if (!next_line(value)) fail("ends after " + item);
    return value;
  }

  long long parse_integer(const std::string& text, const std::string& what) const {
    errno = 0;
    char* end = nullptr;
    const long long value = std::strtoll(text.c_str(), &end, 10);
    if (end == text.c_str() || errno != 0)
      fail(what + " \"" + text.substr(0, 40) + "\" is not an integer");
    return value;
  }

  double parse_real(const std::string& text, const std::string& what) const {
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || !std::isfinite(value)) {
      fail(what + " \"" + text.substr(0, 40) + "\" is not a finite number");
    }
    return value;
  }

  // ITEM: BOX BOUNDS [xy xz yz] bx by bz, then "lo hi" per axis. The box must be orthogonal,
  // periodic along x and y, and the same in every frame.
  void read_box(const std::string& header) {
    std::istringstream words(header.substr(std::string("ITEM: BOX BOUNDS").size()));
    std::vector<std::string> flags;
    for (std::string w; words >> w;) flags.push_back(w);
    if (std::find(flags.begin(), flags.end(), "xy") != flags.end()) {
      fail("a triclinic box (ITEM: BOX BOUNDS xy xz yz); granvv reads orthogonal periodic boxes");
    }
    if (flags.size() >= 2 && (flags[0] != "pp" || flags[1] != "pp")) {
      fail("box boundaries " + flags[0] + " " + flags[1] + "; granvv needs x and y periodic (pp)");
    }
    const std::size_t axes = flags.empty() ? 3 : flags.size();
    std::vector<double> lo, hi;
    for (std::size_t a = 0; a < axes; ++a) {
      std::string line;
      if (!next_line(line)) fail("ends inside ITEM: BOX BOUNDS");
      std::istringstream bounds(line);
      double l = 0.0, h = 0.0;
      if (!(bounds >> l >> h) || !std::isfinite(l) || !std::isfinite(h) || !(h > l)) {
        fail("box bounds \"" + line.substr(0, 40) + "\" are not two finite numbers lo < hi");
      }
      lo.push_back(l), hi.push_back(h);
    }
    if (lo.size() < 2) fail("a box with fewer than two axes");
    if (!lo_.empty() && (lo_ != lo || hi_ != hi)) {
      fail("the box changes at line " + std::to_string(line_number_) +
           " (granvv needs a fixed box)");
    }
    lo_ = lo, hi_ = hi;
    lengths_ = {hi[0] - lo[0], hi[1] - lo[1]};
    box_ = true;
  }

  RecordedFrame read_atoms(const std::string& header, long long n, long long step) {
    std::istringstream words(header.substr(std::string("ITEM: ATOMS").size()));
    std::map<std::string, int> columns;
    int count = 0;
    for (std::string w; words >> w;) columns[w] = count++;
    const Column id = find_column(columns, {"id"});
    const Column xs[3] = {find_column(columns, {"x", "xu", "xs", "xsu"}),
                          find_column(columns, {"y", "yu", "ys", "ysu"}),
                          find_column(columns, {"z", "zu", "zs", "zsu"})};
    const Column vx = find_column(columns, {"vx"}), vy = find_column(columns, {"vy"}),
                 vz = find_column(columns, {"vz"});
    const Column mass = find_column(columns, {"mass"}), radius = find_column(columns, {"radius"}),
                 diameter = find_column(columns, {"diameter"});
    std::string missing;
    if (xs[0].index < 0) missing += " x (or xu, xs)";
    if (xs[1].index < 0) missing += " y (or yu, ys)";
    if (vx.index < 0) missing += " vx";
    if (vy.index < 0) missing += " vy";
    if (!missing.empty())
      fail("ITEM: ATOMS at step " + std::to_string(step) + " has no column" + missing);

    struct Row {
      long long id;
      double x, y, vx, vy;
    };
    std::vector<Row> rows;
    rows.reserve(std::size_t(n));
    std::vector<double> values(static_cast<std::size_t>(count));
    std::string line;
    for (long long i = 0; i < n; ++i) {
      if (!next_line(line)) {
        fail("the frame of step " + std::to_string(step) + " ends after " + std::to_string(i) +
             " of its " + std::to_string(n) + " atoms");
      }
      const char* p = line.c_str();
      for (int c = 0; c < count; ++c) {
        char* end = nullptr;
        values[std::size_t(c)] = std::strtod(p, &end);
        if (end == p) {
          fail("line " + std::to_string(line_number_) + " has fewer than " + std::to_string(count) +
               " numbers");
        }
        if (!std::isfinite(values[std::size_t(c)])) {
          fail("line " + std::to_string(line_number_) + " holds a value that is not finite");
        }
        p = end;
      }
      auto at = [&](const Column& col) { return values[std::size_t(col.index)]; };
      auto position = [&](int axis) {
        const double raw = at(xs[axis]);
        const double length = hi_[std::size_t(axis)] - lo_[std::size_t(axis)];
        return xs[axis].scaled ? lo_[std::size_t(axis)] + raw * length : raw;
      };
      if (vz.index >= 0 && std::abs(at(vz)) > kFrozenZTolerance) {
        fail("3D motion: vz = " + std::to_string(at(vz)) + " at line " +
             std::to_string(line_number_) + " (granvv reads 2D runs, or 3D with z frozen)");
      }
      const long long atom = id.index >= 0 ? std::llround(at(id)) : i + 1;
      if (xs[2].index >= 0) check_frozen_z(atom, position(2));
      if (mass.index >= 0) check_property(at(mass), options_.mass, "mass", "md.recorded.mass");
      if (radius.index >= 0) {
        check_property(2.0 * at(radius), options_.diameter, "2 radius", "md.recorded.diameter");
      }
      if (diameter.index >= 0) {
        check_property(at(diameter), options_.diameter, "diameter", "md.recorded.diameter");
      }
      rows.push_back({atom, position(0), position(1), at(vx), at(vy)});
    }
    std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.id < b.id; });
    std::vector<long long> ids(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) ids[i] = rows[i].id;
    if (std::adjacent_find(ids.begin(), ids.end()) != ids.end()) {
      fail("the frame of step " + std::to_string(step) + " holds an atom ID twice");
    }
    if (ids_.empty()) {
      ids_ = ids;
    } else if (ids != ids_) {
      fail("the atom IDs of step " + std::to_string(step) + " differ from the first frame's");
    }
    RecordedFrame frame;
    if (!particles_) return frame;
    const double cx = 0.5 * (lo_[0] + hi_[0]), cy = 0.5 * (lo_[1] + hi_[1]);
    frame.x.resize(3 * rows.size(), 0.0);
    frame.v.resize(3 * rows.size(), 0.0);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      frame.x[3 * i] = periodic_image(rows[i].x - cx, lengths_[0]);
      frame.x[3 * i + 1] = periodic_image(rows[i].y - cy, lengths_[1]);
      frame.v[3 * i] = rows[i].vx;
      frame.v[3 * i + 1] = rows[i].vy;
    }
    return frame;
  }

  void check_frozen_z(long long atom, double z) {
    const auto [it, inserted] = z_.emplace(atom, z);
    if (!inserted && std::abs(it->second - z) > kFrozenZTolerance) {
      fail("3D motion: atom " + std::to_string(atom) + " moves along z at line " +
           std::to_string(line_number_) + " (granvv reads 2D runs, or 3D with z frozen)");
    }
  }

  void check_property(double value, double expected, const std::string& what,
                      const std::string& key) const {
    if (std::abs(value - expected) > kRecordedPropertyTolerance * std::abs(expected)) {
      fail("line " + std::to_string(line_number_) + " has " + what + " " + std::to_string(value) +
           " but " + key + " = " + std::to_string(expected));
    }
  }

  std::string path_;
  RecordedOptions options_;
  bool particles_;
  std::ifstream in_;
  double file_bytes_ = 0.0;
  long long line_number_ = 0;
  std::optional<bool> box_;
  std::vector<double> lo_, hi_, lengths_;
  std::vector<long long> ids_;
  std::map<long long, double> z_;
};

}  // namespace

RecordedTrajectory read_lammps_dump(const std::string& path, const RecordedOptions& options,
                                    bool particles) {
  return DumpParser(path, options, particles).read();
}

}  // namespace granvv::md
