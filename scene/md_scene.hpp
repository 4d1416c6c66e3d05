#pragma once
// A case's particle part: the [md] table read into a particle scene (docs/physics.md §4), the
// particle engine it names (md_bridge/particle_engine.hpp) with its collision-rule check, an
// ensemble of seeds, and the Haff fit against kinetic theory (dilute and with the Enskog
// factor).
#include <mpi.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "compare/ensemble_statistics.hpp"
#include "compare/haff_fit.hpp"
#include "compare/haff_window.hpp"
#include "compare/sample_average.hpp"
#include "compare/signal_to_noise.hpp"
#include "md_bridge/md_run.hpp"
#include "md_bridge/mpi_environment.hpp"
#include "scene/case_config.hpp"
#include "scene/hydro_scene.hpp"
#include "scene/md_checkpoint.hpp"
#include "scene/work_estimate.hpp"

namespace granvv::app {

struct MdScene {
  md::MdRunSpec spec;                      // spec.seed is the first seed; member m uses seed + m
  int ensemble = 0;                        // md.ensemble
  std::string engine;                      // md.engine
  double checkpoint_interval = 0.0;        // md.checkpoint_interval, wall seconds (0 = none)
  double haff_mode_energy_fraction = 0.0;  // md.haff_mode_energy_fraction
  // Every number and boolean of [md] that is not another engine's own key, by key; the engine's
  // own texts and lists of texts.
  md::EngineSettings engine_settings;
  md::EngineTexts engine_texts;
  // What the files of an engine that replays given particles fix (the recorded engine): the
  // scene's N and box, the frame times (the only times its run can stop at) and the members.
  std::optional<md::GivenParticles> given;
  // The work, memory and wall time of one rank (md_bridge/particle_work.hpp).
  ParticleRunEstimate estimate;
  // Members at a time in threads on each rank, for an engine whose members are independent
  // (scene/md_members.hpp): `granvv run --jobs`, not a case key (the results do not depend on it).
  int jobs = 1;
};

// Reads [md]; std::nullopt if md.enabled is false. Throws ConfigError for scenes that cannot
// run (scene_problem, settings the engine refuses, a profile too dense to place) before the
// engine sees them.
std::optional<MdScene> md_scene_from(const CaseConfig& config, const HydroScene& hydro);

// The [md] keys every scene has and the engine's own (not another engine's), as the engine's
// setup takes them: numbers in settings, strings and lists of strings in texts.
void read_engine_keys(const CaseConfig& config, const std::string& engine,
                      md::EngineSettings& settings, md::EngineTexts& texts);

// The scene's engine; its log goes into log_dir ("" = none), collective over comm (by default
// the particle ranks, md_bridge/mpi_environment.hpp). Opens nothing yet.
std::unique_ptr<md::ParticleEngine> make_engine(const MdScene& scene, const std::string& log_dir,
                                                MPI_Comm comm = md::particle_ranks());

// Member m's H5MD particle file: spec.h5md_path, with _m<m> before its extension in an ensemble
// ("" without frames).
std::string member_h5md_path(const MdScene& scene, int member);

// The initial signal-to-noise of the scene's imposed flow in its three forms (velocity, gradient,
// mode: compare/signal_to_noise.hpp, docs/physics.md §8).
using SignalToNoise = compare::SignalToNoise;
SignalToNoise initial_signal_to_noise(const MdScene& scene);
SignalToNoise initial_gradient_signal_to_noise(const MdScene& scene);
SignalToNoise initial_mode_signal_to_noise(const MdScene& scene);

struct MdOutcome {
  std::vector<md::MdRunResult> runs;
  std::string engine;
  md::CollisionRuleCheck collision_rule;
  compare::HaffFit haff;
  double haff_t0_theory = 0.0, haff_t0_theory_dilute = 0.0;
  // The Haff fit's homogeneous window (compare/haff_window.hpp) from the ensemble's mean mode
  // energy fraction, and the linear-theory onset (md_bridge/box_modes.hpp; +inf: none).
  compare::EnsembleStatistics mode_energy_fraction;
  compare::HomogeneousWindow homogeneous;
  double linear_mode_onset = 0.0;
  // The box's (P_xx + P_yy)/2 and P/(n T) averaged over the samples and the members
  // (compare/sample_average.hpp).
  compare::SampleAverage pressure, compressibility;
  double wall_seconds = 0.0;
  md::EngineCost cost;  // over every member
  md::EngineDetails engine_details;
  // Ensemble statistics of the temperature series (run 0's sample times), and the fields over
  // the ensemble (compare/ensemble_fields.hpp; each member's own are in runs[m].fields).
  compare::EnsembleStatistics T;
  fields::FieldSeries fields;
  // Checkpoints (scene/md_checkpoint.hpp): how many this run wrote, and where it resumed (member
  // -1: it started anew). wall_seconds includes the particle part of the runs it continued.
  int checkpoints_written = 0;
  int resumed_member = -1;
  double resumed_t = 0.0;
  int members_restored = 0;  // finished members taken from the checkpoints
  int threads = 1;           // members at a time on each rank (scene/md_members.hpp)
  int cores = 1;             // the cores those threads share on each rank
  int member_groups = 1;     // groups of ranks the members were spread over, and their size
  int ranks_per_group = 1;   // (scene/md_members.hpp; one group of every rank: members in turn)
};

// Checkpoints of the particle part: into out_dir/.granvv-checkpoint every interval_seconds of
// wall time, and when stop_requested() says so (a signal: the run then stops at its next safe
// point with nothing lost). resume holds the checkpoints of an earlier run of the same case.
struct MdCheckpointing {
  std::filesystem::path out_dir;
  double interval_seconds = 0.0;
  std::function<bool()> stop_requested;
  std::vector<MemberCheckpoint> resume;
  std::function<void(const std::string&)> warn;  // a checkpoint that could not be written
};

// Throws std::runtime_error if the restitution the engine's collision rule really has misses
// the target by more than md::kRestitutionTolerance (the run is refused).
// With checkpointing null (or its out_dir empty) nothing is saved.
MdOutcome run_md_scene(const MdScene& scene, md::ParticleEngine& engine,
                       const std::function<void(int member, const md::MdProgress&)>& progress,
                       const MdCheckpointing* checkpointing = nullptr);

}  // namespace granvv::app
