#include "md_bridge/lammps_engine.hpp"

#include <lammps/library.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "md_bridge/disk_gas.hpp"
#include "md_bridge/disk_overlap.hpp"
#include "md_bridge/particle_blocks.hpp"
#include "md_bridge/restitution_calibration.hpp"

namespace granvv::md {

namespace {

// The per-atom contact stress (docs/physics.md §11). LAMMPS tallies a per-atom virial only on
// steps scheduled for a compute that was invoked since the previous thermo output; the thermo
// line therefore carries the box sum of the compute (kContactVirialSum; -W_xx, -W_yy per
// particle, thermo normalises by N in lj units), which schedules it for the last step of every
// run, where LAMMPS always prints thermo.
constexpr const char* kContactStressCompute = "granvv_contact_stress";
constexpr const char* kContactVirialSum = "granvv_contact_virial";

constexpr const char* kWho = "the LAMMPS engine";

}  // namespace

const EngineKeys& LammpsEngine::keys() {
  static const EngineKeys keys = {
      {"max_overlap", 0.01, hydro::ParameterRange::open_closed(0, 0.1),
       "largest overlap at the fastest relative speed, in sigma (hard-disk limit)"},
      {"steps_per_contact", 30LL, hydro::ParameterRange::closed(10, 1e4),
       "time steps per contact duration"},
      {"adaptive_stiffness", true, hydro::ParameterRange::any(),
       "lower kn and raise dt as the gas cools, restitution fixed"},
      {kRanksPerMemberKey, 0LL, hydro::ParameterRange::closed(0, 1e6),
       "under mpirun: MPI ranks per ensemble member, members spread over the groups (a divisor "
       "of the ranks); 0 = each member on every rank, one after another"},
  };
  return keys;
}

const EngineKeys& LammpsEngine::atlas_keys() {
  using hydro::ParameterRange;
  static const EngineKeys keys = {
      {"max_overlaps", std::vector<double>{},
       ParameterRange::increasing(ParameterRange::open_closed(0, 0.1)),
       "LAMMPS md.max_overlap values ([] = md.max_overlap times 1/2, 1, 2, 5, 10)"},
      {"steps_per_contacts", std::vector<long long>{},
       ParameterRange::increasing(ParameterRange::closed(10, 1e4)),
       "LAMMPS md.steps_per_contact values ([] = md.steps_per_contact times 1/3, 1/2, 1, 2)"},
  };
  return keys;
}

double fastest_relative_speed(const double* v, int n, MPI_Comm comm) {
  double fastest = 0.0;
  for (int i = 0; i < n; ++i) {
    fastest = std::max(fastest, v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1]);
  }
  MPI_Allreduce(MPI_IN_PLACE, &fastest, 1, MPI_DOUBLE, MPI_MAX, comm);
  return 2.0 * std::sqrt(fastest);
}

LammpsEngine::LammpsEngine(LammpsEngineOptions options)
    : options_(std::move(options)), made_(std::chrono::steady_clock::now()) {
  contact_ = contact_for_speed(kCalibrationSpeed);  // refuses a contact that cannot be made
}

std::unique_ptr<ParticleEngine> LammpsEngine::make(const ParticleEngineSetup& setup) {
  LammpsEngineOptions o;
  o.restitution = setup.scene.restitution;
  o.box_length = setup.scene.box_length;
  o.box_width = setup.scene.box_width;
  o.particles = setup.scene.particles;
  o.max_overlap = required_setting(setup.settings, "md.max_overlap", kWho);
  o.steps_per_contact =
      static_cast<int>(std::lround(required_setting(setup.settings, "md.steps_per_contact", kWho)));
  o.adaptive_stiffness = required_setting(setup.settings, "md.adaptive_stiffness", kWho) != 0.0;
  o.ranks_per_member = static_cast<int>(
      std::lround(required_setting(setup.settings, std::string("md.") + kRanksPerMemberKey, kWho)));
  o.log_file = setup.log_dir.empty()
                   ? "none"
                   : (std::filesystem::path(setup.log_dir) / "log.lammps").string();
  o.comm = setup.comm;
  return std::make_unique<LammpsEngine>(std::move(o));
}

ContactModel LammpsEngine::contact_for_speed(double relative_speed) const {
  ContactSpec c;
  c.restitution = options_.restitution;
  c.max_overlap = options_.max_overlap;
  c.max_relative_speed = relative_speed;
  c.steps_per_contact = options_.steps_per_contact;
  validate(c);
  ContactModel model = make_contact_model(c);
  validate(model);
  return model;
}

