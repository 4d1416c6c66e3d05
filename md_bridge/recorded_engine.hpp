#pragma once
// The recorded engine (md.engine = "recorded", docs/recorded.md): particles another program moved,
// replayed from its frames (LAMMPS text dumps, H5MD files: recorded_frames.hpp). Each entry of
// md.recorded.files is a member of the ensemble; a run of member m visits its frames in order,
// each advance_to stopping at the frame nearest the time asked for (at least the next one). The
// box, N and the frame times come from the files (given(), before any run); the restitution is
// the case's md.restitution, the one the recorded run used, which the frames cannot show.
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "md_bridge/particle_engine.hpp"
#include "md_bridge/particle_work.hpp"
#include "md_bridge/recorded_frames.hpp"

namespace granvv::md {

class RecordedEngine final : public ParticleEngine {
 public:
  RecordedEngine(const ParticleScene& scene, std::vector<std::vector<std::string>> members,
                 const RecordedOptions& options, MPI_Comm comm);
  // From the registry: md.recorded.files and the other md.recorded.* keys. Reads no file yet.
  static std::unique_ptr<ParticleEngine> make(const ParticleEngineSetup& setup);
  // The files md.recorded.files names (globs expanded), unread: what the inputs' fingerprint
  // hashes. Throws RecordedFileError for an entry that matches no file.
  static std::vector<std::string> input_files(const EngineTexts& texts);
  // Every member read and checked (RecordedFileError, naming the file and the problem): what the
  // files fix, in sigma and the files' time unit. Members must agree on N, the box and the frame
  // times. std::nullopt without files (md.recorded.files = []: the engine cannot run).
  static std::optional<GivenParticles> given(const EngineSettings& settings,
                                             const EngineTexts& texts);
  // md.recorded.files, md.recorded.format, md.recorded.timestep, md.recorded.diameter,
  // md.recorded.mass.
  static const EngineKeys& keys();
  // Its work in members read (md.ensemble of them); the memory of a member is bounded by the
  // readers (kMaxRecordedBytes).
  static ParticleWorkEstimate work(const ParticleWorkQuestion& question);

  std::string name() const override { return "recorded"; }
  std::string log_path() const override { return "none"; }
  // md.restitution as given: the recorded run's own, not measured from its frames.
  CollisionRuleCheck check_collision_rule() override;
  // The next member (in the order of md.recorded.files, again from the first after the last),
  // at its first frame; the sample is not used.
  void set_up(const ParticleSample& sample) override;
  void set_up_sampled(const RangeSampler& sample) override;
  MPI_Comm comm() const override { return comm_; }
  // The longest interval between two frames: any time within the frames is at most half of it
  // from one.
  double time_resolution() const override { return resolution_; }
  // The frame nearest t after the present one. Throws std::runtime_error past the last frame.
  double advance_to(double t) override;
  long long steps() const override;       // the file's steps since the first frame
  long long frame_step() const override;  // the file's step
  // Rank 0 holds every particle; the others none.
  LocalParticles local_particles() override;
  std::vector<long long> local_ids() override;
  ParticleFrame gather_frame() override;
  EngineState save_state(bool with_particles) override;
  void restore_state(const EngineState& state) override;
  EngineCost cost() const override;  // frames read
  // recorded.format, recorded.members, recorded.frames, recorded.diameter, recorded.mass.
  EngineDetails details() const override;

 private:
  void load(int member);
  const RecordedFrame& frame() const { return trajectory_.frames.at(frame_); }

  ParticleScene scene_;
  std::vector<std::vector<std::string>> members_;
  RecordedOptions options_;
  MPI_Comm comm_;
  int rank_ = 0;
  std::chrono::steady_clock::time_point made_;
  RecordedTrajectory trajectory_;
  int member_ = -1, next_member_ = 0;
  std::size_t frame_ = 0;
  double resolution_ = 0.0;
  long long frames_visited_ = 0;
  std::vector<double> mass_;
};

}  // namespace granvv::md
