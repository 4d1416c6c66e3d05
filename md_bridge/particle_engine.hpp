#pragma once
// The particle-engine seam (docs/architecture.md): what the engine-neutral particle run
// (md_run.hpp) needs from an engine that moves the disks of a particle scene. The run samples
// the particles, coarse-grains them, writes the H5MD frames and keeps the time series; the
// engine owns the dynamics and its collision rule. LAMMPS (lammps_engine.hpp) is the first
// implementation; engines are made by name (particle_engine_registry.hpp), so app/ never
// names one.
#include <mpi.h>

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "fields/model_result.hpp"
#include "hydro/parameter_set.hpp"
#include "md_bridge/mpi_environment.hpp"
#include "md_bridge/particle_sampler.hpp"
#include "md_bridge/particle_scene.hpp"

namespace granvv::md {

// The case keys an engine declares as its own (hydro/parameter_set.hpp): md.<name>, with its
// default, range and help. The case schema derives them through the registry
// (particle_engine_registry.hpp), and a case that runs another engine may not set them.
using EngineKeys = std::vector<hydro::ParameterSpec>;

// The name of the engine key md.<name> whose value ranks_per_member() gives (ParticleEngine), for
// the engine that declares it: the scene refuses a value that does not divide the run's ranks.
inline constexpr const char* kRanksPerMemberKey = "ranks_per_member";

// The case's settings for the engine by key ("md.max_overlap" -> 0.01; integers as reals,
// booleans as 1 or 0): the [md] keys every scene has and the engine's own keys.
using EngineSettings = std::map<std::string, double>;

// The setting `key`; std::invalid_argument "<who> needs the setting <key>" when it is missing.
inline double required_setting(const EngineSettings& settings, const std::string& key,
                               const std::string& who) {
  const auto found = settings.find(key);
  if (found == settings.end()) throw std::invalid_argument(who + " needs the setting " + key);
  return found->second;
}

// The case's text and list-of-text settings for the engine by key ("md.recorded.files" -> the
// paths; a text key as a list of one), the engine's own keys only.
using EngineTexts = std::map<std::string, std::vector<std::string>>;

// What the files of an engine that replays particles another program moved (the recorded
// engine) fix before any run, in MD units (sigma = 1 and the files' time): N, the box, the frame
// times (every member's, the same for each) and the files of each member of the ensemble.
struct GivenParticles {
  long long particles = 0;
  double box_length = 0.0, box_width = 0.0;
  std::vector<double> times;
  std::vector<std::vector<std::string>> members;
};

struct ParticleEngineSetup {
  ParticleScene scene;
  EngineSettings settings;
  EngineTexts texts;
  std::string log_dir;               // folder for the engine's own log ("" = no log)
  MPI_Comm comm = particle_ranks();  // collective over these ranks (mpi_environment.hpp)
};

// The result of calibrating or verifying the collision rule before any run.
struct CollisionRuleCheck {
  double restitution = 0.0;  // normal restitution the engine's collisions really have
  std::string description;   // how it was obtained, one line
};

// A run is refused when its engine's collision rule has a restitution further than this from the
// scene's: Haff's time scales as 1/(1 - r^2), so at r = 0.9 an error of 1e-3 in r moves t0 by
// about 1 %, inside the 3 % the cooling is judged by (compare/haff_fit.hpp).
inline constexpr double kRestitutionTolerance = 1e-3;

// Whether the checked restitution misses the target by more than kRestitutionTolerance (a NaN
// check does not miss: nothing is known against it).
inline bool misses_restitution(const CollisionRuleCheck& check, double target) {
  return std::abs(check.restitution - target) > kRestitutionTolerance;
}

// One rank's particles as the engine holds them: xyz triplets (z = 0 in 2D) and per-particle
// masses, valid until the engine next moves them.
struct LocalParticles {
  const double* x = nullptr;
  const double* v = nullptr;
  const double* mass = nullptr;
  int count = 0;
};

// One rank's contact virial per local particle, in the order of local_particles(): particle i's
// share of the pair sum sum_{pairs} r_ij (x) F_ij (r_ij = r_i - r_j, F_ij the contact force on i
// from j, repulsion positive; half of each pair to each partner), so that the values summed
// over every particle of every rank are the box's contact virial W_xx, W_yy (energy, MD units;
// the contact part of P_aa times the area, docs/physics.md §11). An engine with continuous
// contacts gives the instantaneous value; an event-driven engine gives the collisional transfer
// sum over collisions of r_ij (x) Delta p_ij divided by the time since the previous sample,
// whose expectation is the same. Both empty: no contact stress measured at this state (before
// the first step of a run, or an engine that cannot give it); the pressure is then not defined.
//
// energy_flux_x: the particle's share of the contact transfer of energy along x, in the box frame
// (energy x length / time; summed over every particle, the box's contact energy flux times the
// area). A collision of i and j that changes their energies by dE_i, dE_j moves
// (dE_i - dE_j) / 2 from r_j to r_i, adding x_ij (dE_i - dE_j) / 2 (half to each partner); the
// energy it dissipates, -(dE_i + dE_j), is lost at the contact and carries no flux. Empty: not
// measured (an engine with continuous contacts gives none).
struct LocalVirial {
  std::vector<double> xx, yy;
  std::vector<double> energy_flux_x;
};

// Every particle ordered by its ID, xyz triplets, on every rank.
struct ParticleFrame {
  std::vector<double> x, v;
};

// Wall seconds since the engine was made (the whole particle part: collision-rule check,
// every run, the coarse-graining between segments) and the engine's own unit of work
// (LAMMPS: "atom_steps", particles x time steps) summed over every run so far.
using EngineCost = fields::ModelCost;

// An engine-specific result for the summary, by a dotted key inside its `md` block
// ("contact_initial.kn"); the writer prints it without knowing what it means.
struct EngineDetail {
  std::string key;
  std::variant<double, long long, std::string> value;
};
using EngineDetails = std::vector<EngineDetail>;

// Engine-specific numbers by name ("kn"), recorded at every sample of the time series and
// written beside it (results.h5 /md/timeseries/<name>).
using EngineValues = std::vector<std::pair<std::string, double>>;

// What an engine needs to continue a run where it was saved (a checkpoint, docs/outputs.md
// "Checkpoints and resume"): every particle by ID, and the engine's own numbers by name (its
// clock, step count, collision-rule state and its totals over the runs so far). Without
// particles it holds the totals only: the state between two runs.
// An engine that spreads its particles over P > 1 ranks saves on each rank only that rank's
// block of IDs (particle_blocks.hpp: IDs first_row + 1 ..), so that no rank gathers them all.
// An engine may add its own arrays by name (the event-driven one: its whole event-driven state,
// so that a restored run continues with the same digits).
using EngineArrays = std::vector<std::pair<std::string, std::vector<double>>>;
struct EngineState {
  ParticleFrame particles;
  int particle_blocks = 1;  // P: the ranks the particles are split over (1: all of them here)
  long long first_row = 0;  // the row of particles' first entry in the whole (its ID - 1)
  EngineValues numbers;
  EngineArrays arrays;
};

// One engine serves every member of an ensemble: set_up starts a new run.
class ParticleEngine {
 public:
  virtual ~ParticleEngine() = default;

