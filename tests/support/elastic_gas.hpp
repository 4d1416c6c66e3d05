#pragma once
// An elastic gas of hard disks run through the event-driven engine for a number of collisions
// (tests/test_event_driven_engine.cpp, tests/slow_event_driven.cpp): how well it conserves.
namespace granvv::testing {

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
