#pragma once
// The event-driven particle engine (docs/physics.md §10): smooth inelastic hard disks
// (sigma = m = 1) in a periodic box, moved from one exact binary collision to the next. No
// contact time, no overlap, no time step: between events every disk flies straight, with its
// own clock; positions are brought to a common time only when the run looks at them (the end
// of every advance_to). Events (collisions and cell crossings) come from an EventCalendar
// (event_calendar.hpp) over a PeriodicCells grid (periodic_cells.hpp); the collision kernel
// and the collapse rule are hard_disk_collision.hpp.
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "md_bridge/collision_virial.hpp"
#include "md_bridge/event_calendar.hpp"
#include "md_bridge/hard_disk_collision.hpp"
#include "md_bridge/particle_engine.hpp"
#include "md_bridge/periodic_cells.hpp"

namespace granvv::md {

struct EventDrivenOptions {
  // Set from the scene and the md.* keys (their defaults are in keys() only).
  double restitution = 1.0;  // r, the scene's
  double box_length = 0.0;   // Lx, Ly (sigma); the box is [-L/2, L/2)
  double box_width = 0.0;
  long long particles = 0;
  // md.collapse_speed (u0 of impact_restitution), md.contact_duration (t_c of the TC model),
  // md.elastic_speed (delta): the rules against inelastic collapse (hard_disk_collision.hpp).
  CollapseRule collapse;
  double max_collision_rate = 0.0;  // md.max_collision_rate: per particle per unit MD time
  int virial_bins = 1;              // md.bins: the collision virial per bin along x
  MPI_Comm comm = MPI_COMM_WORLD;
};

// The collisional (virial) part of the pressure over the last sampled interval: for hard disks
// in 2D, p_c = sum over collisions of r_ij . Delta p_i / (2 A Delta t), with r_ij . Delta p_i =
// sigma J the separation at contact times the impulse (docs/physics.md §10). `bins` along x
// (md.bins bins of area Lx Ly / bins) take each collision at the midpoint of its pair; box is
// their mean. The kinetic part n T is the coarse-grainer's.
struct CollisionVirial {
  double t_begin = 0.0, t_end = 0.0;  // the interval (MD time); empty before the first advance
  double box = 0.0;
  std::vector<double> bins;
};

class EventDrivenEngine final : public ParticleEngine {
 public:
  // Throws std::invalid_argument (naming the md.* key or the box) for settings it cannot run.
  explicit EventDrivenEngine(EventDrivenOptions options);
  // From the registry: the scene, its own keys (keys()) and md.bins.
  static std::unique_ptr<ParticleEngine> make(const ParticleEngineSetup& setup);
  // Its own case keys: md.collapse_speed, md.contact_duration, md.contact_speed,
  // md.elastic_speed, md.max_collision_rate.
  static const EngineKeys& keys();
  // The atlas's particle-count grid and its limit on the collapse rules
  // (models/family_event_driven.cpp).
  static const EngineKeys& atlas_keys();

  std::string name() const override { return "event_driven"; }
  std::string log_path() const override { return "none"; }

  // A head-on collision at approach speed kCheckSpeed (above md.collapse_speed) through the
  // engine's own collision code: the restitution its collisions have.
  CollisionRuleCheck check_collision_rule() override;

  void set_up(const ParticleSample& sample) override;
  MPI_Comm comm() const override { return options_.comm; }
  double time_resolution() const override { return 0.0; }
  // Processes every event up to t and brings all disks to t. Throws std::runtime_error
  // (event-rate runaway) if the segment needs more than md.max_collision_rate N (t - now) + N
  // collisions, or if any 10 N of its collisions take less than 10 / md.max_collision_rate of
  // time (the rule in event_driven_engine.cpp): inelastic collapse, which the collapse rule
  // should have prevented. Calls the run's within-segment check every 65536 events, between
  // two events. After a restore of a state saved there it continues that segment.
  double advance_to(double t) override;
  // Its state is saved whole (every disk's flight, cell, prediction and calendar entry, and
  // the segment's sums so far): a restored run goes on with the same digits, also from inside
  // a segment.
  bool saves_within_segment() const override { return true; }
  long long steps() const override { return events_; }  // events of this run
  // The events and the stops: a stop, which brings every disk to its time, is an event of the
  // run of its own, so that a segment without a collision or a cell crossing (a short sample
  // interval in a cold, dilute gas) still moves the H5MD step on.
  long long frame_step() const override { return events_ + stops_; }