  virtual std::string name() const = 0;
  // The engine's log file, or "none".
  virtual std::string log_path() const = 0;

  // Calibrates or verifies the collision rule for the scene's restitution (collective).
  virtual CollisionRuleCheck check_collision_rule() = 0;

  // A new run from the sampled particles (the full sample on every rank), at t = 0.
  virtual void set_up(const ParticleSample& sample) = 0;
  // A new run from particles drawn for the x-range this rank holds (collective): `sample(x_lo,
  // x_hi)` gives those of the strips overlapping it (particle_sampler.hpp), with their IDs. An
  // engine that holds every particle on every rank asks for the whole box.
  using RangeSampler = std::function<ParticleSample(double x_lo, double x_hi)>;
  virtual void set_up_sampled(const RangeSampler& sample) {
    set_up(
        sample(-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()));
  }
  // The ranks over which the local particles are spread.
  virtual MPI_Comm comm() const = 0;
  // Times the engine reaches lie within half of this of the time asked for (LAMMPS: the time
  // step; 0 for an engine that stops at any time).
  virtual double time_resolution() const = 0;
  // Advances to the reachable time nearest t (at least one step past now); returns it.
  virtual double advance_to(double t) = 0;
  // Called by an engine whose segment can take long (the event-driven one, every few ten
  // thousand events) with the time it has reached, from inside advance_to, so that the
  // run can print progress and stop at a signal there (by throwing; the segment is then
  // abandoned and the engine must be set up or restored before it is used again).
  using WithinSegment = std::function<void(double t)>;
  void set_within_segment(WithinSegment check) { within_segment_ = std::move(check); }
  // Whether save_state(true) may be called from the within-segment check, giving a state from
  // which restore_state continues the segment where it stood (the run's checkpoints are then
  // taken inside long segments too). Its numbers' "t" stays the segment's start (the last
  // sample); "segment_time" is the time reached inside it.
  virtual bool saves_within_segment() const { return false; }
  // The engine's own adjustments after a segment has been sampled (LAMMPS: a softer contact
  // as the gas cools).
  virtual void between_segments() {}
  // The engine's step count in this run (time steps, or events): summary.json's md.steps.
  virtual long long steps() const = 0;
  // The step of a particle frame or an observation at the present time (the H5MD step, which
  // must increase from one frame to the next): it grows with every advance_to that moves time.
  // An engine whose every advance makes a step has its step count.
  virtual long long frame_step() const { return steps(); }

