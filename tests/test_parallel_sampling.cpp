// The sampler in strips (md_bridge/particle_sampler.hpp, issue 15): a scene of one strip (at
// most kStripParticles disks, every shipped case) is sampled bit for bit as before strips
// existed, checked against fingerprints of the sampler of commit e24271b; a scene of many strips
// gives the same particles whatever x-range a rank asks for, has no overlaps across strip
// boundaries and follows the density profile.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>

#include "hydro/dilute_closure.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "md_bridge/particle_sampler.hpp"
#include "md_bridge/particle_scene.hpp"

namespace granvv::md {
namespace {

// FNV-1a over the bytes of the positions and velocities: any change of any bit changes it.
std::uint64_t fingerprint(const ParticleSample& s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (const std::vector<double>* a : {&s.x, &s.v}) {
    for (double d : *a) {
      unsigned char b[sizeof d];
      std::memcpy(b, &d, sizeof d);
      for (unsigned char c : b) h = (h ^ c) * 1099511628211ULL;
    }
  }
  return h;
}

hydro::InitialFields single_mode(double a) {
  return hydro::find_initial_condition("single_mode")
      .generate({{"velocity_amplitude", a}, {"mode", 1LL}}, hydro::DiluteClosure(hydro::Physics{}));
}

hydro::InitialFields random_modes() {
  return hydro::find_initial_condition("random_modes")
      .generate({{"random_modes", 3LL}, {"random_amplitude", 0.2}, {"seed", 1LL}},
                hydro::DiluteClosure(hydro::Physics{}));
}

// The smallest centre distance squared of a sample (periodic), by a cell list of 1 sigma cells.
double smallest_distance_squared(const ParticleScene& s, const ParticleSample& p) {
  const int nx = int(s.box_length), ny = int(s.box_width);
  std::vector<std::vector<long long>> cells(std::size_t(nx) * ny);
  auto cell = [&](double u, double l, int n) {
    return std::min(n - 1, int((u + 0.5 * l) / l * n));
  };
  for (long long i = 0; i < p.count(); ++i)
    cells[std::size_t(cell(p.x[3 * i + 1], s.box_width, ny)) * nx +
          cell(p.x[3 * i], s.box_length, nx)]
        .push_back(i);
  double min_d2 = 1e300;
  for (long long i = 0; i < p.count(); ++i) {
    const int cx = cell(p.x[3 * i], s.box_length, nx), cy = cell(p.x[3 * i + 1], s.box_width, ny);
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (long long j : cells[std::size_t((cy + dy + ny) % ny) * nx + (cx + dx + nx) % nx]) {
          if (j == i) continue;
          double ddx = p.x[3 * i] - p.x[3 * j], ddy = p.x[3 * i + 1] - p.x[3 * j + 1];
          ddx -= s.box_length * std::round(ddx / s.box_length);
          ddy -= s.box_width * std::round(ddy / s.box_width);
          min_d2 = std::min(min_d2, ddx * ddx + ddy * ddy);
        }
      }
    }
  }
  return min_d2;
}

TEST(StripSampler, OneStripScenesAreSampledAsBeforeStrips) {
  // The shipped md_paper_scene's 28 209 disks (the largest shipped scene), a dense uniform gas
  // and a profile in n and v, against the sampler before strips (fingerprints printed by it).
  const ParticleScene paper = scene_from_scaled(4e-4, 0.01, 0.05, 10.0);
  ASSERT_EQ(paper.particles, 28209);
  ASSERT_EQ(strip_count(paper), 1);
  const ParticleSample a = sample_particles(paper, single_mode(-0.05), 1);
  EXPECT_EQ(fingerprint(a), 6892939689008131296ULL);
  EXPECT_TRUE(a.id.empty());
  const ParticleSample b =
      sample_particles(scene_from_particles(4000, 0.2, 20.0, 0.9), hydro::uniform_fields(), 7);
  EXPECT_EQ(fingerprint(b), 9034608269382702762ULL);
  const ParticleScene modes = scene_from_particles(20000, 0.05, 20.0, 0.9);
  const ParticleSample c = sample_particles(modes, random_modes(), 11);
  EXPECT_EQ(fingerprint(c), 677867255930760619ULL);
  // The ranged form of a one-strip box is the whole box, whatever the range.
  const ParticleSample d = sample_particles_in(modes, random_modes(), 11, 0.0, 1.0, {});
  EXPECT_EQ(fingerprint(d), fingerprint(c));
}

// Three strips (an odd count: even, odd and the last strip in a third colour), 2.5e5 disks.
class ManyStrips : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new ParticleScene(scene_from_particles(250001, 0.05, 100.0, 0.9));
    fields_ = new hydro::InitialFields(random_modes());
    whole_ = new ParticleSample(sample_particles(*scene_, *fields_, 5));
  }
  static void TearDownTestSuite() {
    delete whole_;
    delete fields_;
    delete scene_;
  }
  static ParticleScene* scene_;
  static hydro::InitialFields* fields_;
  static ParticleSample* whole_;
};
ParticleScene* ManyStrips::scene_ = nullptr;
hydro::InitialFields* ManyStrips::fields_ = nullptr;
ParticleSample* ManyStrips::whole_ = nullptr;

