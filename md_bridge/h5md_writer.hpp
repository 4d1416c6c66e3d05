#pragma once
// Particle snapshots and scalar observables of an MD run in the H5MD 1.1 layout (de Buyl,
// Colberg & Höfling, Comp. Phys. Comm. 185, 1546 (2014); h5md.nongnu.org), so that H5MD
// readers and plain HDF5 tools (h5py, h5ls) read them. Layout written:
//
//   /h5md                        +-- version: int32[2] = {1, 1}
//        \-- author              +-- name: string (fixed length, scalar)
//        \-- creator             +-- name: "granvv", version: string (the version passed in)
//   /particles/all
//        \-- box                 +-- dimension: int32 = 2
//        |                       +-- boundary: string[2] = {"periodic", "periodic"}
//        |    \-- edges: float64[2] = {Lx, Ly}              (a fixed box: time-independent)
//        \-- id: int64[N] = {1, ..., N}                     (row i holds LAMMPS atom ID i + 1)
//        \-- position
//        |    \-- step: int64[frames]
//        |    \-- time: float64[frames]
//        |    \-- value: float64[frames][N][2]              (wrapped into the box, see below)
//        \-- velocity
//             \-- step, time: hard links to position/step and position/time
//             \-- value: float64[frames][N][2]
//   /observables/<name>          one per observable; thermal_energy, kinetic_energy_x,
//        \-- step: int64[frames]                  kinetic_energy_y and total_energy always
//        \-- time: float64[frames]                exist (possibly with 0 frames); any other
//        \-- value: float64[frames]               name is created on its first append.
//
// Every time-dependent dataset is chunked (a joined file's values: virtual, below) and extendible
// along its first (frame) axis; strings are fixed-length, null-terminated ASCII, as H5MD requires.
// Units are those of the MD run (sigma = m = T0 = 1, docs/physics.md §4); step is the engine's step
// count and time the physical time. Steps must increase strictly and times must not decrease within
// each element (H5MD requires monotonic step/time so that readers may bisect them).
//
// Positions are written modulo the box into [-Lx/2, Lx/2) x [-Ly/2, Ly/2), the box of
// md_run (LAMMPS: `region box block -Lx/2 Lx/2 -Ly/2 Ly/2`); no image element is written.
//
// Crash safety: the file uses the HDF5 1.8 object format (superblock version 2, no
// file-consistency flags), and every append ends with a flush. A process that dies between two
// appends (an error inside LAMMPS ends the whole process, docs/physics.md §10) leaves a valid file
// holding every frame appended so far. The writer takes no HDF5 file lock, so other processes
// may open the file read-only while the run goes on (they see the state of the last flush;
// a read that overlaps an append may fail and is to be retried).
//
// Under MPI the particle rows are written in blocks (docs/outputs.md "particles.h5";
// particle_blocks.hpp, h5md_frames.hpp): rank k writes the rows of its block of IDs, as a file
// of its own (a *block* file: /particles/all/{box, id, position, velocity} for IDs first + 1 ..
// first + count, no observables), and rank 0 writes the *joined* file, laid out as above, whose
// /particles/all/id and {position, velocity}/value are HDF5 virtual datasets (HDF5 >= 1.10)
// mapping every block file's rows into rows [first, first + count) of the whole, along an
// unlimited frame axis; its step, time and observables are its own. A reader opens the joined
// file alone (the block files are found beside it, by their file names) and sees one
// [frames][N][2] dataset; a block file missing reads as NaN. Its value datasets are as long as
// the longest block file, so that after a kill they may show a frame more than step and time,
// which count the frames every block file finished. The joined file keeps superblock version 2
// (HDF5 1.8 lower bound; the virtual layout needs the 1.10 upper bound).
// Needs HDF5 >= 1.10.7 (H5Pset_file_locking).
//
// Errors (bad arguments, HDF5 failures) throw std::invalid_argument or std::runtime_error,
// naming the file; an append that throws leaves the frames already flushed intact.
#include <memory>
#include <string>
#include <vector>

namespace granvv::md {

// A block of particle rows: rows [first, first + count) of an N-particle frame, IDs first + 1
// .. first + count; for a joined file, the block file holding them (a name relative to the
// joined file's folder).
struct H5mdBlock {
  std::string file;
  long long first = 0;
  long long count = 0;
};

class H5mdWriter {
 public:
  // The observables created with the file.
  static const std::vector<std::string>& standard_observables();