  // This rank's particles, for the coarse-grainer.
  virtual LocalParticles local_particles() = 0;
  // The IDs (1 .. N) of local_particles(), in its order: where each goes in a particle frame.
  virtual std::vector<long long> local_ids() = 0;
  // This rank's contact virial, per particle of local_particles() (collective: an engine may
  // need its ranks to exchange contributions of ghost particles).
  virtual LocalVirial local_virial() { return {}; }
  // All particles on every rank (collective; particle frames use local_ids and
  // particle_blocks.hpp instead, which gather nothing).
  virtual ParticleFrame gather_frame() = 0;
  // Engine-specific numbers of the current state, taken at every time-series sample.
  virtual EngineValues series_values() const { return {}; }

  // The state now (collective; its numbers the same on every rank): after set_up and any
  // advance_to. Without particles (with_particles false, or between runs) it holds the totals
  // only, gathering nothing.
  virtual EngineState save_state(bool with_particles) = 0;
  // Continues from a saved state (collective): the run in progress with its particles (all of
  // them on every rank, or each rank its block, as saved on the same number of ranks), or only
  // the totals. Throws std::invalid_argument for a state this engine did not save.
  virtual void restore_state(const EngineState& state) = 0;
  // Why restore_state would refuse a saved state ("" if it would not, or if the engine finds
  // out only while it restores), found without touching this engine: a resume refuses a
  // damaged checkpoint before its run starts.
  virtual std::string state_problem(const EngineState& /*state*/) const { return ""; }

  virtual EngineCost cost() const = 0;
  virtual EngineDetails details() const { return {}; }

  // Whether each member of an ensemble may run on an engine of its own, made afresh by the
  // registry on a communicator of its own, in a thread of its own, with the results it would
  // have on one engine that runs the members in turn: an engine that keeps nothing from one run
  // to the next but its totals, and holds no process-wide state (the event-driven engine; not
  // LAMMPS, whose library instances are not independent of each other in one process).
  virtual bool independent_members() const { return false; }
  // The ranks one member runs on under MPI, for an engine that declares the key
  // md.<kRanksPerMemberKey> (0: every rank of comm(), one member after another). Members then run
  // apart as for independent_members(), each on a group of that many ranks
  // (scene/md_members.hpp), one member at a time in each group.
  virtual int ranks_per_member() const { return 0; }
  // Adds the totals of the runs another engine of the same settings made (its save_state(false)),
  // as if they had been made here: the ensemble's totals when its members ran apart, added in
  // member order. Throws std::logic_error for an engine whose members never run apart.
  virtual void add_totals(const EngineState& /*other*/) {
    throw std::logic_error(name() + " engine: its members do not run apart");
  }

 protected:
  void within_segment(double t) const {
    if (within_segment_) within_segment_(t);
  }

 private:
  WithinSegment within_segment_;
};

}  // namespace granvv::md
