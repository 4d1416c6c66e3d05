#include "support/elastic_gas.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <limits>

#include "hydro/enskog_factors.hpp"
#include "hydro/initial_conditions.hpp"
#include "md_bridge/event_driven_engine.hpp"
#include "md_bridge/hard_disk_theory.hpp"
#include "md_bridge/mpi_environment.hpp"
#include "md_bridge/particle_sampler.hpp"

namespace granvv::testing {

namespace {

struct Totals {
  double energy = 0.0, px = 0.0, py = 0.0;
};

Totals totals(const md::ParticleFrame& f) {
  Totals g;
  for (std::size_t i = 0; i < f.v.size(); i += 3) {
    g.energy += 0.5 * (f.v[i] * f.v[i] + f.v[i + 1] * f.v[i + 1]);
    g.px += f.v[i];
    g.py += f.v[i + 1];
  }
  return g;
}

}  // namespace

md::EventDrivenOptions event_driven_options(const md::ParticleScene& scene, int bins) {
  md::EventDrivenOptions o;
  o.restitution = scene.restitution;
  o.box_length = scene.box_length;
  o.box_width = scene.box_width;
  o.particles = scene.particles;
  o.collapse.collapse_speed = 0.01;
  o.max_collision_rate = 1000.0;
  o.virial_bins = bins;
  o.comm = MPI_COMM_SELF;
  return o;
}

ElasticGasDrift run_elastic_gas(double area_fraction, long long collisions) {
  md::MpiEnvironment::ensure();
  const md::ParticleScene scene = md::scene_from_particles(2000, area_fraction, 40.0, 1.0);
  md::EventDrivenEngine engine(event_driven_options(scene));
  engine.set_up(md::sample_particles(scene, hydro::uniform_fields(), 3));
  const Totals start = totals(engine.gather_frame());
  const double nu = 2.0 * std::sqrt(M_PI) * scene.number_density() *
                    hydro::enskog::chi(area_fraction);  // per disk, at T = 1
  const double segment = double(collisions) / 20.0 / (0.5 * double(scene.particles) * nu);
  ElasticGasDrift drift;
  drift.closest = std::numeric_limits<double>::infinity();
  double t = 0.0;
  while (engine.collisions() < collisions) {
    t = engine.advance_to(t + segment);
    drift.closest = std::min(drift.closest, engine.smallest_separation());
  }
  const Totals end = totals(engine.gather_frame());
  drift.energy = std::abs(end.energy / start.energy - 1.0);
  drift.momentum = std::hypot(end.px - start.px, end.py - start.py) / double(scene.particles);
  drift.collisions = engine.collisions();
  drift.changed = engine.collisions_changed();
  return drift;
}

}  // namespace granvv::testing

namespace granvv::testing {

MeasuredCompressibility measure_compressibility(double phi, long long disks, unsigned seed,
                                                double relax, double per_block, int blocks) {
  const std::clock_t cpu_start = std::clock();
  md::MpiEnvironment::ensure();
  const double side = std::sqrt(double(disks) * M_PI / (4.0 * phi));
  const md::ParticleScene scene = md::scene_from_particles(disks, phi, side, 1.0);
  md::EventDrivenEngine engine(event_driven_options(scene));
  engine.set_up(md::sample_particles(scene, hydro::uniform_fields(), seed));
  const Totals g = totals(engine.gather_frame());
  const double T = g.energy / double(disks - 1);
  const double n = scene.number_density();
  const double nu = md::enskog_collision_frequency(n, phi, T);
  double t = engine.advance_to(relax / nu);
  const long long before = engine.collisions();
  MeasuredCompressibility m;
  double sum = 0.0, squares = 0.0;
  for (int b = 0; b < blocks; ++b) {
    t = engine.advance_to(t + per_block / nu);
    const double z = 1.0 + engine.collision_virial().box / (n * T);
    sum += z;
    squares += z * z;
  }
  m.blocks = blocks;
  m.z = sum / blocks;
  m.error =
      blocks > 1 ? std::sqrt(std::max(0.0, squares / blocks - m.z * m.z) / (blocks - 1)) : 0.0;
  m.collisions = engine.collisions() - before;
  m.cpu_seconds = double(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  return m;
}

}  // namespace granvv::testing
