#pragma once
// The collisions a hard-disk run will make, counted over the densities the scene will reach
// (docs/physics.md §10, "The collision forecast"). Each disk collides at Enskog's frequency
// nu = 2 sqrt(pi) n chi(phi) sqrt(T) at the area fraction phi around it, and the gas cools by
// Haff's law T = T_h / (1 + t/t0)^2, so a share w of N disks held at phi from t_a to t_b makes
//   (w N / 2) 2 sqrt(pi) n chi(phi) sqrt(T_h) t0 ln((1 + t_b/t0) / (1 + t_a/t0))
// collisions (N nu (t_b - t_a) / 2 without cooling). A clustering scene gathers its disks into
// packings near close packing after the onset that its linear theory or its initial flow gives;
// the packings' share grows as the flow by inertia of a sine mode gathers its mass, and the TC
// rule holds their collision frequency near 1 / (2 t_c).
#include <limits>
#include <vector>

#include "md_bridge/particle_scene.hpp"

namespace granvv::md {

// Random close packing of equal disks (Berryman, Phys. Rev. A 27, 1053 (1983): 0.82): the area
// fraction of the packings a clustering gas of hard disks makes.
inline constexpr double kPackingAreaFraction = 0.82;

// A share of the disks at one area fraction. `frequency` > 0 holds their collision frequency per
// disk at that value where Enskog's at the cooling temperature would be higher (a packing held
// by the TC rule, below); 0 leaves Enskog's.
struct DensityPhase {
  double mass_fraction = 1.0;
  double area_fraction = 0.0;
  double frequency_cap = 0.0;
};

// The phases that hold from `from` to `until` (MD time).
struct DensityStage {
  double from = 0.0;
  double until = std::numeric_limits<double>::infinity();
  std::vector<DensityPhase> phases;
};

// Haff's law T(t) = temperature / (1 + t/haff_time)^2; haff_time infinite or <= 0: no cooling.
struct Cooling {
  double temperature = 1.0;
  double haff_time = std::numeric_limits<double>::infinity();
};

// The collisions N disks make from t = 0 to t (MD time) over the stages (their parts before t),
// each phase at Enskog's frequency (or its cap) with the temperature of `cooling`.
double forecast_collisions(double particles, const std::vector<DensityStage>& stages,
                           const Cooling& cooling, double t);

// What sets where a scene's disks will be.
struct ClusteringInputs {
  ParticleScene scene;
  double t_end = 0.0;  // MD time
  // The initial density profile n/n0 sampled at equispaced points of the box (empty: uniform):
  // where the disks are before clusters form.
  std::vector<double> initial_density;
  // The flow by inertia of the initial velocity profile collapses at this MD time
  // (hydro/flow_by_inertia.hpp; +inf: it does not).
  double profile_collapse_time = std::numeric_limits<double>::infinity();
  // md.contact_duration: the TC rule's t_c (0: off).
  double contact_duration = 0.0;
};

// Clustering onset from the linear theory (hydro/linear_stability.hpp): the fastest-growing
// clustering mode of the box, in the collision clock s with the hydro's Haff time t0, grows
// from the density noise of N disks (relative amplitude 2/sqrt(N)) to 1 at s* = ln(sqrt(N)/2) /
// lambda_max, t* = t0 (e^{s*/t0} - 1). MD time; +inf when no mode grows.
double linear_clustering_onset_md(const ParticleScene& scene);

// The share of the mass a sine mode's flow by inertia has gathered into its cluster by t, with
// tau the collapse time: the labels xi with 2 pi xi / sin(2 pi xi) <= t / tau (0 before tau,
// 1/2 at t = pi tau / 2, tending to 1).
double gathered_mass_fraction(double t, double tau);

// The stages of a scene: the initial profile's densities until the onset (the earlier of the
// linear theory's and the initial flow's collapse, which counts only in a scene with an unstable
// clustering mode: elsewhere pressure stops it), then in each of 48 stretches of log time a
// growing share w (gathered_mass_fraction at the stretch's middle) of the disks in packings at
// kPackingAreaFraction, the rest a gas filling the box's other area. A freely cooling packing
// makes per e-fold of time the collisions the gas makes (Haff's law gives every density the same
// nu t0 = 4 / (1 - r^2)), so packings count only where the TC rule (t_c > 0) holds them warm: a
// loaded packing stops cooling once its disks collide about once per 2 t_c (2 nu t_c = 1: then
// most impacts fall within t_c of a partner's previous one, docs/physics.md §10). Such a packing
// collides at Enskog's frequency at the gas's temperature, at most 1 / (2 t_c). Without the TC
// rule the initial profile's stage lasts to t_end.
std::vector<DensityStage> forecast_density_stages(const ClusteringInputs& inputs);

}  // namespace granvv::md
