#pragma once
// Particle frames another program wrote (docs/recorded.md): LAMMPS text dumps
// (lammps_dump_reader.hpp) and H5MD files (h5md_reader.hpp), read into one trajectory per
// ensemble member and checked for what a recorded run of 2D disks in a fixed periodic box must
// be. Every file is untrusted input: a file that is not what it claims (a missing column, motion
// along z, frames whose times do not increase, a box or a particle count that changes, a value
// that is not finite, more data than kMaxRecordedBytes) is refused with RecordedFileError, one
// line naming the file and the problem.
#include <stdexcept>
#include <string>
#include <vector>

namespace granvv::md {

// The most particle data one member may hold in memory (positions and velocities of every frame):
// 4 GB, half of this machine's memory.
inline constexpr double kMaxRecordedBytes = 4e9;
// A z coordinate or z velocity beyond this (in the file's units) is motion along z: a 3D run.
inline constexpr double kFrozenZTolerance = 1e-10;
// A per-particle mass or diameter column (LAMMPS dumps) differing from md.recorded.mass or
// md.recorded.diameter by more than this, relative, is a different gas.
inline constexpr double kRecordedPropertyTolerance = 1e-6;

struct RecordedFileError : std::invalid_argument {
  RecordedFileError(const std::string& file, const std::string& problem)
      : std::invalid_argument(file + ": " + problem) {}
};

// md.recorded.format and the units of md.recorded.* (the user's: the file's length and time).
struct RecordedOptions {
  std::string format = "auto";  // "auto", "lammps_dump", "h5md"
  double timestep = 0.0;        // time per dump step (0: not given)
  double diameter = 1.0;        // sigma, in the file's length unit
  double mass = 1.0;            // m, in the file's mass unit
};

// One frame in the file's units: the step, the time (NaN until known), and every particle's
// position (wrapped into [-L/2, L/2) about the box centre) and velocity as xyz triplets (z = 0),
// ordered by particle ID.
struct RecordedFrame {
  long long step = 0;
  double time = 0.0;
  std::vector<double> x, v;
};

// One file's frames, or a member's (the files of one entry of md.recorded.files, joined).
struct RecordedTrajectory {
  std::vector<std::string> files;
  long long particles = 0;
  double box_length = 0.0, box_width = 0.0;  // Lx, Ly
  std::vector<RecordedFrame> frames;
};

// The format of a file: options.format unless "auto", else from its first bytes (the HDF5
// signature) and its extension (.h5, .h5md, .hdf5), a text file starting with "ITEM:" a dump.
std::string recorded_format(const std::string& path, const std::string& requested);

// The members of md.recorded.files: each entry a path or a glob (sorted matches: the files of
// one run, e.g. LAMMPS's dump.*.txt), one member per entry. Throws RecordedFileError for an
// entry that matches no file.
std::vector<std::vector<std::string>> recorded_members(const std::vector<std::string>& entries);

// A member read and checked: its files' frames joined in order (steps and times rising
// strictly across them), times from the files or step x options.timestep, shifted so that the
// first frame is t = 0, and lengths, velocities and times in units of sigma and the file's time
// (x / sigma, v / sigma). With particles false the frames keep their step and time only.
RecordedTrajectory read_recorded_member(const std::vector<std::string>& files,
                                        const RecordedOptions& options, bool particles);

// Helpers for the readers: the checks every format shares.
// Throws unless every value is finite.
void check_finite(const std::string& file, const std::vector<double>& values,
                  const std::string& what);
// The particle data of `frames` frames of n particles (x and v, xyz), checked against
// kMaxRecordedBytes before anything that size is allocated.
void check_recorded_size(const std::string& file, double frames, double n);

}  // namespace granvv::md
