#include "md_bridge/particle_work.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "md_bridge/collision_forecast.hpp"

namespace granvv::md {

namespace {

constexpr const char* kWho = "the work estimate";

bool cools(double haff_time) {
  return std::isfinite(haff_time) && haff_time > 0.0;
}

}  // namespace

ParticleWorkEstimate lammps_work(const ParticleWorkQuestion& q) {
  const double n = double(q.scene.particles);
  const double u =
      2.0 * (std::sqrt(2.0 * q.hottest_temperature * std::log(std::max(n, 2.0))) + q.fastest_flow);
  const double dt0 =
      3.14159265358979323846 * required_setting(q.settings, "md.max_overlap", kWho) / u /
      double(std::lround(required_setting(q.settings, "md.steps_per_contact", kWho)));
  const bool adaptive = required_setting(q.settings, "md.adaptive_stiffness", kWho) != 0.0;
  const bool haff = adaptive && cools(q.haff_time);
  const double t0 = q.haff_time;
  auto steps = [=](double t) { return haff ? t0 / dt0 * std::log1p(t / t0) : t / dt0; };
  ParticleWorkEstimate w;
  w.work = n * q.ensemble * steps(q.t_end);
  w.member_work_until = [=](double t) { return n * steps(t); };
  w.limit = kMaxAtomSteps;
  w.unit = "atom-steps";
  w.keys = {"md.t_end", "md.ensemble", "md.particles", "md.steps_per_contact", "md.max_overlap"};
  w.first_step = dt0;
  w.rate = kLammpsAtomStepsPerCoreSecond;
  w.divides_over_ranks = true;
  w.bytes_fixed = kLammpsBytesFixed;
  w.bytes_per_disk = kLammpsBytesPerDisk;
  // The step at the end of the run, where adaptive stiffness has made it longest.
  w.last_step = haff ? dt0 * (1.0 + q.t_end / q.haff_time) : dt0;
  return w;
}

ParticleWorkEstimate event_driven_work(const ParticleWorkQuestion& q) {
  const double n = double(q.scene.particles);
  ClusteringInputs inputs;
  inputs.scene = q.scene;
  inputs.t_end = q.t_end;
  inputs.initial_density = q.initial_density;
  inputs.profile_collapse_time = q.profile_collapse_time;
  inputs.contact_duration = required_setting(q.settings, "md.contact_duration", kWho);
  const std::vector<DensityStage> stages = forecast_density_stages(inputs);
  const Cooling cooling{q.hottest_temperature, cools(q.haff_time) ? q.haff_time : 0.0};
  ParticleWorkEstimate w;
  w.member_work_until = [=](double t) { return forecast_collisions(n, stages, cooling, t); };
  w.work = q.ensemble * w.member_work_until(q.t_end);
  w.limit = kMaxCollisions;
  w.unit = "collisions";
  w.keys = {"md.t_end", "md.ensemble", "md.particles", "md.area_fraction"};
  w.rate = kEventDrivenCollisionsPerCoreSecond;
  w.bytes_fixed = kEventDrivenBytesFixed;
  w.bytes_per_disk = kEventDrivenBytesPerDisk;
  return w;
}

}  // namespace granvv::md