TEST_F(ManyStrips, TwoRangesGiveTheParticlesOfTheWholeBoxBitForBit) {
  ASSERT_EQ(strip_count(*scene_), 3);
  ASSERT_EQ(whole_->count(), 250001);
  EXPECT_TRUE(whole_->id.empty());
  // Two "ranks" split at x = 0.3 Lx (not at a strip edge): the first pass learns each one's
  // strip momenta, the second gives both (the MPI_MAX all-reduce of md_run.cpp).
  const double lx = scene_->box_length;
  const double cut = 0.3 * lx;
  std::vector<double> seen[2];
  for (int pass = 0; pass < 2; ++pass) {
    std::map<long long, std::pair<int, std::size_t>> found;  // id -> (rank, index)
    ParticleSample part[2];
    for (int r = 0; r < 2; ++r) {
      part[r] = sample_particles_in(*scene_, *fields_, 5, r == 0 ? -0.5 * lx : cut,
                                    r == 0 ? cut : 0.5 * lx, [&](std::vector<double>& m) {
                                      if (pass == 0) {
                                        seen[r] = m;
                                        for (double& x : m) x = std::isfinite(x) ? x : 0.0;
                                      } else {
                                        for (std::size_t i = 0; i < m.size(); ++i)
                                          m[i] = std::max(seen[0][i], seen[1][i]);
                                      }
                                    });
      ASSERT_EQ(part[r].id.size(), std::size_t(part[r].count()));
    }
    if (pass == 0) continue;
    // Every particle a rank owns (its x in the rank's range) is the whole box's, bit for bit.
    long long owned = 0;
    for (int r = 0; r < 2; ++r) {
      for (long long i = 0; i < part[r].count(); ++i) {
        const double x = part[r].x[3 * i];
        if (!(r == 0 ? x < cut : x >= cut)) continue;
        ++owned;
        const long long j = part[r].id[i] - 1;
        ASSERT_GE(j, 0);
        ASSERT_LT(j, whole_->count());
        for (int d = 0; d < 3; ++d) {
          ASSERT_EQ(part[r].x[3 * i + d], whole_->x[3 * j + d]) << "particle " << j + 1;
          ASSERT_EQ(part[r].v[3 * i + d], whole_->v[3 * j + d]) << "particle " << j + 1;
        }
      }
    }
    EXPECT_EQ(owned, whole_->count());
  }
}

// Two strips, each the other's neighbour on both sides (across x = 0 and the periodic edge): the
// paper's scene 40 sigma wide (112 838 disks), where a first version of the sampler left one
// pair overlapping by 0.28 sigma across the periodic edge.
TEST(StripSampler, TwoStripsDoNotOverlapAcrossEitherEdge) {
  const ParticleScene s = scene_from_scaled(4e-4, 0.01, 0.05, 40.0);
  ASSERT_EQ(strip_count(s), 2);
  EXPECT_GE(smallest_distance_squared(s, sample_particles(s, single_mode(-0.05), 1)), 1.0);
}

TEST_F(ManyStrips, NoOverlapsAcrossStripsAndTheFieldsAreFollowed) {
  const ParticleScene& s = *scene_;
  const ParticleSample& p = *whole_;
  EXPECT_GE(smallest_distance_squared(s, p), 1.0);
  // The density and velocity profiles in 30 bins (Poisson and thermal noise, 5 sigma), the
  // total momentum the fields' (<v> = int n v / int n) and the temperature T0 = 1 (of v_y, which
  // carries no flow).
  const int bins = 30;
  std::vector<double> count(bins, 0.0), vsum(bins, 0.0), expected(bins, 0.0);
  double px = 0.0, kinetic = 0.0;
  for (long long i = 0; i < p.count(); ++i) {
    const int b = std::min(bins - 1, int((s.scaled_position(p.x[3 * i]) + 0.5) * bins));
    count[b] += 1, vsum[b] += p.v[3 * i];
    px += p.v[3 * i];
  }
  double norm = 0.0, nv = 0.0;
  for (int b = 0; b < bins; ++b) {
    for (int g = 0; g < 100; ++g) {
      const double x = -0.5 + (b + (g + 0.5) / 100) / bins;
      expected[b] += fields_->n(x) / 100;
      nv += fields_->n(x) * fields_->v(x) / 100;
    }
    norm += expected[b];
  }
  for (int b = 0; b < bins; ++b) {
    const double e = expected[b] / norm * double(p.count());
    EXPECT_NEAR(count[b], e, 5 * std::sqrt(e)) << "bin " << b;
    const double xc = -0.5 + (b + 0.5) / bins;
    EXPECT_NEAR(vsum[b] / count[b], fields_->v(xc), 5 / std::sqrt(count[b]) + 0.07) << "bin " << b;
  }
  EXPECT_NEAR(px / double(p.count()), nv / norm, 1e-3);  // the quadratures differ at 1e-4
  for (long long i = 0; i < p.count(); ++i) kinetic += p.v[3 * i + 1] * p.v[3 * i + 1];
  EXPECT_NEAR(kinetic / double(p.count()), 1.0, 5 * std::sqrt(2.0 / double(p.count())));
}

}  // namespace
}  // namespace granvv::md
