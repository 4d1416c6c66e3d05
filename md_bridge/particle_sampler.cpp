#include "md_bridge/particle_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>

#include "fields/constants.hpp"

namespace granvv::md {
namespace {

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

// Cumulative mass of the scaled profile on [-1/2, 1/2) (trapezoid rule), to invert, and its
// momentum.
struct Profile {
  std::vector<double> cdf;
  double total = 0.0, momentum_x = 0.0, momentum_y = 0.0;
  // The cumulative mass at scaled x (linear between the table's points, as its inverse).
  double mass_below(double xs) const {
    const double u = (xs + 0.5) * kProfilePoints;
    const int i = std::clamp(int(std::floor(u)), 0, kProfilePoints - 1);
    return cdf[i] + (u - i) * (cdf[i + 1] - cdf[i]);
  }
  // The scaled x of cumulative mass `target`.
  double position(double target) const {
    const auto it = std::upper_bound(cdf.begin(), cdf.end(), target);
    const int i = std::clamp(int(it - cdf.begin()) - 1, 0, kProfilePoints - 1);
    const double frac = cdf[i + 1] > cdf[i] ? (target - cdf[i]) / (cdf[i + 1] - cdf[i]) : 0.5;
    return -0.5 + (i + frac) / kProfilePoints;
  }
};

Profile tabulate(const ParticleScene& scene, const hydro::InitialFields& f) {
  Profile p;
  p.cdf.assign(kProfilePoints + 1, 0.0);
  double n_max = 0.0;
  for (int i = 0; i < kProfilePoints; ++i) {
    const double xa = -0.5 + double(i) / kProfilePoints, xb = xa + 1.0 / kProfilePoints;
    const double xm = 0.5 * (xa + xb);
    const double na = f.n(xa), nb = f.n(xb), nm = f.n(xm);
    n_max = std::max({n_max, na, nb, nm});
    if (!(na >= 0.0 && nb >= 0.0)) {
      throw std::invalid_argument("initial density is negative near x = " + std::to_string(xa));
    }
    p.cdf[i + 1] = p.cdf[i] + 0.5 * (na + nb) / kProfilePoints;
    p.momentum_x += nm * f.v(xm) / kProfilePoints;
    p.momentum_y += nm * (f.vy ? f.vy(xm) : 0.0) / kProfilePoints;
  }
  p.total = p.cdf.back();
  if (n_max * scene.area_fraction > 0.5) {
    std::ostringstream why;
    why << "the initial density peak n/n0 = " << n_max << " at area fraction "
        << scene.area_fraction << " gives a local area fraction " << n_max * scene.area_fraction
        << " > 0.5: disks cannot be placed without overlap";
    throw std::invalid_argument(why.str());
  }
  return p;
}

}  // namespace

void check_sampled_profile(const ParticleScene& scene, const hydro::InitialFields& f) {
  (void)tabulate(scene, f);
}

namespace {

// One disk's velocity at scaled position xs: the local flow plus a Maxwellian of the local
// temperature (T = m <c_x^2> per component), appended as an xyz triplet.
void append_velocity(std::vector<double>& v, const hydro::InitialFields& f, double xs,
                     Uniform& uniform) {
  const double thermal = std::sqrt(std::max(f.T(xs), 0.0));
  v.insert(v.end(), {f.v(xs) + thermal * uniform.normal(),
                     (f.vy ? f.vy(xs) : 0.0) + thermal * uniform.normal(), 0.0});
}

[[noreturn]] void no_free_spot(long long particle, long long particles) {
  throw std::invalid_argument("no free spot for particle " + std::to_string(particle) + " of " +
                              std::to_string(particles) + " after " + std::to_string(kMaxTries) +
                              " tries: the scene is too dense to place without overlap");
}

// Total momentum as the fields carry it, N <v> with <v> = int n v dx / int n dx: one shift of
// every velocity (xyz triplets) from the sample's momentum (px, py) of its n disks.
void shift_to_field_momentum(std::vector<double>& v, const Profile& profile, double px, double py,
                             double n) {
  const double shift_x = profile.momentum_x / profile.total - px / n,
               shift_y = profile.momentum_y / profile.total - py / n;
  for (std::size_t i = 0; i < v.size(); i += 3) v[i] += shift_x, v[i + 1] += shift_y;
}

// The whole box from one stream (a box of one strip): the sampler as it was before strips.
ParticleSample sample_whole_box(const ParticleScene& scene, const hydro::InitialFields& f,
                                std::uint64_t seed) {
  const long long n = scene.particles;
  const double lx = scene.box_length, ly = scene.box_width;
  const Profile profile = tabulate(scene, f);
  const double total = profile.total;

  Uniform uniform(seed);
  ParticleSample s;
  s.x.reserve(3 * n);
  s.v.reserve(3 * n);
  OverlapGrid grid(lx, ly);
  for (long long p = 0; p < n; ++p) {
    bool placed = false;
    for (int attempt = 0; attempt < kMaxTries && !placed; ++attempt) {
      const double xs = profile.position(uniform() * total);  // scaled position
      const double x = scene.md_position(xs), y = (uniform() - 0.5) * ly;
      if (!grid.free(x, y, s.x)) continue;
      grid.add(x, y, int(p));
      s.x.insert(s.x.end(), {x, y, 0.0});
      append_velocity(s.v, f, xs, uniform);
      placed = true;
    }
    if (!placed) no_free_spot(p, n);
  }
  double px = 0.0, py = 0.0;
  for (long long p = 0; p < n; ++p) px += s.v[3 * p], py += s.v[3 * p + 1];
  shift_to_field_momentum(s.v, profile, px, py, double(n));
  return s;
}

// SplitMix64 (Steele, Lea & Flood 2014): the seeds of the strips' streams from (seed, k).
std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
std::uint64_t strip_seed(std::uint64_t seed, int k) {
  return mix(mix(seed) + std::uint64_t(k) + 1);
}
std::uint64_t counts_seed(std::uint64_t seed) {
  return mix(mix(seed) ^ 0x636f756e7473ULL);  // "counts"
}

// Occupancy grid of one strip and a margin of one sigma either side: x in [origin, origin +
// width) (positions taken periodically in Lx), periodic in y. Overlaps are tested with the
// minimum image in both directions.
class StripGrid {
 public:
  StripGrid(double origin, double width, double lx, double ly) : origin_(origin), lx_(lx), ly_(ly) {
    nx_ = std::max(1, int(width)), ny_ = std::max(1, int(ly));
    width_ = width;
    cells_.resize(size_t(nx_) * ny_);
  }
  bool free(double x, double y) const {
    const int cx = column(x), cy = std::min(ny_ - 1, int((y + 0.5 * ly_) / ly_ * ny_));
    for (int dx = -1; dx <= 1; ++dx) {
      const int c = cx + dx;
      if (c < 0 || c >= nx_) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        for (const auto& [px, py] : cells_[size_t((cy + dy + ny_) % ny_) * nx_ + c]) {
          double ddx = px - x, ddy = py - y;
          ddx -= lx_ * std::round(ddx / lx_);
          ddy -= ly_ * std::round(ddy / ly_);
          if (ddx * ddx + ddy * ddy < 1.0) return false;
        }
      }
    }
    return true;
  }
  // False (nothing added) for a position outside the grid.
  bool add(double x, double y) {
    const int cx = column(x);
    if (cx < 0) return false;
    const int cy = std::min(ny_ - 1, int((y + 0.5 * ly_) / ly_ * ny_));
    cells_[size_t(cy) * nx_ + cx].push_back({x, y});
    return true;
  }

