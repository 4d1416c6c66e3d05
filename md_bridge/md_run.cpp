#include "md_bridge/md_run.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "fields/field_series.hpp"
#include "fields/hdf5_datasets.hpp"
#include "md_bridge/box_modes.hpp"
#include "md_bridge/every_rank.hpp"
#include "md_bridge/h5md_frames.hpp"
#include "md_bridge/moment_reduction.hpp"
#include "md_bridge/mpi_environment.hpp"
#include "md_bridge/particle_sampler.hpp"

namespace granvv::md {

namespace {

// The particle frames, closed under the HDF5 lock (members may run in threads).
struct CloseFramesLocked {
  void operator()(H5mdFrames* frames) const {
    const std::lock_guard<std::recursive_mutex> lock(h5::library_mutex());
    delete frames;
  }
};

}  // namespace

double resumed_time(const MdRunState& state) {
  for (const auto& [name, value] : state.engine.numbers)
    if (name == "segment_time") return value;
  return state.t;
}

const std::vector<MdSeriesColumn>& md_series_columns() {
  static const std::vector<MdSeriesColumn> columns{
      {"t", &MdSeries::t},
      {"T", &MdSeries::T},
      {"energy_thermal", &MdSeries::energy_thermal},
      {"energy_kinetic_x", &MdSeries::energy_kinetic_x},
      {"energy_kinetic_y", &MdSeries::energy_kinetic_y},
      {"energy_total", &MdSeries::energy_total},
      {"kinetic_noise_x", &MdSeries::kinetic_noise_x},
      {"kinetic_noise_y", &MdSeries::kinetic_noise_y},
      {"momentum_x", &MdSeries::momentum_x},
      {"momentum_y", &MdSeries::momentum_y},
      {"pressure_xx", &MdSeries::pressure_xx},
      {"pressure_yy", &MdSeries::pressure_yy},
      {"pressure_stderr", &MdSeries::pressure_stderr},
      {"compressibility", &MdSeries::compressibility},
      {"mode_energy_fraction", &MdSeries::mode_energy_fraction},
      {"structure_factor", &MdSeries::structure_factor}};
  return columns;
}

namespace {

// One sample of the box at time t: its energies, pressure and long-wave modes, and the engine's
// own values, appended to the time series (one row of md_series_columns()).
void append_sample(MdSeries& s, double t, const BoxEnergies& e, const BoxPressure& pressure,
                   const BoxModes& box, const EngineValues& own) {
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
  s.pressure_xx.push_back(pressure.xx);
  s.pressure_yy.push_back(pressure.yy);
  s.pressure_stderr.push_back(pressure.mean_stderr);
  s.compressibility.push_back(pressure.compressibility());
  s.mode_energy_fraction.push_back(box.energy_fraction);
  s.structure_factor.push_back(box.structure_factor);
  if (s.engine.empty()) {
    for (const auto& [name, value] : own) s.engine.push_back({name, {}});
  }
  for (std::size_t i = 0; i < own.size(); ++i) s.engine[i].second.push_back(own[i].second);
}

// The moments of the particles on every rank, reduced over the engine's ranks: the bins' sums,
// the box's energies and pressure, and its long-wave modes.
struct BoxSample {
  Moments moments;
  BoxEnergies energies;
  BoxPressure pressure;
  BoxModes modes;
};

BoxSample sample_box(const CoarseGrainer& grainer, ParticleEngine& engine, double lx, double ly) {
  const LocalVirial w = engine.local_virial();
  const LocalParticles p = engine.local_particles();
  const bool virial = w.xx.size() == std::size_t(p.count) && w.yy.size() == w.xx.size() &&
                      !(p.count > 0 && w.xx.empty());
  const bool contact_flux = virial && w.energy_flux_x.size() == w.xx.size();
  Moments m(grainer.grid().bins);
  // A non-finite particle on one rank (the coarse-grainer refuses it) stops every rank here,
  // with that rank's reason, rather than leaving the others waiting in the sums below.
  on_every_rank(engine.comm(), [&] {
    grainer.accumulate(m, p.x, p.v, p.mass, p.count, 3, virial ? w.xx.data() : nullptr,
                       virial ? w.yy.data() : nullptr,
                       contact_flux ? w.energy_flux_x.data() : nullptr);
  });
  if (virial) m.virial_particles = m.particles;  // also a rank without particles
  if (contact_flux) m.contact_flux_particles = m.particles;
  allreduce(m, engine.comm());
  BoxModeSums modes = box_mode_sums(p.x, p.v, p.mass, p.count, lx, ly);
  allreduce(modes, engine.comm());
  const BoxEnergies e = grainer.energies(m);
  const BoxPressure pressure = grainer.pressure(m);
  return {std::move(m), e, pressure, box_modes(modes)};
}

// The run's t = 0 particles drawn from the scene's fields: each rank draws the strips of its own
// part of the box; the strips' momenta are shared.
void place_sampled_particles(const MdRunSpec& spec, ParticleEngine& engine) {
  const MPI_Comm comm = engine.comm();
  engine.set_up_sampled([&](double x_lo, double x_hi) {
    return sample_particles_in(spec.scene, spec.fields, spec.seed, x_lo, x_hi,
                               [comm](std::vector<double>& momenta) {
                                 MPI_Allreduce(MPI_IN_PLACE, momenta.data(), int(momenta.size()),
                                               MPI_DOUBLE, MPI_MAX, comm);
                               });
  });
}

// The box energies of a sample as H5MD observables (under the HDF5 lock: members may write
// from several threads).
void append_energy_observables(H5mdWriter& h5md, long long step, double t, const BoxEnergies& e) {
  const std::lock_guard<std::recursive_mutex> lock(h5::library_mutex());
  h5md.append_observable("thermal_energy", step, t, e.thermal);
  h5md.append_observable("kinetic_energy_x", step, t, e.kinetic_macro_x);
  h5md.append_observable("kinetic_energy_y", step, t, e.kinetic_macro_y);
  h5md.append_observable("total_energy", step, t, e.kinetic_total);
}

}  // namespace

MdRunResult run_md(const MdRunSpec& spec, ParticleEngine& engine,
                   const std::function<void(const MdProgress&)>& progress,
                   const MdCheckpoints& checkpoints) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const MdRunState* resume = checkpoints.resume_from;
  const double wall_before = resume ? resume->so_far.wall_seconds : 0.0;
  auto wall = [&] {
    return wall_before + std::chrono::duration<double>(clock::now() - start).count();
  };
  const std::string problem = scene_problem(spec.scene);
  if (!problem.empty()) throw std::invalid_argument(problem);
  if (!(spec.t_end > 0.0) || !(spec.sample_interval > 0.0)) {
    throw std::invalid_argument("md.t_end and md.sample_interval must be > 0");
  }

