#include "md_bridge/md_run.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "md_bridge/disk_gas.hpp"
#include "md_bridge/h5md_writer.hpp"
#include "md_bridge/lammps_session.hpp"
#include "md_bridge/moment_reduction.hpp"
#include "md_bridge/particle_sampler.hpp"

namespace granvv::md {
namespace {

ContactModel contact_for_speed(const MdRunSpec& spec, double relative_speed) {
  ContactSpec c;
  c.restitution = spec.scene.restitution;
  c.max_overlap = spec.max_overlap;
  c.max_relative_speed = relative_speed;
  c.steps_per_contact = spec.steps_per_contact;
  validate(c);
  ContactModel model = make_contact_model(c);
  validate(model);
  return model;
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

MdRunResult run_md(const MdRunSpec& spec, const std::function<void(const MdProgress&)>& progress) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto wall = [&] { return std::chrono::duration<double>(clock::now() - start).count(); };
  const std::string problem = scene_problem(spec.scene);
  if (!problem.empty()) throw std::invalid_argument(problem);
  if (!(spec.t_end > 0.0) || !(spec.sample_interval > 0.0)) {
    throw std::invalid_argument("md.t_end and md.sample_interval must be > 0");
  }

  MpiEnvironment::ensure();
  const ParticleScene& scene = spec.scene;
  const ParticleSample sample = sample_particles(scene, spec.fields, spec.seed);
  const double lx = scene.box_length, ly = scene.box_width;
  CoarseGrainer grainer({-0.5 * lx, lx, -0.5 * ly, ly, spec.bins, spec.kernel, spec.kernel_width});

  MdRunResult result;
  double speed = fastest_relative_speed(sample.v.data(), int(sample.count()), MPI_COMM_SELF);
  ContactModel contact = contact_for_speed(spec, std::max(speed, 1e-12));
  result.initial_contact = contact;

  LammpsSessionOptions options;
  options.log_file = spec.log_file;
  LammpsSession lmp(options);
  // Local atom arrays (LAMMPS layout); null on a rank that holds no atoms.
  auto local_x = [&] { return lmp.nlocal() > 0 ? lmp.x()[0] : nullptr; };
  auto local_v = [&] { return lmp.nlocal() > 0 ? lmp.v()[0] : nullptr; };
  set_up_disk_gas(lmp, lx, ly, sample, contact);

  // Particle output in H5MD layout (rank 0 writes; gathering is collective).
  std::unique_ptr<H5mdWriter> h5md;
  if (!spec.h5md_path.empty() && lmp.rank() == 0) {
    h5md =
        std::make_unique<H5mdWriter>(spec.h5md_path, scene.particles, lx, ly, spec.creator_version);
  }
  double next_frame = 0.0;
  auto write_frame = [&](double time) {
    if (spec.snapshot_interval <= 0.0 || spec.h5md_path.empty()) return;
    if (time < next_frame - 0.5 * contact.dt) return;
    const auto x = lmp.gather_atoms("x", 3), v = lmp.gather_atoms("v", 3);
    if (h5md) h5md->append_particles(result.steps, time, x, v);
    next_frame += spec.snapshot_interval;
  };

  double t = 0.0;
  size_t next_output = 0;
  bool first_run = true, changed = false;
  auto observe = [&](bool snapshot) {
    Moments m = grainer.accumulate(local_x(), local_v(), lmp.rmass(), lmp.nlocal());
    allreduce(m, lmp.comm());
    const BoxEnergies e = grainer.energies(m);
    auto& s = result.series;
    s.t.push_back(t);
    s.T.push_back(e.thermal / e.particles);
    s.energy_thermal.push_back(e.thermal);
    s.energy_kinetic_x.push_back(e.kinetic_macro_x);
    s.energy_kinetic_y.push_back(e.kinetic_macro_y);
    s.kinetic_noise_x.push_back(e.macro_noise_x);
    s.kinetic_noise_y.push_back(e.macro_noise_y);
    s.energy_total.push_back(e.kinetic_total);
    s.momentum_x.push_back(e.momentum_x);
    s.momentum_y.push_back(e.momentum_y);
    s.kn.push_back(contact.kn);
    s.dt.push_back(contact.dt);
    if (snapshot) result.snapshots.push_back({t, grainer.fields(m)});
    if (h5md) {
      h5md->append_observable("thermal_energy", result.steps, t, e.thermal);
      h5md->append_observable("kinetic_energy_x", result.steps, t, e.kinetic_macro_x);
      h5md->append_observable("kinetic_energy_y", result.steps, t, e.kinetic_macro_y);
      h5md->append_observable("total_energy", result.steps, t, e.kinetic_total);
    }
    write_frame(t);
  };
  const auto& outputs = spec.output_times;
  while (next_output < outputs.size() && outputs[next_output] <= 0.0) ++next_output;
  observe(!outputs.empty() && outputs.front() <= 0.0);

  while (t < spec.t_end - 0.5 * contact.dt) {  // samples land on the nearest step
    // Next stop: a sample time or an output time, whichever comes first.
    double target = std::min(spec.t_end, t + spec.sample_interval);
    if (spec.snapshot_interval > 0.0 && !spec.h5md_path.empty())
      target = std::min(target, next_frame);
    bool snapshot = false;
    if (next_output < outputs.size() && outputs[next_output] <= target + 0.5 * contact.dt) {
      target = outputs[next_output];
      snapshot = true;
    }
    const long long steps = std::max(1LL, std::llround((target - t) / contact.dt));
    lmp.run(steps, first_run || changed);
    first_run = changed = false;
    t += steps * contact.dt;
    result.steps += steps;
    result.atom_steps += double(steps) * scene.particles;
    if (snapshot) ++next_output;
    observe(snapshot);
    if (progress) progress({t, spec.t_end, result.series.T.back(), wall(), result.steps});

    // Hard-disk limit as the gas cools: a softer spring and a longer step at the same r.
    // The discrete contact map depends only on gamma_n dt and omega0 dt, which are the same
    // for any kn at fixed steps_per_contact, so the restitution is unchanged.
    if (spec.adaptive_stiffness) {
      const double now = fastest_relative_speed(local_v(), lmp.nlocal(), lmp.comm());
      if (now > 0.0 && now < spec.adapt_below * speed) {
        speed = now;
        contact = contact_for_speed(spec, speed);
        lmp.commands(
            {pair_style_command(contact), pair_coeff_command(), timestep_command(contact)});
        changed = true;
        ++result.stiffness_changes;
      }
    }
  }
  result.final_contact = contact;
  result.status = "ok";
  result.stop_reason = "end time reached";
  result.wall_seconds = wall();
  return result;
}

}  // namespace granvv::md
