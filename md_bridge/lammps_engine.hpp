#pragma once
// The LAMMPS particle engine (docs/physics.md §5, §10): smooth inelastic disks with the
// gran/hooke contact (friction off) of contact_model.hpp, integrated by velocity Verlet in a
// periodic box (disk_gas.hpp). The contact is made for the fastest relative speed of the
// sample and softened at fixed restitution as the gas cools (hard-disk limit); the
// restitution it really gives is measured in LAMMPS by head-on collisions
// (restitution_calibration.hpp). Every contact model, the calibrated one included, comes from
// one validated ContactSpec (contact_for_speed).
#include <array>
#include <chrono>
#include <memory>
#include <string>
#include <utility>

#include "md_bridge/contact_model.hpp"
#include "md_bridge/lammps_session.hpp"
#include "md_bridge/particle_engine.hpp"

namespace granvv::md {

struct LammpsEngineOptions {
  // Set from the scene and the md.* keys (their defaults are in keys() only).
  double restitution = 0.0;  // target r, the scene's
  double box_length = 0.0;   // Lx, Ly (sigma); the box is [-L/2, L/2)
  double box_width = 0.0;
  long long particles = 0;          // N, for the cost in atom-steps
  double max_overlap = 0.0;         // sigma, at the fastest relative speed present (md.max_overlap)
  int steps_per_contact = 0;        // md.steps_per_contact
  bool adaptive_stiffness = false;  // md.adaptive_stiffness
  double adapt_below = 0.5;         // re-stiffen when the fastest speed fell below this fraction
  int ranks_per_member = 0;         // md.ranks_per_member (0: every rank, members in turn)
  std::string log_file = "none";    // LAMMPS -log of the runs (not of the calibration)
  MPI_Comm comm = MPI_COMM_WORLD;
};

// The fastest relative normal speed two particles can have, 2 max |v| over the local atoms
// of every rank of comm (v: xyz triplets): the speed the contact must resolve.
double fastest_relative_speed(const double* v, int n, MPI_Comm comm);

class LammpsEngine final : public ParticleEngine {
 public:
  // Throws std::invalid_argument (naming the md.* key) if no valid contact can be made.
  explicit LammpsEngine(LammpsEngineOptions options);
  // From the registry: the scene and the case keys md.max_overlap, md.steps_per_contact,
  // md.adaptive_stiffness and md.ranks_per_member (std::invalid_argument if one is missing); the
  // log is log_dir/log.lammps.
  static std::unique_ptr<ParticleEngine> make(const ParticleEngineSetup& setup);
  // Its own case keys: md.max_overlap, md.steps_per_contact, md.adaptive_stiffness,
  // md.ranks_per_member.
  static const EngineKeys& keys();
  // The atlas's grid of the contact knobs (models/family_lammps.cpp).
  static const EngineKeys& atlas_keys();

  std::string name() const override { return "lammps"; }
  std::string log_path() const override { return options_.log_file; }

  // The phase-averaged restitution of the contact made for relative speed
  // kCalibrationSpeed, measured at approach speed 1 (restitution_calibration.hpp). The
  // discrete contact map depends only on gamma_n dt and omega0 dt, the same for every kn at
  // fixed steps per contact, so this is the restitution of every contact the runs use.
  CollisionRuleCheck check_collision_rule() override;

  void set_up(const ParticleSample& sample) override;
  void set_up_sampled(const RangeSampler& sample) override;
  MPI_Comm comm() const override { return options_.comm; }
  double time_resolution() const override { return contact_.dt; }
  double advance_to(double t) override;
  void between_segments() override;
  long long steps() const override { return steps_; }
  LocalParticles local_particles() override;
  std::vector<long long> local_ids() override;
  // -S_xx, -S_yy of LAMMPS's `compute stress/atom NULL pair` (stress x area with the sign of
  // a tension: S_ab = -m v_a v_b - W_ab, of which the pair keyword keeps -W_ab), tallied on the
  // last step of every run (the thermo line, which LAMMPS prints there, invokes it through its
  // box sum). Empty before the first step of a run.
  LocalVirial local_virial() override;
  ParticleFrame gather_frame() override;
  // kn and dt of the contact in use.
  EngineValues series_values() const override;
  // Numbers: t, steps, speed (the contact's), changes (this run's); runs, atom_steps,
  // all_changes, first_initial_speed, first_final_speed, wall_seconds (the totals). The contacts
  // are made again from their speeds (contact_for_speed is deterministic).
  EngineState save_state(bool with_particles) override;
  void restore_state(const EngineState& state) override;
  // Its numbers as restore_state reads them, its count of particles, and how deep its disks
  // overlap (deeper than kDamagedOverlap x md.max_overlap: refused), checked on the whole state
  // (a checkpoint saved in blocks is checked with every block).
  std::string state_problem(const EngineState& state) const override;
  EngineCost cost() const override;
  // stiffness_changes (all runs), contact_initial and contact_final ({kn, gamma_n, dt}, of
  // the first run).
  EngineDetails details() const override;

  // Each member on a LAMMPS instance of its own, opened on its group's communicator in a
  // process of its own (one instance per process: the instances of one process are not
  // independent of each other).
  int ranks_per_member() const override { return options_.ranks_per_member; }
  // The later run's own state (its clock, steps, contact) and the totals summed; the first run's
  // contacts stay this engine's.
  void add_totals(const EngineState& other) override;

  // The validated contact model for relative normal speeds up to `relative_speed`.
  ContactModel contact_for_speed(double relative_speed) const;
  const ContactModel& contact() const { return contact_; }
  int stiffness_changes() const { return changes_; }  // in the current run

  static constexpr double kCalibrationSpeed = 10.0;
  // An overlap this many times md.max_overlap is not one a run made (state_problem).
  static constexpr double kDamagedOverlap = 5.0;

 private:
  LammpsEngineOptions options_;
  std::chrono::steady_clock::time_point made_;
  std::unique_ptr<LammpsSession> lmp_;
  // A fresh LAMMPS instance on the engine's communicator (the old one closed first) with the
  // empty box: this rank's subdomain (lo, hi), for the particles it is to create.
  std::pair<std::array<double, 2>, std::array<double, 2>> open_box();
  // The clock, counts, speeds and contacts of a saved state (std::invalid_argument for a
  // missing or non-finite number, or a contact that cannot be made).
  void restore_numbers(const EngineState& state);
  // The disks (add_disks: `total` over all ranks) at contact_, and the stress computes.
  void fill_box(const ParticleSample& sample, long long total);
  void add_stress_computes();  // and the thermo line that tallies them
  ContactModel contact_;
  double speed_ = 0.0;  // relative speed the contact was made for
  double t_ = 0.0;
  long long steps_ = 0;
  int changes_ = 0;
  bool pre_ = true;
  bool virial_tallied_ = false;  // a step has run in this session (the compute has its values)  //
                                 // the next run must set LAMMPS up again (new atoms, pair or step)
  int runs_ = 0;
  // Over every run: the work and the changes; of the first run: its contacts.
  double atom_steps_ = 0.0;
  int all_changes_ = 0;
  ContactModel first_initial_, first_final_;
  double first_initial_speed_ = 0.0, first_final_speed_ = 0.0;
  double wall_before_ = 0.0;  // wall seconds of the processes that ran before a restore
};

}  // namespace granvv::md
