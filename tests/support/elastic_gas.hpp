#pragma once
#include "md_bridge/event_driven_engine.hpp"
#include "md_bridge/particle_scene.hpp"

// An elastic gas of hard disks run through the event-driven engine for a number of collisions
// (tests/test_event_driven_engine.cpp, tests/slow_event_driven.cpp): how well it conserves.
namespace granvv::testing {

// The event-driven engine for a scene on one rank, with the case schema's defaults of
// md.collapse_speed (0.01) and md.max_collision_rate (1000) and `bins` virial bins.
md::EventDrivenOptions event_driven_options(const md::ParticleScene& scene, int bins = 1);

struct ElasticGasDrift {
  double energy = 0.0;    // |E_end / E_start - 1|
  double momentum = 0.0;  // |P_end - P_start| per disk (unit thermal speed)
  double closest = 0.0;   // smallest centre distance at any of 20 samples (sigma = 1)
  long long collisions = 0;
  long long changed = 0;  // collisions the collapse rule changed (0 at r = 1)
};

// 2000 disks at this area fraction, sampled Maxwellian (seed 3), until `collisions` collisions.
ElasticGasDrift run_elastic_gas(double area_fraction, long long collisions);

}  // namespace granvv::testing

namespace granvv::testing {

// The compressibility factor Z = p / (n T) of an elastic hard-disk gas measured through the
// event-driven engine: 1 + the collision virial pressure (the engine's time average) over n T,
// with T = E / (N - 1) (zero total momentum: 2N - 2 degrees of freedom).
struct MeasuredCompressibility {
  double z = 0.0, error = 0.0;  // mean over the blocks and its standard error
  long long collisions = 0;     // in the measured blocks
  int blocks = 0;
  double cpu_seconds = 0.0;
};

// `disks` disks at area fraction phi in a square box, sampled uniformly (seed), relaxed for
// `relax` collisions per disk (Enskog's nu t), then measured over `blocks` blocks of
// `per_block` collisions per disk each.
MeasuredCompressibility measure_compressibility(double phi, long long disks, unsigned seed,
                                                double relax, double per_block, int blocks);

}  // namespace granvv::testing