  MpiEnvironment::ensure();
  const ParticleScene& scene = spec.scene;
  const double lx = scene.box_length, ly = scene.box_width;
  CoarseGrainer grainer({-0.5 * lx, lx, -0.5 * ly, ly, spec.bins, spec.kernel, spec.kernel_width});

  MdRunResult result;
  double t = 0.0;
  size_t next_output = 0;
  double next_frame = 0.0;
  if (resume) {
    engine.restore_state(resume->engine);
    result = resume->so_far;
    t = resume->t;
    next_output = resume->next_output;
    next_frame = resume->next_frame;
  } else {
    result.fields = fields::FieldSeries::on_bins(-0.5 * lx, lx, spec.bins);
    place_sampled_particles(spec, engine);
  }
  int rank = 0;
  MPI_Comm_rank(engine.comm(), &rank);

  // Particle output in H5MD layout: every rank writes its block of the frames, rank 0 the
  // observables (h5md_frames.hpp).
  std::unique_ptr<H5mdFrames, CloseFramesLocked> frames;
  if (!spec.h5md_path.empty()) {
    const std::lock_guard<std::recursive_mutex> lock(h5::library_mutex());
    frames.reset(new H5mdFrames(
        H5mdFrames::Spec{spec.h5md_path, scene.particles, lx, ly, spec.creator_version},
        engine.comm(), resume ? engine.frame_step() : -1));
  }
  H5mdWriter* h5md = frames ? frames->observables() : nullptr;
  // The sample, frame and output clocks are sums kept apart, so a frame or an output time due
  // with a sample may differ from it by rounding; such times are one stop, with one
  // observation. A stop of its own would be a segment without an event (the event-driven
  // engine has no time step): the same step twice in the H5MD observables, and a sample of a
  // vanishing interval.
  auto due_by = [&](double due, double time) {
    return due <= time + 0.5 * engine.time_resolution() || fields::same_time(time, due);
  };
  auto write_frame = [&](double time) {
    if (spec.snapshot_interval <= 0.0 || !frames) return;
    if (!due_by(next_frame, time)) return;
    const std::lock_guard<std::recursive_mutex> lock(h5::library_mutex());
    frames->append_frame(engine.frame_step(), time, engine);
    next_frame += spec.snapshot_interval;
  };

