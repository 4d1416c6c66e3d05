#pragma once
// The H5MD output of one particle run over the ranks of an engine (docs/outputs.md
// "particles.h5"). On one rank: the file at `path`, written whole (h5md_writer.hpp). On P > 1
// ranks: rank k writes the rows of its block of IDs (particle_blocks.hpp) to its block file
// block_file_path(path, k), and rank 0 writes the joined file at `path` (the whole-box
// observables, the frames' steps and times, and virtual datasets joining the blocks). No rank
// holds more particles than its block and its own.
#include <mpi.h>

#include <memory>
#include <string>

#include "md_bridge/h5md_writer.hpp"
#include "md_bridge/particle_engine.hpp"

namespace granvv::md {

// Rank k's block file beside `path`: particles.h5 -> particles.rank0003.h5 (k = 3; four digits
// or more).
std::string block_file_path(const std::string& path, int rank);

class H5mdFrames {
 public:
  struct Spec {
    std::string path;
    long long n_particles = 0;
    double box_length = 0.0, box_width = 0.0;
    std::string creator_version;
  };
  // Creates the files (collective over comm); with resume_step >= 0, continues those of the run
  // that was stopped, cut back to frames at steps <= resume_step (H5mdWriter::continue_file).
  // A resume refuses (std::runtime_error, on every rank) files written by another number of
  // ranks.
  H5mdFrames(const Spec& spec, MPI_Comm comm, long long resume_step = -1);

  // The writer of the observables: rank 0's whole or joined file; null on the other ranks.
  H5mdWriter* observables() { return summary_; }
  // One particle frame of the engine's particles (collective). Throws std::runtime_error on
  // every rank if any rank could not write its rows.
  void append_frame(long long step, double time, ParticleEngine& engine);

 private:
  Spec spec_;
  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1;
  std::unique_ptr<H5mdWriter> rows_;    // this rank's rows: the whole file, or its block file
  std::unique_ptr<H5mdWriter> joined_;  // rank 0 on P > 1 ranks
  H5mdWriter* summary_ = nullptr;
};

}  // namespace granvv::md
