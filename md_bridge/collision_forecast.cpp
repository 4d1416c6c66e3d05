#include "md_bridge/collision_forecast.hpp"

#include <algorithm>
#include <cmath>

#include "fields/constants.hpp"
#include "hydro/haff.hpp"
#include "hydro/linear_stability.hpp"
#include "md_bridge/hard_disk_theory.hpp"

namespace granvv::md {

namespace {

// Stretches of log time over which the packings' share is held constant: w changes by a few
// per cent of itself from one to the next.
constexpr int kClusterStretches = 48;

bool cools(double haff_time) {
  return std::isfinite(haff_time) && haff_time > 0.0;
}

// Integral of sqrt(T(t)/T_h) from a to b.
double thermal_clock(double a, double b, double haff_time) {
  if (!(b > a)) return 0.0;
  return cools(haff_time) ? haff_time * std::log((haff_time + b) / (haff_time + a)) : b - a;
}

// Number density n sigma^2 of disks at area fraction phi.
double number_density_at(double phi) {
  return 4.0 * phi / kPi;
}

}  // namespace

double forecast_collisions(double particles, const std::vector<DensityStage>& stages,
                           const Cooling& cooling, double t) {
  double per_disk = 0.0;  // collisions per disk, each collision counted for both disks
  for (const DensityStage& stage : stages) {
    const double a = stage.from, b = std::min(stage.until, t);
    if (!(b > a)) continue;
    for (const DensityPhase& p : stage.phases) {
      if (!(p.mass_fraction > 0.0)) continue;
      const double enskog = enskog_collision_frequency(number_density_at(p.area_fraction),
                                                       p.area_fraction, cooling.temperature) *
                            thermal_clock(a, b, cooling.haff_time);
      // A capped phase collides at Enskog's frequency while that is below the cap, then at the
      // cap: nu(t) = nu_h / (1 + t/t0) reaches it at t_cap.
      double held = enskog;
      if (p.frequency_cap > 0.0) {
        const double nu_h = enskog_collision_frequency(number_density_at(p.area_fraction),
                                                       p.area_fraction, cooling.temperature);
        const double t_cap = nu_h <= p.frequency_cap ? a
                             : cools(cooling.haff_time)
                                 ? cooling.haff_time * (nu_h / p.frequency_cap - 1.0)
                                 : b;
        const double capped_until = std::clamp(t_cap, a, b);
        held = p.frequency_cap * (capped_until - a) +
               nu_h * thermal_clock(capped_until, b, cooling.haff_time);
      }
      per_disk += p.mass_fraction * held;
    }
  }
  return 0.5 * particles * per_disk;
}

double linear_clustering_onset_md(const ParticleScene& scene) {
  const double inf = std::numeric_limits<double>::infinity();
  if (!(scene.restitution < 1.0) || scene.particles < 4) return inf;
  const hydro::Physics physics = scene.physics();
  const int modes = int(std::floor(hydro::clustering_cutoff_mode(physics)));
  double fastest = 0.0;
  for (int k = 1; k <= modes; ++k) {
    fastest = std::max(fastest, hydro::hcs_modes(physics, k)[0].rate.real());
  }
  if (!(fastest > 0.0)) return inf;
  const double s = std::log(0.5 * std::sqrt(double(scene.particles))) / fastest;
  const double t0 = hydro::haff_time_scale(physics);
  return scene.md_time(t0 * std::expm1(s / t0));
}

double gathered_mass_fraction(double t, double tau) {
  if (!(t > tau) || !std::isfinite(tau) || !(tau > 0.0)) return 0.0;
  // Solve x / sin x = t / tau for x in (0, pi): x / sin x rises from 1 to infinity there.
  const double ratio = t / tau;
  double lo = 0.0, hi = kPi;
  for (int i = 0; i < 100; ++i) {
    const double x = 0.5 * (lo + hi);
    if (x / std::sin(x) < ratio) {
      lo = x;
    } else {
      hi = x;
    }
  }
  return 0.5 * (lo + hi) / kPi;
}

std::vector<DensityStage> forecast_density_stages(const ClusteringInputs& in) {
  const double phi0 = in.scene.area_fraction;
  std::vector<DensityStage> stages;
  // The initial flow collapses by inertia only where pressure cannot stop it: in a scene whose
  // linear theory has clustering modes.
  const double linear = linear_clustering_onset_md(in.scene);
  const double onset = std::isfinite(linear) ? std::min(linear, in.profile_collapse_time) : linear;
  // Before the onset: the initial profile, each sample point's share of the disks at its density.
  DensityStage before{0.0, std::min(onset, in.t_end), {}};
  double mass = 0.0;
  for (double n : in.initial_density) mass += std::max(0.0, n);
  if (mass > 0.0) {
    for (double n : in.initial_density) {
      if (n > 0.0) before.phases.push_back({n / mass, std::min(phi0 * n, kPackingAreaFraction)});
    }
  } else {
    before.phases.push_back({1.0, phi0});
  }
  // A freely cooling packing costs what the gas does: Haff's law gives every density the same
  // nu t0 = 4 / (1 - r^2), so late in the run each disk makes about 2 / (1 - r^2) collisions per
  // e-fold of time wherever it is. Only a loaded packing held warm by the TC rule costs more.
  if (!(onset < in.t_end) || !(in.contact_duration > 0.0)) {
    before.until = in.t_end;
    stages.push_back(before);
    return stages;
  }
  stages.push_back(before);
  const double cap = 0.5 / in.contact_duration;
  const double step = std::log(in.t_end / onset) / kClusterStretches;
  for (int i = 0; i < kClusterStretches; ++i) {
    const double a = onset * std::exp(step * i);
    const double b = i + 1 == kClusterStretches ? in.t_end : onset * std::exp(step * (i + 1));
    const double w = gathered_mass_fraction(std::sqrt(a * b), onset);
    // The gas keeps the area the packings leave: (1 - w) phi0 / (1 - w phi0 / phi_c).
    const double gas_phi = (1.0 - w) * phi0 / (1.0 - w * phi0 / kPackingAreaFraction);
    stages.push_back({a, b, {{1.0 - w, gas_phi}, {w, kPackingAreaFraction, cap}}});
  }
  return stages;
}

}  // namespace granvv::md