  auto observe = [&](bool snapshot) {
    const BoxSample b = sample_box(grainer, engine, lx, ly);
    const BoxEnergies& e = b.energies;
    append_sample(result.series, t, e, b.pressure, b.modes, engine.series_values());
    if (snapshot) {
      fields::FieldSnapshot f = grainer.fields(b.moments);
      f.t = t;
      f.label = "output";
      result.fields.snapshots.push_back(std::move(f));
    }
    if (h5md) append_energy_observables(*h5md, engine.frame_step(), t, e);
    write_frame(t);
  };
  const auto& outputs = spec.output_times;
  if (!resume) {
    while (next_output < outputs.size() && outputs[next_output] <= 0.0) ++next_output;
    observe(!outputs.empty() && outputs.front() <= 0.0);
  }
  // The decision is rank 0's, so that every rank saves at the same sample.
  auto checkpoint_if_due = [&] {
    if (!checkpoints.save) return;
    int due = (rank == 0 && checkpoints.due && checkpoints.due()) ? 1 : 0;
    MPI_Bcast(&due, 1, MPI_INT, 0, engine.comm());
    if (!due) return;
    MdRunState state;
    state.t = t;
    state.next_output = next_output;
    state.next_frame = next_frame;
    state.engine = engine.save_state(true);
    state.so_far = result;
    state.so_far.status = "running";
    state.so_far.wall_seconds = wall();
    checkpoints.save(state);  // every rank: each may hold its own block of the particles
  };

  // Inside a long segment the engine reports the time it has reached: the checkpoints (if the
  // engine can save a state there) and the progress callback (the app's progress lines and its
  // stop at a signal) are looked at there too, the checkpoint first, so that a signal inside a
  // segment leaves a checkpoint of that moment.
  struct WithinSegment {
    ParticleEngine& engine;
    ~WithinSegment() { engine.set_within_segment({}); }
  } within{engine};
  const bool save_within = checkpoints.save && engine.saves_within_segment();
  if (progress || save_within) {
    engine.set_within_segment([&](double now) {
      if (save_within) checkpoint_if_due();
      if (progress)
        progress({now, spec.t_end, result.series.T.empty() ? 0.0 : result.series.T.back(), wall(),
                  engine.steps(), engine.cost()});
    });
  }
  while (t < spec.t_end - 0.5 * engine.time_resolution()) {  // samples land on the nearest step
    // Next stop: a sample time or an output time, whichever comes first.
    double target = std::min(spec.t_end, t + spec.sample_interval);
    if (spec.snapshot_interval > 0.0 && !spec.h5md_path.empty() &&
        !fields::same_time(target, next_frame))
      target = std::min(target, next_frame);
    bool snapshot = false;
    if (next_output < outputs.size() && due_by(outputs[next_output], target)) {
      target = outputs[next_output];
      snapshot = true;
    }
    t = engine.advance_to(target);
    result.steps = engine.steps();
    if (snapshot) ++next_output;
    // A snapshot time passed without its snapshot: two output times within one engine step.
    if (next_output < outputs.size() && outputs[next_output] < t - 0.5 * engine.time_resolution()) {
      throw std::runtime_error(
          "md.output_times: the snapshot at t = " + std::to_string(outputs[next_output]) +
          " lies within one engine step of the previous one (the step is " +
          std::to_string(engine.time_resolution()) + ")");
    }
    observe(snapshot);
    engine.between_segments();
    checkpoint_if_due();
    if (progress)
      progress({t, spec.t_end, result.series.T.back(), wall(), result.steps, engine.cost()});
  }
  result.status = "ok";
  result.stop_reason = "end time reached";
  result.wall_seconds = wall();
  return result;
}

}  // namespace granvv::md