  // Every rank holds and moves all disks (the same dynamics on each); rank 0 hands them to the
  // coarse-grainer, the others none.
  LocalParticles local_particles() override;
  std::vector<long long> local_ids() override;
  ParticleFrame gather_frame() override;
  // Each disk's share of the collision virial over the last interval of advance_to
  // (collision_virial.hpp), on rank 0; empty before the first advance of a run.
  LocalVirial local_virial() override;
  // collision_virial_pressure (the box's, CollisionVirial) and collisions_per_particle_time
  // (2 collisions / (N dt)) over the last interval; 0 at the first sample (no interval yet).
  EngineValues series_values() const override;
  EngineState save_state(bool with_particles) override;
  void restore_state(const EngineState& state) override;
  std::string state_problem(const EngineState& state) const override;
  EngineCost cost() const override;  // collisions
  // events, events_per_second, crossings, restitution_effective, collapse_rule.{rule,
  // collapse_speed, collisions_changed, fraction_changed}, max_collision_rate, cells.
  EngineDetails details() const override;
  // Each member on an engine of its own (it keeps only its totals from one run to the next).
  bool independent_members() const override { return true; }
  void add_totals(const EngineState& other) override;

  // The collision virial over the last interval of advance_to (for the pressure: kinetic plus
  // collisional).
  const CollisionVirial& collision_virial() const { return virial_; }
  long long collisions() const { return collisions_; }  // of this run
  long long collisions_changed() const { return changed_; }
  long long collisions_made_elastic() const { return tc_elastic_; }  // by the TC rule
  long long collisions_below_elastic_speed() const { return speed_elastic_; }
  // Current time and the disks' positions and velocities (xyz triplets) at it.
  double time() const { return t_; }
  // The smallest centre distance of any two disks now (sigma = 1 means touching).
  double smallest_separation() const;

  static constexpr double kCheckSpeed = 1.0;

 private:
  // What gather reads of every candidate: 32 bytes, two to a cache line, in cell
  // order (order_by_cell). (x, y) is the disk's position on its straight flight extended to the
  // engine's epoch_, so that no candidate needs a clock of its own: at time t the disk is at
  // (x + vx (t - epoch_), y + vy (t - epoch_)).
  struct alignas(32) Disk {
    double x = 0.0, y = 0.0, vx = 0.0, vy = 0.0;
  };
  // What a disk's calendar entry is: its soonest collision (kCollision) or leaving its cell along
  // axis 0 (x) or 1 (y).
  static constexpr std::int8_t kCollision = -1;
  // The soonest collision with a disk of its neighbourhood found since its last full scan
  // (absolute time, the partner and the partner's count then; never, -1 if none).
  struct Soonest {
    double t = 0.0;
    int partner = -1;
    std::uint32_t partner_count = 0;
  };
  void start(const std::vector<double>& x, const std::vector<double>& v, double t);
  // The position of disk d at time t (on its straight flight).
  double x_at(const Disk& d, double t) const { return d.x + d.vx * (t - epoch_); }
  double y_at(const Disk& d, double t) const { return d.y + d.vy * (t - epoch_); }
  // Moves the epoch to t (every position with it), so that positions stay near the disks'.
  void rebase(double t);
  // Its next event from a scan of its whole neighbourhood (after it collided, or its partner
  // did), or after it entered a new cell from the three cells that joined the neighbourhood.
  void predict(int i, double now);
  void predict_after_crossing(int i, double now, int axis, int direction);
  // The candidates of disk i in `count` cells (at most a neighbourhood's): their separation from
  // it now (in each cell's image) and their relative velocity, appended to candidates_.
  void gather(int i, double now, const PeriodicCells::Neighbour* cells, int count);
  // The soonest contact of disk i among candidates_, if sooner than its soonest so far.
  void choose_soonest(int i, double now);
  void schedule(int i, double now);
  void collide(int i, int j, double now);
  void cross(int i, int axis, double now);
  void synchronise();
  // The whole event-driven state (save_state's arrays), and a restore from them; the restore
  // throws std::invalid_argument for arrays of another size or out of range.
  EngineArrays whole_state() const;
  void restore_whole(const EngineState& state, double segment_time);
  // Renumbers the disks in the order of their cells (cells, calendar and partners follow), so
  // that the disks of neighbouring cells lie near each other in memory as the gas mixes; and
  // moves the epoch to now.
  void order_by_cell(double now);
  // The nearest image of a separation d along a side of the given length: for disks at contact.
  double minimum_image(double d, double length) const;