 private:
  // The column of x, or -1 outside [origin, origin + width) (periodically in Lx).
  int column(double x) const {
    double u = x - origin_;
    u -= lx_ * std::floor(u / lx_);
    return u < width_ ? std::min(nx_ - 1, int(u / width_ * nx_)) : -1;
  }
  double origin_, width_, lx_, ly_;
  int nx_, ny_;
  std::vector<std::vector<std::pair<double, double>>> cells_;
};

struct Strips {
  int count = 1;
  std::vector<double> edge;       // MD x of the strips' edges, count + 1
  std::vector<double> mass_edge;  // cumulative profile mass at the edges
  std::vector<long long> disks;   // disks per strip
  std::vector<long long> first;   // index of each strip's first disk
  int colour(int k) const { return (count % 2 == 1 && k == count - 1) ? 2 : k % 2; }
};

Strips make_strips(const ParticleScene& scene, const Profile& profile, std::uint64_t seed) {
  Strips s;
  s.count = strip_count(scene);
  for (int k = 0; k <= s.count; ++k) {
    const double xs = -0.5 + double(k) / s.count;
    s.edge.push_back(k == s.count ? 0.5 * scene.box_length : scene.md_position(xs));
    s.mass_edge.push_back(k == 0 ? 0.0 : k == s.count ? profile.total : profile.mass_below(xs));
  }
  // The strip of each of N positions drawn from the profile: a multinomial count per strip.
  s.disks.assign(std::size_t(s.count), 0);
  Uniform uniform(counts_seed(seed));
  for (long long p = 0; p < scene.particles; ++p) {
    const double target = uniform() * profile.total;
    const auto it = std::upper_bound(s.mass_edge.begin(), s.mass_edge.end(), target);
    ++s.disks[std::size_t(std::clamp(int(it - s.mass_edge.begin()) - 1, 0, s.count - 1))];
  }
  long long first = 0;
  for (long long d : s.disks) s.first.push_back(first), first += d;
  return s;
}

struct StripSample {
  std::vector<double> x, v;  // xyz triplets, in the strip's own order
  double px = 0.0, py = 0.0;
};

class StripSampler {
 public:
  StripSampler(const ParticleScene& scene, const hydro::InitialFields& f, const Profile& profile,
               const Strips& strips, std::uint64_t seed)
      : scene_(scene), f_(f), profile_(profile), strips_(strips), seed_(seed) {}

