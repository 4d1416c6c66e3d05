#include "md_bridge/particle_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>

namespace granvv::md {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kProfilePoints = 8192;  // tabulation of n(x) for the inverse CDF
constexpr int kMaxTries = 10000;

class Uniform {
 public:
  explicit Uniform(std::uint64_t seed) : rng_(seed) {}
  double operator()() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }
  // Standard normal by Box-Muller (portable: no std::normal_distribution).
  double normal() {
    double u = (*this)();
    while (u <= 0.0) u = (*this)();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * kPi * (*this)());
  }

 private:
  std::mt19937_64 rng_;
};

// Occupancy grid of cell size >= sigma: an overlap can only be with the 3 x 3 neighbourhood.
class OverlapGrid {
 public:
  OverlapGrid(double lx, double ly) : lx_(lx), ly_(ly) {
    nx_ = std::max(1, int(lx)), ny_ = std::max(1, int(ly));
    cells_.resize(size_t(nx_) * ny_);
  }
  bool free(double x, double y, const std::vector<double>& pos) const {
    const int cx = cell(x + 0.5 * lx_, lx_, nx_), cy = cell(y + 0.5 * ly_, ly_, ny_);
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int j : cells_[index((cx + dx + nx_) % nx_, (cy + dy + ny_) % ny_)]) {
          double ddx = pos[3 * j] - x, ddy = pos[3 * j + 1] - y;
          ddx -= lx_ * std::round(ddx / lx_);
          ddy -= ly_ * std::round(ddy / ly_);
          if (ddx * ddx + ddy * ddy < 1.0) return false;  // centres closer than sigma
        }
      }
    }
    return true;
  }
  void add(double x, double y, int id) {
    cells_[index(cell(x + 0.5 * lx_, lx_, nx_), cell(y + 0.5 * ly_, ly_, ny_))].push_back(id);
  }

 private:
  static int cell(double u, double l, int n) { return std::min(n - 1, int(u / l * n)); }
  size_t index(int cx, int cy) const { return size_t(cy) * nx_ + cx; }
  double lx_, ly_;
  int nx_, ny_;
  std::vector<std::vector<int>> cells_;
};

}  // namespace

ParticleSample sample_particles(const ParticleScene& scene, const hydro::InitialFields& f,
                                std::uint64_t seed) {
  const long long n = scene.particles;
  const double lx = scene.box_length, ly = scene.box_width;
  // Cumulative mass of the scaled profile on [-1/2, 1/2) (trapezoid rule), to invert.
  std::vector<double> cdf(kProfilePoints + 1, 0.0);
  double n_max = 0.0, momentum_x = 0.0, momentum_y = 0.0;
  for (int i = 0; i < kProfilePoints; ++i) {
    const double xa = -0.5 + double(i) / kProfilePoints, xb = xa + 1.0 / kProfilePoints;
    const double xm = 0.5 * (xa + xb);
    const double na = f.n(xa), nb = f.n(xb), nm = f.n(xm);
    n_max = std::max({n_max, na, nb, nm});
    if (!(na >= 0.0 && nb >= 0.0)) {
      throw std::invalid_argument("initial density is negative near x = " + std::to_string(xa));
    }
    cdf[i + 1] = cdf[i] + 0.5 * (na + nb) / kProfilePoints;
    momentum_x += nm * f.v(xm) / kProfilePoints;
    momentum_y += nm * (f.vy ? f.vy(xm) : 0.0) / kProfilePoints;
  }
  const double total = cdf.back();
  if (n_max * scene.area_fraction > 0.5) {
    std::ostringstream why;
    why << "the initial density peak n/n0 = " << n_max << " at area fraction "
        << scene.area_fraction << " gives a local area fraction " << n_max * scene.area_fraction
        << " > 0.5: disks cannot be placed without overlap";
    throw std::invalid_argument(why.str());
  }

  Uniform uniform(seed);
  ParticleSample s;
  s.x.reserve(3 * n);
  s.v.reserve(3 * n);
  OverlapGrid grid(lx, ly);
  for (long long p = 0; p < n; ++p) {
    bool placed = false;
    for (int attempt = 0; attempt < kMaxTries && !placed; ++attempt) {
      const double target = uniform() * total;
      const auto it = std::upper_bound(cdf.begin(), cdf.end(), target);
      const int i = std::clamp(int(it - cdf.begin()) - 1, 0, kProfilePoints - 1);
      const double frac = cdf[i + 1] > cdf[i] ? (target - cdf[i]) / (cdf[i + 1] - cdf[i]) : 0.5;
      const double xs = -0.5 + (i + frac) / kProfilePoints;  // scaled position
      const double x = scene.md_position(xs), y = (uniform() - 0.5) * ly;
      if (!grid.free(x, y, s.x)) continue;
      grid.add(x, y, int(p));
      s.x.insert(s.x.end(), {x, y, 0.0});
      const double thermal = std::sqrt(std::max(f.T(xs), 0.0));  // T = m <c_x^2> per component
      s.v.insert(s.v.end(), {f.v(xs) + thermal * uniform.normal(),
                             (f.vy ? f.vy(xs) : 0.0) + thermal * uniform.normal(), 0.0});
      placed = true;
    }
    if (!placed) {
      throw std::invalid_argument("no free spot for particle " + std::to_string(p) + " of " +
                                  std::to_string(n) + " after " + std::to_string(kMaxTries) +
                                  " tries: the scene is too dense to place without overlap");
    }
  }
  // Total momentum as the fields carry it: N <v> with <v> = int n v dx / int n dx.
  double px = 0.0, py = 0.0;
  for (long long p = 0; p < n; ++p) px += s.v[3 * p], py += s.v[3 * p + 1];
  const double shift_x = momentum_x / total - px / n, shift_y = momentum_y / total - py / n;
  for (long long p = 0; p < n; ++p) s.v[3 * p] += shift_x, s.v[3 * p + 1] += shift_y;
  return s;
}

}  // namespace granvv::md