  EventDrivenOptions options_;
  std::chrono::steady_clock::time_point made_;
  double wall_before_ = 0.0;
  int rank_ = 0;
  std::vector<Disk> disks_;  // in cell order after each order_by_cell
  double epoch_ = 0.0;
  std::vector<std::uint32_t> count_;  // collisions of each disk so far
  std::vector<std::int8_t> event_;    // each disk's calendar entry: kCollision or an axis
  std::vector<Soonest> soonest_;
  // Time of each disk's last impact, for the TC rule (-infinity before its first in this
  // engine; a resumed run starts without that history).
  std::vector<double> last_impact_;
  std::vector<int> id_;  // particle ID of each disk
  // The candidates of one prediction, as a structure of arrays so that their contact times are
  // computed several at a time (SIMD); in a dilute gas whether a candidate approaches is a coin
  // toss that a branch per candidate would mispredict half the time.
  struct Candidates {
    std::vector<double> dx, dy, dvx, dvy;
    std::vector<int> disk;
    std::vector<int> touching;  // choose_soonest's list of the candidates that touch
    std::size_t size = 0;
  };
  Candidates candidates_;
  std::unique_ptr<PeriodicCells> cells_;
  EventCalendar calendar_;
  std::vector<double> x_, v_, mass_;  // the disks at t_ (xyz), for the run loop
  double t_ = 0.0;
  // This run.
  long long events_ = 0, collisions_ = 0, crossings_ = 0, changed_ = 0, tc_elastic_ = 0,
            speed_elastic_ = 0;
  long long ordered_at_ = 0;  // events_ when the disks were last put in cell order
  long long stops_ = 0;       // advance_to calls that moved time (frame_step)
  // Over every run.
  int runs_ = 0;
  long long all_events_ = 0, all_collisions_ = 0, all_crossings_ = 0, all_changed_ = 0,
            all_tc_elastic_ = 0, all_speed_elastic_ = 0;
  double approach_sum_ = 0.0, recoil_sum_ = 0.0;  // of the normal speeds, for r measured
  // The interval being accumulated and the last one finished.
  std::vector<double> virial_sum_;  // sum of sigma J per bin
  long long segment_collisions_ = 0;
  CollisionVirial virial_;
  CollisionVirialTally tally_;  // the same per disk
  double collision_rate_ = 0.0;
  // The segment advance_to is inside (open between its start and its end, also across a save
  // and restore from within it): where it began, its events then, and the rate window's start.
  struct Segment {
    bool open = false;
    double begin = 0.0, window_begin = 0.0, now = 0.0;
    long long events_at_begin = 0, window_collisions = 0;
  };
  Segment segment_;
};

}  // namespace granvv::md
