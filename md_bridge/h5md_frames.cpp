#include "md_bridge/h5md_frames.hpp"

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "md_bridge/every_rank.hpp"
#include "md_bridge/particle_blocks.hpp"

namespace granvv::md {

std::string block_file_path(const std::string& path, int rank) {
  const std::filesystem::path p = path;
  char number[16];
  std::snprintf(number, sizeof number, "%04d", rank);
  return (p.parent_path() / (p.stem().string() + ".rank" + number + p.extension().string()))
      .string();
}

H5mdFrames::H5mdFrames(const Spec& spec, MPI_Comm comm, long long resume_step)
    : spec_(spec), comm_(comm) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &ranks_);
  const long long n = spec.n_particles;
  const double lx = spec.box_length, ly = spec.box_width;
  const std::string& version = spec.creator_version;
  const bool resume = resume_step >= 0;
  if (ranks_ == 1) {
    rows_ = std::make_unique<H5mdWriter>(
        resume ? H5mdWriter::continue_file(spec.path, resume_step, n, lx, ly, version)
               : H5mdWriter(spec.path, n, lx, ly, version));
    summary_ = rows_.get();
    return;
  }
  std::vector<H5mdBlock> blocks;  // the non-empty ones (N < P leaves some empty)
  for (int k = 0; k < ranks_; ++k) {
    const IdBlock b = id_block(n, ranks_, k);
    if (b.count > 0)
      blocks.push_back({std::filesystem::path(block_file_path(spec.path, k)).filename().string(),
                        b.first, b.count});
  }
  if (resume) {  // the stopped run's files must be laid out as this run's
    on_every_rank(comm, [&] {
      if (rank_ != 0) return;
      std::vector<std::string> expected;
      for (const auto& b : blocks) expected.push_back(b.file);
      const std::vector<std::string> found = H5mdWriter::joined_block_files(spec.path);
      if (found != expected)
        throw std::runtime_error("H5MD file " + spec.path + " was written " +
                                 (found.empty()
                                      ? std::string("whole, by one rank")
                                      : "in " + std::to_string(found.size()) + " block files") +
                                 "; this resume runs on " + std::to_string(ranks_) +
                                 " ranks: resume it on the number of ranks the run started with");
    });
  }
  const IdBlock own = id_block(n, ranks_, rank_);
  on_every_rank(comm, [&] {
    if (own.count == 0) return;
    const std::string file = block_file_path(spec.path, rank_);
    const H5mdBlock block{"", own.first, own.count};
    rows_ = std::make_unique<H5mdWriter>(
        resume ? H5mdWriter::continue_block_file(file, resume_step, n, block, lx, ly, version)
               : H5mdWriter::block_file(file, n, block, lx, ly, version));
  });
  on_every_rank(comm, [&] {
    if (rank_ != 0) return;
    joined_ = std::make_unique<H5mdWriter>(
        resume
            ? H5mdWriter::continue_joined_file(spec.path, resume_step, n, blocks, lx, ly, version)
            : H5mdWriter::joined_file(spec.path, n, blocks, lx, ly, version));
    summary_ = joined_.get();
  });
}

void H5mdFrames::append_frame(long long step, double time, ParticleEngine& engine) {
  const ParticleFrame rows =
      block_frame(engine.local_particles(), engine.local_ids(), spec_.n_particles, comm_);
  on_every_rank(comm_, [&] {
    if (rows_) rows_->append_particles(step, time, rows.x, rows.v);
  });
  // Every block file has its rows (flushed): the joined file may now show the frame.
  if (ranks_ > 1)
    on_every_rank(comm_, [&] {
      if (joined_) joined_->append_joined_frame(step, time);
    });
}

}  // namespace granvv::md
