// Speed of the event-driven particle engine (docs/physics.md §10, docs/md_benchmarks.md): an
// elastic gas of 10^4 hard disks at phi = 0.05 on one core, in collisions/s and events/s (the
// target: >= 1e6 collisions/s), and the same gas at phi = 0.3. Run: build/granvv_bench
// --benchmark_filter=EventDriven.
#include <benchmark/benchmark.h>

#include "hydro/initial_conditions.hpp"
#include "md_bridge/event_driven_engine.hpp"
#include "md_bridge/mpi_environment.hpp"
#include "md_bridge/particle_sampler.hpp"

namespace {

using namespace granvv::md;

void elastic_gas(benchmark::State& state, double area_fraction) {
  MpiEnvironment::ensure();
  const ParticleScene scene = scene_from_particles(10000, area_fraction, 100.0, 1.0);
  EventDrivenOptions o;
  o.restitution = 1.0;
  o.box_length = scene.box_length;
  o.box_width = scene.box_width;
  o.particles = scene.particles;
  o.collapse.collapse_speed = 0.0;
  o.max_collision_rate = 1e6;
  o.comm = MPI_COMM_SELF;
  EventDrivenEngine engine(o);
  engine.set_up(sample_particles(scene, granvv::hydro::uniform_fields(), 1));
  engine.advance_to(20.0);  // relaxed from the sample
  // About 1e5 collisions per iteration: N nu / 2 per unit time, nu from Enskog.
  const double nu = 2.0 * 1.7724538509 * scene.number_density() * enskog_chi(area_fraction);
  const double step = 2e5 / (scene.particles * nu);
  double t = engine.time();
  long long collisions = 0, events = 0;
  for (auto _ : state) {
    const long long c0 = engine.collisions(), e0 = engine.steps();
    t = engine.advance_to(t + step);
    collisions += engine.collisions() - c0;
    events += engine.steps() - e0;
  }
  state.counters["collisions_per_s"] =
      benchmark::Counter(double(collisions), benchmark::Counter::kIsRate);
  state.counters["events_per_s"] = benchmark::Counter(double(events), benchmark::Counter::kIsRate);
  state.counters["events_per_collision"] = double(events) / double(collisions);
}

void EventDrivenElasticDilute(benchmark::State& state) {
  elastic_gas(state, 0.05);
}
void EventDrivenElasticDense(benchmark::State& state) {
  elastic_gas(state, 0.3);
}

BENCHMARK(EventDrivenElasticDilute)->Unit(benchmark::kMillisecond)->MinTime(3.0);
BENCHMARK(EventDrivenElasticDense)->Unit(benchmark::kMillisecond)->MinTime(3.0);

}  // namespace
