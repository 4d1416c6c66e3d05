#include "md_bridge/box_modes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "fields/constants.hpp"
#include "hydro/haff.hpp"
#include "hydro/linear_stability.hpp"

namespace granvv::md {

const std::vector<std::pair<int, int>>& box_mode_wave_vectors() {
  static const std::vector<std::pair<int, int>> k = {{1, 0},  {0, 1}, {1, 1},
                                                     {1, -1}, {2, 0}, {0, 2}};
  return k;
}

BoxModeSums box_mode_sums(const double* x, const double* v, const double* mass, int n, double lx,
                          double ly) {
  const auto& waves = box_mode_wave_vectors();
  BoxModeSums s;
  s.mode.assign(waves.size(), {0.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  for (int p = 0; p < n; ++p) {
    const double* r = x + 3 * static_cast<std::ptrdiff_t>(p);
    const double* c = v + 3 * static_cast<std::ptrdiff_t>(p);
    const double m = mass ? mass[p] : 1.0;
    const double c2 = c[0] * c[0] + c[1] * c[1];
    s.mass += m;
    s.kinetic2 += m * c2;
    s.noise += m * m * c2;
    for (std::size_t w = 0; w < waves.size(); ++w) {
      const double phase = kTwoPi * (waves[w].first * r[0] / lx + waves[w].second * r[1] / ly);
      const double re = std::cos(phase), im = -std::sin(phase);
      auto& a = s.mode[w];
      a[0] += m * c[0] * re, a[1] += m * c[0] * im;
      a[2] += m * c[1] * re, a[3] += m * c[1] * im;
      a[4] += re, a[5] += im;
    }
  }
  s.particles = n;
  return s;
}

void allreduce(BoxModeSums& sums, MPI_Comm comm) {
  std::vector<double> buffer;
  for (const auto& a : sums.mode) buffer.insert(buffer.end(), a.begin(), a.end());
  for (double d : {sums.mass, sums.kinetic2, sums.noise, sums.particles}) buffer.push_back(d);
  const int rc = MPI_Allreduce(MPI_IN_PLACE, buffer.data(), static_cast<int>(buffer.size()),
                               MPI_DOUBLE, MPI_SUM, comm);
  if (rc != MPI_SUCCESS)
    throw std::runtime_error("box modes: MPI_Allreduce failed (code " + std::to_string(rc) + ")");
  std::size_t i = 0;
  for (auto& a : sums.mode) {
    for (double& d : a) d = buffer[i++];
  }
  sums.mass = buffer[i++];
  sums.kinetic2 = buffer[i++];
  sums.noise = buffer[i++];
  sums.particles = buffer[i];
}

BoxModes box_modes(const BoxModeSums& s) {
  BoxModes out;
  if (!(s.mass > 0.0 && s.kinetic2 > 0.0 && s.particles > 0.0)) {
    out.energy_fraction = out.structure_factor = std::numeric_limits<double>::quiet_NaN();
    return out;
  }
  double flow = 0.0, density = 0.0;
  for (const auto& a : s.mode) {
    flow += (a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3] - s.noise) / s.mass;
    density += (a[4] * a[4] + a[5] * a[5]) / s.particles;
  }
  out.energy_fraction = flow / (0.5 * s.kinetic2);
  out.structure_factor = density / double(s.mode.size());
  return out;
}

double linear_mode_onset_md(const ParticleScene& scene, double threshold) {
  const double inf = std::numeric_limits<double>::infinity();
  if (!(scene.restitution < 1.0)) return inf;
  const hydro::Physics physics = scene.physics();
  const double shear = hydro::shear_rate(physics, 1);
  const double longitudinal = hydro::hcs_modes(physics, 1)[0].rate.real();
  // Wave vectors of the lowest |k| = 2 pi / Lx: (1, 0), and (0, 1) too in a box square to 1 %
  // (the scenes' Lx follows from N, phi and Ly: md_cooling_sweep's is 125.66 for Ly = 125).
  const double pairs = std::abs(scene.box_width / scene.box_length - 1.0) < 0.01 ? 2.0 : 1.0;
  const double N = double(scene.particles);
  const double t0 = hydro::haff_time_scale(physics);
  double onset = inf;
  // Shear: one polarisation (the velocity across k); longitudinal: the one along k.
  for (double rate : {shear, longitudinal}) {
    const double f0 = pairs / N;
    if (!(rate > 0.0) || !(threshold > f0)) continue;
    const double s = std::log(threshold / f0) / (2.0 * rate);
    onset = std::min(onset, t0 * std::expm1(s / t0));
  }
  return std::isfinite(onset) ? scene.md_time(onset) : inf;
}

}  // namespace granvv::md