CollisionRuleCheck LammpsEngine::check_collision_rule() {
  RestitutionCalibrationOptions calibration_options;
  calibration_options.comm = options_.comm;
  RestitutionCalibration calibration(contact_for_speed(kCalibrationSpeed),
                                     std::move(calibration_options));
  const RestitutionMeasurement m = calibration.measure(1.0);
  std::ostringstream what;
  what << "measured in LAMMPS: " << m.per_phase.size()
       << " head-on collisions at entry phases spread over a time step, r from "
       << m.restitution_min << " to " << m.restitution_max;
  return {m.restitution, what.str()};
}

std::pair<std::array<double, 2>, std::array<double, 2>> LammpsEngine::open_box() {
  lmp_.reset();  // one LAMMPS instance at a time
  LammpsSessionOptions session;
  session.log_file = options_.log_file;
  session.comm = options_.comm;
  lmp_ = std::make_unique<LammpsSession>(std::move(session));
  create_disk_box(*lmp_, options_.box_length, options_.box_width);
  return lammps_subdomain(*lmp_);
}

void LammpsEngine::fill_box(const ParticleSample& sample, long long total) {
  add_disks(*lmp_, sample, contact_, total);
  add_stress_computes();
}

void LammpsEngine::add_stress_computes() {
  const std::string stress = kContactStressCompute, sum = kContactVirialSum;
  lmp_->commands(
      {"compute " + stress + " all stress/atom NULL pair",
       "compute " + sum + " all reduce sum c_" + stress + "[1] c_" + stress + "[2]",
       "thermo_style custom step temp epair emol etotal press c_" + sum + "[1] c_" + sum + "[2]"});
  pre_ = true;
  virial_tallied_ = false;
}

void LammpsEngine::set_up(const ParticleSample& sample) {
  set_up_sampled([&](double, double) { return sample; });
}

// The box first, so that each rank knows its subdomain and draws only the strips over it; the
// contact is made for the fastest speed over every rank's particles.
void LammpsEngine::set_up_sampled(const RangeSampler& sample) {
  if (runs_ == 1) {
    first_final_ = contact_;
    first_final_speed_ = speed_;
  }
  const auto [lo, hi] = open_box();
  const ParticleSample particles = sample(lo[0], hi[0]);
  // A sample without IDs is the whole box on every rank (its fastest speed is every rank's).
  speed_ = std::max(fastest_relative_speed(particles.v.data(), int(particles.count()),
                                           particles.id.empty() ? MPI_COMM_SELF : options_.comm),
                    1e-12);
  contact_ = contact_for_speed(speed_);
  fill_box(particles, particles.id.empty() ? particles.count() : options_.particles);
  t_ = 0.0;
  steps_ = 0;
  changes_ = 0;
  if (runs_ == 0) {
    first_initial_ = contact_;
    first_initial_speed_ = speed_;
  }
  ++runs_;
}

EngineState LammpsEngine::save_state(bool with_particles) {
  EngineState state;
  if (lmp_ && with_particles) {  // each rank its block of IDs (all of them on one rank)
    int rank = 0;
    MPI_Comm_rank(options_.comm, &rank);
    MPI_Comm_size(options_.comm, &state.particle_blocks);
    state.particles =
        block_frame(local_particles(), local_ids(), options_.particles, options_.comm);
    state.first_row = id_block(options_.particles, state.particle_blocks, rank).first;
  }
  state.numbers = {{"t", t_},
                   {"steps", double(steps_)},
                   {"speed", speed_},
                   {"changes", double(changes_)},
                   {"runs", double(runs_)},
                   {"atom_steps", atom_steps_},
                   {"all_changes", double(all_changes_)},
                   {"first_initial_speed", first_initial_speed_},
                   {"first_final_speed", runs_ > 1 ? first_final_speed_ : speed_},
                   {"wall_seconds", cost().wall_seconds}};
  return state;
}