  const StripSample& strip(int k) {
    const auto found = done_.find(k);
    if (found != done_.end()) return found->second;
    const int n = strips_.count;
    const double lx = scene_.box_length, ly = scene_.box_width;
    const double lo = strips_.edge[k], hi = strips_.edge[k + 1];
    StripGrid grid(lo - 1.0, hi - lo + 2.0, lx, ly);        // the strip and a margin of sigma
    const int left = (k + n - 1) % n, right = (k + 1) % n;  // one strip when n = 2
    std::vector<int> neighbours{left};
    if (right != left) neighbours.push_back(right);
    for (int neighbour : neighbours) {
      if (strips_.colour(neighbour) >= strips_.colour(k)) continue;
      const StripSample& other = strip(neighbour);
      for (std::size_t i = 0; i < other.x.size(); i += 3) grid.add(other.x[i], other.x[i + 1]);
    }
    StripSample s;
    const long long disks = strips_.disks[std::size_t(k)];
    s.x.reserve(3 * std::size_t(disks));
    s.v.reserve(3 * std::size_t(disks));
    Uniform uniform(strip_seed(seed_, k));
    const double m_lo = strips_.mass_edge[k], m_hi = strips_.mass_edge[k + 1];
    for (long long p = 0; p < disks; ++p) {
      bool placed = false;
      for (int attempt = 0; attempt < kMaxTries && !placed; ++attempt) {
        const double xs = profile_.position(m_lo + uniform() * (m_hi - m_lo));
        const double x = scene_.md_position(xs), y = (uniform() - 0.5) * ly;
        if (!(x >= lo && x < hi) || !grid.free(x, y)) continue;
        grid.add(x, y);
        s.x.insert(s.x.end(), {x, y, 0.0});
        append_velocity(s.v, f_, xs, uniform);
        s.px += s.v[s.v.size() - 3];
        s.py += s.v[s.v.size() - 2];
        placed = true;
      }
      if (!placed) no_free_spot(strips_.first[std::size_t(k)] + p, scene_.particles);
    }
    return done_.emplace(k, std::move(s)).first->second;
  }

 private:
  const ParticleScene& scene_;
  const hydro::InitialFields& f_;
  const Profile& profile_;
  const Strips& strips_;
  std::uint64_t seed_;
  std::map<int, StripSample> done_;
};

}  // namespace

int strip_count(const ParticleScene& scene) {
  // Strips at least 8 sigma wide, so that a strip's grid and its margins stay within the period.
  const long long by_count = (scene.particles + kStripParticles - 1) / kStripParticles;
  return int(std::max(1LL, std::min(by_count, (long long)(scene.box_length / 8.0))));
}

ParticleSample sample_particles(const ParticleScene& scene, const hydro::InitialFields& f,
                                std::uint64_t seed) {
  if (strip_count(scene) == 1) return sample_whole_box(scene, f, seed);
  ParticleSample s = sample_particles_in(scene, f, seed, -0.5 * scene.box_length,
                                         0.5 * scene.box_length, [](std::vector<double>&) {});
  s.id.clear();  // every strip in order: IDs 1 .. N
  return s;
}

ParticleSample sample_particles_in(const ParticleScene& scene, const hydro::InitialFields& f,
                                   std::uint64_t seed, double x_lo, double x_hi,
                                   const StripMomentumCombine& combine) {
  if (strip_count(scene) == 1) return sample_whole_box(scene, f, seed);
  const Profile profile = tabulate(scene, f);
  const Strips strips = make_strips(scene, profile, seed);
  StripSampler sampler(scene, f, profile, strips, seed);
  std::vector<int> mine;
  for (int k = 0; k < strips.count; ++k) {
    if (strips.edge[k] < x_hi && strips.edge[k + 1] > x_lo) mine.push_back(k);
  }
  std::vector<double> momenta(2 * std::size_t(strips.count),
                              -std::numeric_limits<double>::infinity());
  ParticleSample out;
  for (int k : mine) {
    const StripSample& s = sampler.strip(k);
    out.x.insert(out.x.end(), s.x.begin(), s.x.end());
    out.v.insert(out.v.end(), s.v.begin(), s.v.end());
    for (long long i = 0; i < strips.disks[std::size_t(k)]; ++i) {
      out.id.push_back(strips.first[std::size_t(k)] + i + 1);
    }
    momenta[2 * std::size_t(k)] = s.px;
    momenta[2 * std::size_t(k) + 1] = s.py;
  }
  if (combine) combine(momenta);
  // The momentum summed over the strips in their order (the same on every rank).
  double px = 0.0, py = 0.0;
  for (int k = 0; k < strips.count; ++k) {
    if (!std::isfinite(momenta[2 * std::size_t(k)]))
      throw std::logic_error("sample_particles_in: no rank sampled strip " + std::to_string(k));
    px += momenta[2 * std::size_t(k)], py += momenta[2 * std::size_t(k) + 1];
  }
  shift_to_field_momentum(out.v, profile, px, py, double(scene.particles));
  return out;
}
}  // namespace granvv::md
