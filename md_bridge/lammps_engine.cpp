#include "md_bridge/lammps_engine.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "md_bridge/disk_gas.hpp"
#include "md_bridge/restitution_calibration.hpp"

namespace granvv::md {

namespace {

double required_setting(const EngineSettings& settings, const std::string& key) {
  const auto found = settings.find(key);
  if (found == settings.end())
    throw std::invalid_argument("the LAMMPS engine needs the setting " + key);
  return found->second;
}

}  // namespace

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
  o.max_overlap = required_setting(setup.settings, "md.max_overlap");
  o.steps_per_contact =
      static_cast<int>(std::lround(required_setting(setup.settings, "md.steps_per_contact")));
  o.adaptive_stiffness = required_setting(setup.settings, "md.adaptive_stiffness") != 0.0;
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

void LammpsEngine::set_up(const ParticleSample& sample) {
  if (runs_ == 1) first_final_ = contact_;
  lmp_.reset();  // one LAMMPS instance at a time
  speed_ = fastest_relative_speed(sample.v.data(), int(sample.count()), MPI_COMM_SELF);
  contact_ = contact_for_speed(std::max(speed_, 1e-12));
  LammpsSessionOptions session;
  session.log_file = options_.log_file;
  session.comm = options_.comm;
  lmp_ = std::make_unique<LammpsSession>(std::move(session));
  set_up_disk_gas(*lmp_, options_.box_length, options_.box_width, sample, contact_);
  t_ = 0.0;
  steps_ = 0;
  changes_ = 0;
  pre_ = true;
  if (runs_ == 0) first_initial_ = contact_;
  ++runs_;
}

double LammpsEngine::advance_to(double t) {
  if (!lmp_) throw std::logic_error("LammpsEngine::advance_to before set_up");
  const long long steps = std::max(1LL, std::llround((t - t_) / contact_.dt));
  lmp_->run(steps, pre_);
  pre_ = false;
  t_ += steps * contact_.dt;
  steps_ += steps;
  atom_steps_ += double(steps) * options_.particles;
  return t_;
}

LocalParticles LammpsEngine::local_particles() {
  const int n = lmp_->nlocal();
  return {n > 0 ? lmp_->x()[0] : nullptr, n > 0 ? lmp_->v()[0] : nullptr, lmp_->rmass(), n};
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

EngineValues LammpsEngine::series_values() const {
  return {{"kn", contact_.kn}, {"dt", contact_.dt}};
}

EngineCost LammpsEngine::cost() const {
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - made_).count();
  return {wall, atom_steps_, "atom_steps"};
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