  // Creates (truncating) the file at `path`; its directory must exist. n_particles >= 1,
  // box_length = Lx and box_width = Ly finite and > 0. An empty author is replaced by $USER
  // (or "unknown"): H5MD makes /h5md/author/name mandatory.
  H5mdWriter(const std::string& path, long long n_particles, double box_length, double box_width,
             const std::string& creator_version, const std::string& author = "");
  // Continues the file a run wrote before it was stopped (a resumed run, docs/outputs.md
  // "Checkpoints and resume"): the file at `path` is made anew with the frames of the old one
  // whose step is at most last_step, particles and observables alike; frames written after the
  // checkpoint at last_step are dropped. Throws std::runtime_error if the old file cannot be
  // read (it is then left as it was).
  static H5mdWriter continue_file(const std::string& path, long long last_step,
                                  long long n_particles, double box_length, double box_width,
                                  const std::string& creator_version);

  // A block file: the rows `block` (count >= 1) of an n_particles frame (its file name unused).
  static H5mdWriter block_file(const std::string& path, long long n_particles,
                               const H5mdBlock& block, double box_length, double box_width,
                               const std::string& creator_version);
  // The joined file of the block files `blocks`, which cover rows 0 .. n_particles - 1 once, in
  // order. Its frames are recorded by append_joined_frame once every block file has its rows.
  static H5mdWriter joined_file(const std::string& path, long long n_particles,
                                const std::vector<H5mdBlock>& blocks, double box_length,
                                double box_width, const std::string& creator_version);
  // continue_file for a block file, and for a joined file (step, time and observables up to
  // last_step; the block files are continued by their own writers).
  static H5mdWriter continue_block_file(const std::string& path, long long last_step,
                                        long long n_particles, const H5mdBlock& block,
                                        double box_length, double box_width,
                                        const std::string& creator_version);
  static H5mdWriter continue_joined_file(const std::string& path, long long last_step,
                                         long long n_particles,
                                         const std::vector<H5mdBlock>& blocks, double box_length,
                                         double box_width, const std::string& creator_version);
  // The block files an existing file joins (empty for a file that holds its rows itself).
  // Throws std::runtime_error if it cannot be read.
  static std::vector<std::string> joined_block_files(const std::string& path);

  ~H5mdWriter();  // closes the file; never throws
  H5mdWriter(H5mdWriter&&) noexcept;
  H5mdWriter& operator=(H5mdWriter&&) noexcept;
  H5mdWriter(const H5mdWriter&) = delete;
  H5mdWriter& operator=(const H5mdWriter&) = delete;

  // One particle frame. x_xyz and v_xyz are LAMMPS-style triplets (x0 y0 z0 x1 y1 z1 ...)
  // ordered by atom ID (lammps_gather_atoms order), 3 N values each; z is ignored. Appends to
  // /particles/all/{position,velocity} and flushes.
  void append_particles(long long step, double time, const std::vector<double>& x_xyz,
                        const std::vector<double>& v_xyz);
  // A block file: the same with the 3 count values of its rows. A joined file: the frame's step
  // and time only (append_particles refuses), after every block file has appended its rows.
  void append_joined_frame(long long step, double time);
  // One sample of the scalar observable /observables/<name> (created on first use; a name is
  // non-empty, without '/', and not "." or ".."). Flushes.
  void append_observable(const std::string& name, long long step, double time, double value);

  void flush();
  // Flushes and closes the file; later appends throw std::logic_error. Idempotent.
  void close();

  const std::string& path() const;
  long long n_particles() const;  // rows a frame of this file holds (a block file: its count)
  long long particle_frames() const;
  long long observable_frames(const std::string& name) const;  // 0 for an unknown name

  // x modulo length, into [-length/2, length/2) (periodic_image, particle_scene.hpp).
  static double wrap(double x, double length);

 private:
  struct Layout;  // which rows the file holds, and how (h5md_writer.cpp)
  H5mdWriter(const std::string& path, const Layout& layout, double box_length, double box_width,
             const std::string& creator_version, const std::string& author);
  static H5mdWriter continue_layout(const std::string& path, long long last_step,
                                    const Layout& layout, double box_length, double box_width,
                                    const std::string& creator_version);
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Impl& impl() const;
};

}  // namespace granvv::md
