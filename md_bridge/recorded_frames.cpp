#include "md_bridge/recorded_frames.hpp"

#include <glob.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "md_bridge/h5md_reader.hpp"
#include "md_bridge/lammps_dump_reader.hpp"

namespace granvv::md {
namespace {

std::string number(double x) {
  std::ostringstream os;
  os.precision(10);
  os << x;
  return os.str();
}

bool has_hdf5_signature(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[8] = {};
  in.read(head, 8);
  static const char signature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
  return in.gcount() == 8 && std::equal(head, head + 8, signature);
}

bool starts_with_item(const std::string& path) {
  std::ifstream in(path);
  std::string word;
  in >> word;
  return word.rfind("ITEM:", 0) == 0;
}

RecordedTrajectory read_file(const std::string& path, const std::string& format,
                             const RecordedOptions& options, bool particles) {
  if (format == "h5md") return read_h5md(path, particles);
  return read_lammps_dump(path, options, particles);
}

}  // namespace

void check_finite(const std::string& file, const std::vector<double>& values,
                  const std::string& what) {
  for (double x : values) {
    if (!std::isfinite(x))
      throw RecordedFileError(file, what + " holds a value that is not finite");
  }
}

void check_recorded_size(const std::string& file, double frames, double n) {
  const double bytes = frames * n * 6.0 * sizeof(double);
  if (!(bytes <= kMaxRecordedBytes)) {
    throw RecordedFileError(file, number(frames) + " frames of " + number(n) + " particles need " +
                                      number(bytes / 1e9) + " GB, more than the " +
                                      number(kMaxRecordedBytes / 1e9) +
                                      " GB a recorded member may hold");
  }
}

std::string recorded_format(const std::string& path, const std::string& requested) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw RecordedFileError(path, "no such file");
  if (requested != "auto") return requested;
  if (has_hdf5_signature(path)) return "h5md";
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".h5" || ext == ".h5md" || ext == ".hdf5") {
    throw RecordedFileError(path, "named like an HDF5 file but is not one");
  }
  if (starts_with_item(path)) return "lammps_dump";
  throw RecordedFileError(path,
                          "neither an HDF5 file nor a LAMMPS text dump (starting with ITEM:); "
                          "md.recorded.format reads \"lammps_dump\" or \"h5md\"");
}

std::vector<std::vector<std::string>> recorded_members(const std::vector<std::string>& entries) {
  std::vector<std::vector<std::string>> members;
  for (const std::string& entry : entries) {
    glob_t found{};
    const int status = glob(entry.c_str(), 0, nullptr, &found);
    std::vector<std::string> files;
    if (status == 0) {
      for (std::size_t i = 0; i < found.gl_pathc; ++i) files.emplace_back(found.gl_pathv[i]);
    }
    globfree(&found);
    if (files.empty()) throw RecordedFileError(entry, "no such file (md.recorded.files)");
    std::sort(files.begin(), files.end());
    members.push_back(files);
  }
  return members;
}

RecordedTrajectory read_recorded_member(const std::vector<std::string>& files,
                                        const RecordedOptions& options, bool particles) {
  if (!(options.diameter > 0.0)) throw std::invalid_argument("md.recorded.diameter must be > 0");
  RecordedTrajectory member;
  for (const std::string& file : files) {
    RecordedTrajectory part =
        read_file(file, recorded_format(file, options.format), options, particles);
    if (part.frames.empty()) throw RecordedFileError(file, "holds no frame");
    for (RecordedFrame& f : part.frames) {
      if (std::isnan(f.time)) {
        if (!(options.timestep > 0.0)) {
          throw RecordedFileError(file, "holds steps but no times; set md.recorded.timestep");
        }
        f.time = double(f.step) * options.timestep;
      }
    }
    if (member.frames.empty()) {
      member.particles = part.particles;
      member.box_length = part.box_length;
      member.box_width = part.box_width;
    } else {
      if (part.particles != member.particles) {
        throw RecordedFileError(file, "holds " + std::to_string(part.particles) + " particles, " +
                                          member.files.front() + " " +
                                          std::to_string(member.particles));
      }
      if (part.box_length != member.box_length || part.box_width != member.box_width) {
        throw RecordedFileError(
            file, "its box " + number(part.box_length) + " x " + number(part.box_width) +
                      " differs from " + member.files.front() + "'s " + number(member.box_length) +
                      " x " + number(member.box_width) + " (the box must be fixed)");
      }
    }
    member.files.push_back(file);
    for (RecordedFrame& f : part.frames) {
      if (!member.frames.empty()) {
        const RecordedFrame& last = member.frames.back();
        if (!(f.step > last.step && f.time > last.time)) {
          throw RecordedFileError(
              file, "frame at step " + std::to_string(f.step) + " (t = " + number(f.time) +
                        ") does not come after the one at step " + std::to_string(last.step) +
                        " (t = " + number(last.time) +
                        "): frames overlap or go back (the files of one glob are one run; list "
                        "the members of an ensemble as separate entries)");
        }
      }
      member.frames.push_back(std::move(f));
    }
  }
  // In units of sigma and the file's time, from the first frame.
  const double t0 = member.frames.front().time;
  const double unit = 1.0 / options.diameter;
  member.box_length *= unit;
  member.box_width *= unit;
  for (RecordedFrame& f : member.frames) {
    f.time -= t0;
    for (double& x : f.x) x *= unit;
    for (double& v : f.v) v *= unit;
  }
  return member;
}

}  // namespace granvv::md