void LammpsEngine::restore_numbers(const EngineState& state) {
  std::map<std::string, double> number;
  for (const auto& [name, value] : state.numbers) number[name] = value;
  const auto get = [&](const std::string& name) {
    const auto found = number.find(name);
    if (found == number.end() || !std::isfinite(found->second))
      throw std::invalid_argument("LAMMPS engine state without a finite '" + name + "'");
    return found->second;
  };
  t_ = get("t");
  steps_ = std::llround(get("steps"));
  speed_ = get("speed");
  changes_ = int(std::lround(get("changes")));
  runs_ = int(std::lround(get("runs")));
  atom_steps_ = get("atom_steps");
  all_changes_ = int(std::lround(get("all_changes")));
  first_initial_speed_ = get("first_initial_speed");
  first_final_speed_ = get("first_final_speed");
  wall_before_ = get("wall_seconds");
  made_ = std::chrono::steady_clock::now();
  contact_ = contact_for_speed(speed_);
  if (runs_ > 0) first_initial_ = contact_for_speed(first_initial_speed_);
  if (runs_ > 1) first_final_ = contact_for_speed(first_final_speed_);
}

std::string LammpsEngine::state_problem(const EngineState& state) const {
  LammpsEngine probe(options_);
  try {
    probe.restore_numbers(state);
  } catch (const std::exception& e) {
    return e.what();
  }
  const auto& p = state.particles;
  if (p.x.empty() || state.particle_blocks != 1) return "";  // a block alone: checked whole
  if (p.x.size() != 3 * std::size_t(options_.particles) || p.v.size() != p.x.size())
    return std::to_string(p.x.size() / 3) + " particles for a scene of " +
           std::to_string(options_.particles);
  // The contact is made so that a head-on collision at the fastest relative speed present
  // presses two disks md.max_overlap into each other, and a Hookean contact's deepest overlap
  // grows only linearly with the approach speed: an overlap kDamagedOverlap times deeper would
  // need a collision kDamagedOverlap times faster than any in the run, and two disks on one
  // spot make the contact force 0 * inf (LAMMPS would end the run on the rank holding them).
  try {
    const DiskOverlap o = deepest_overlap(p.x, options_.box_length, options_.box_width);
    if (o.depth > kDamagedOverlap * options_.max_overlap) {
      std::ostringstream what;
      what << "disks " << o.first + 1 << " and " << o.second + 1 << " overlap by " << o.depth
           << " sigma, more than " << kDamagedOverlap
           << " x md.max_overlap = " << kDamagedOverlap * options_.max_overlap
           << "; no collision of the run presses disks so deep";
      return what.str();
    }
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

void LammpsEngine::restore_state(const EngineState& state) {
  restore_numbers(state);
  lmp_.reset();
  const auto& p = state.particles;
  if (p.x.empty() && state.particle_blocks == 1) return;  // between runs: set_up starts one
  int rank = 0, ranks = 1;
  MPI_Comm_rank(options_.comm, &rank);
  MPI_Comm_size(options_.comm, &ranks);
  const bool blocks = state.particle_blocks > 1;
  if (blocks && state.particle_blocks != ranks)
    throw std::invalid_argument("LAMMPS engine state saved over " +
                                std::to_string(state.particle_blocks) + " ranks, restored on " +
                                std::to_string(ranks));
  const IdBlock block =
      blocks ? id_block(options_.particles, ranks, rank) : IdBlock{0, options_.particles};
  if (p.x.size() != 3 * std::size_t(block.count) || p.v.size() != p.x.size() ||
      state.first_row != block.first)
    throw std::invalid_argument("LAMMPS engine state with " + std::to_string(p.x.size() / 3) +
                                " particles from row " + std::to_string(state.first_row) +
                                " for a scene of " + std::to_string(options_.particles) +
                                (blocks ? " on " + std::to_string(ranks) + " ranks" : ""));
  // Saved positions may lie up to half the neighbour skin outside the periodic box (LAMMPS maps
  // atoms back only when it rebuilds its lists); their images inside it are the same state.
  ParticleSample sample{p.x, p.v, {}};
  const double edge[2] = {options_.box_length, options_.box_width};
  for (std::size_t i = 0; i < sample.x.size(); i += 3) {
    for (int d = 0; d < 2; ++d) sample.x[i + d] = periodic_image(sample.x[i + d], edge[d]);
  }
  const auto [lo, hi] = open_box();
  if (!blocks) return fill_box(sample, sample.count());
  // Each rank's block goes to the ranks whose subdomain holds it (1 sigma of margin against
  // round-off at the cuts: LAMMPS keeps each disk on its owner alone).
  for (long long i = 0; i < block.count; ++i) sample.id.push_back(block.first + i + 1);
  fill_box(to_subdomains(sample, lo.data(), hi.data(), 1.0, options_.comm), options_.particles);
}

double LammpsEngine::advance_to(double t) {
  if (!lmp_) throw std::logic_error("LammpsEngine::advance_to before set_up");
  const long long steps = std::max(1LL, std::llround((t - t_) / contact_.dt));
  lmp_->run(steps, pre_);
  pre_ = false;
  virial_tallied_ = true;
  t_ += steps * contact_.dt;
  steps_ += steps;
  atom_steps_ += double(steps) * options_.particles;
  return t_;
}

LocalParticles LammpsEngine::local_particles() {
  const int n = lmp_->nlocal();
  return {n > 0 ? lmp_->x()[0] : nullptr, n > 0 ? lmp_->v()[0] : nullptr, lmp_->rmass(), n};
}

std::vector<long long> LammpsEngine::local_ids() {
  const int n = lmp_->nlocal();
  const LammpsTag* tag = lmp_->id();
  return std::vector<long long>(tag, tag + n);
}

LocalVirial LammpsEngine::local_virial() {
  LocalVirial w;
  if (!lmp_ || !virial_tallied_) return w;
  const int n = lmp_->nlocal();
  auto** stress = static_cast<double**>(lammps_extract_compute(
      lmp_->handle(), kContactStressCompute, LMP_STYLE_ATOM, LMP_TYPE_ARRAY));
  if (n > 0 && stress == nullptr)
    throw std::runtime_error("LAMMPS gave no per-atom contact stress");
  w.xx.resize(std::size_t(n));
  w.yy.resize(std::size_t(n));
  for (int i = 0; i < n; ++i) {
    w.xx[std::size_t(i)] = -stress[i][0];
    w.yy[std::size_t(i)] = -stress[i][1];
  }
  return w;
}

ParticleFrame LammpsEngine::gather_frame() {
  ParticleFrame frame;
  frame.x = lmp_->gather_atoms("x", 3);
  frame.v = lmp_->gather_atoms("v", 3);
  return frame;
}

// Hard-disk limit as the gas cools: a softer spring and a longer step at the same r. The
// discrete contact map depends only on gamma_n dt and omega0 dt, which are the same for any
// kn at fixed steps_per_contact, so the restitution is unchanged.
void LammpsEngine::between_segments() {
  if (!options_.adaptive_stiffness) return;
  const LocalParticles local = local_particles();
  const double now = fastest_relative_speed(local.v, local.count, options_.comm);
  if (now > 0.0 && now < options_.adapt_below * speed_) {
    speed_ = now;
    contact_ = contact_for_speed(speed_);
    lmp_->commands(
        {pair_style_command(contact_), pair_coeff_command(), timestep_command(contact_)});
    pre_ = true;
    ++changes_;
    ++all_changes_;
  }
}

void LammpsEngine::add_totals(const EngineState& other) {
  LammpsEngine run(options_);
  run.restore_state({{}, 1, 0, other.numbers, {}});
  if (runs_ == 1) {  // the first run's final contact, kept as set_up keeps it for a second run
    first_final_ = contact_;
    first_final_speed_ = speed_;
  }
  t_ = run.t_;
  steps_ = run.steps_;
  speed_ = run.speed_;
  contact_ = run.contact_;
  changes_ = run.changes_;
  runs_ += run.runs_;
  atom_steps_ += run.atom_steps_;
  all_changes_ += run.all_changes_;
  wall_before_ += run.wall_before_;
}

EngineValues LammpsEngine::series_values() const {
  return {{"kn", contact_.kn}, {"dt", contact_.dt}};
}

EngineCost LammpsEngine::cost() const {
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - made_).count();
  return {wall_before_ + wall, atom_steps_, "atom_steps"};
}

EngineDetails LammpsEngine::details() const {
  EngineDetails d = {{"stiffness_changes", static_cast<long long>(all_changes_)}};
  auto add = [&d](const std::string& name, const ContactModel& c) {
    d.push_back({name + ".kn", c.kn});
    d.push_back({name + ".gamma_n", c.gamma_n});
    d.push_back({name + ".dt", c.dt});
    d.push_back({name + ".contact_time", c.contact_time});
  };
  add("contact_initial", first_initial_);
  add("contact_final", runs_ > 1 ? first_final_ : contact_);
  return d;
}

}  // namespace granvv::md
