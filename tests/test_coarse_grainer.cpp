// The coarse-grainer (md_bridge/coarse_grainer.hpp) against known answers on generated
// particles: a uniform lattice (exact density), drifting Maxwellians (mean flow and granular
// temperature within their standard errors, local flow removed), sparse bins (the Bessel
// correction), additivity of moments and the MPI reduction, the energy split and wrapping.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "fields/constants.hpp"
#include "md_bridge/coarse_grainer.hpp"
#include "md_bridge/moment_reduction.hpp"

namespace {

using granvv::fields::FieldSnapshot;
using granvv::md::BoxEnergies;
using granvv::md::CoarseGrainer;
using granvv::md::CoarseGrainGrid;
using granvv::md::Moments;

using granvv::kPi;

// Particles in the LAMMPS layout (x[3 i + 0..2], v[3 i + 0..2]) with per-particle masses.
struct Particles {
  std::vector<double> x, v, m;
  int size() const { return static_cast<int>(m.size()); }
  void add(double px, double py, double vx, double vy, double mass = 1.0) {
    x.insert(x.end(), {px, py, 0.0});
    v.insert(v.end(), {vx, vy, 0.0});
    m.push_back(mass);
  }
};

CoarseGrainGrid make_grid(double x_lo, double Lx, double Ly, int bins, const std::string& kernel,
                          double width) {
  CoarseGrainGrid g;
  g.x_lo = x_lo;
  g.Lx = Lx;
  g.y_lo = -0.5 * Ly;
  g.Ly = Ly;
  g.bins = bins;
  g.kernel = kernel;
  g.width = width;
  return g;
}

// The kernels of the tests, as (name, width in units of the bin width).
struct KernelChoice {
  std::string name;
  double width_in_bins;
};
const std::vector<KernelChoice> kKernels = {{"bin", 0.0}, {"gaussian", 1.0}, {"lucy", 2.0}};

// Smoothing factor F(q) = <cos(q r)> of a kernel (the continuous formula of the header, its
// own normalisation over its support), by composite Simpson with 4000 intervals: an
// independent reference for the smoothed drift, error below 1e-10.
double smoothing_factor(const std::string& kernel, double width, double dx, double q) {
  std::function<double(double)> W;
  double R = 0.0;
  if (kernel == "bin") {
    W = [](double) { return 1.0; };
    R = 0.5 * dx;
  } else if (kernel == "gaussian") {
    W = [width](double r) { return std::exp(-0.5 * r * r / (width * width)); };
    R = 3.0 * width;
  } else {
    W = [width](double r) {
      const double s = std::abs(r) / width;
      return (1.0 + 3.0 * s) * std::pow(1.0 - s, 3);
    };
    R = width;
  }
  const int n = 4000;
  const double h = 2.0 * R / n;
  double num = 0.0;
  double den = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double r = -R + i * h;
    const double c = (i == 0 || i == n) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    num += c * W(r) * std::cos(q * r);
    den += c * W(r);
  }
  return num / den;
}

// A Maxwellian gas, uniform in the box: 2D temperature T (each velocity component has
// variance T/m) about the drift (vx(x), vy(x)).
Particles maxwellian(int N, double x_lo, double Lx, double Ly, double T,
                     const std::function<double(double)>& vx,
                     const std::function<double(double)>& vy, std::mt19937_64& rng,
                     const std::vector<double>& masses = {1.0}) {
  std::uniform_real_distribution<double> ux(x_lo, x_lo + Lx);
  std::uniform_real_distribution<double> uy(-0.5 * Ly, 0.5 * Ly);
  std::uniform_int_distribution<std::size_t> pick(0, masses.size() - 1);
  std::normal_distribution<double> gauss(0.0, 1.0);
  Particles p;
  for (int i = 0; i < N; ++i) {
    const double x = ux(rng);
    const double y = uy(rng);
    const double mass = masses[pick(rng)];
    const double s = std::sqrt(T / mass);
    const double cx = vx(x) + s * gauss(rng);
    const double cy = vy(x) + s * gauss(rng);
    p.add(x, y, cx, cy, mass);
  }
  return p;
}

void finalize_mpi_if_open() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

Moments grain(const CoarseGrainer& cg, const Particles& p) {
  return cg.accumulate(p.x.data(), p.v.data(), p.m.data(), p.size());
}

TEST(CoarseGrainer, RejectsImpossibleGridsAndParticles) {
  const auto make = [](int bins, double Lx, const std::string& kernel, double width) {
    return CoarseGrainer(make_grid(0.0, Lx, 1.0, bins, kernel, width));
  };
  EXPECT_THROW(make(0, 10.0, "bin", 0.0), std::invalid_argument);
  EXPECT_THROW(make(10, 0.0, "bin", 0.0), std::invalid_argument);
  EXPECT_THROW(make(10, -1.0, "bin", 0.0), std::invalid_argument);
  EXPECT_THROW(make(10, 10.0, "tophat", 0.0), std::invalid_argument);
  EXPECT_THROW(make(10, 10.0, "gaussian", 0.0), std::invalid_argument);
  EXPECT_THROW(make(10, 10.0, "lucy", -1.0), std::invalid_argument);
  // Support radius below half a bin (dx = 1): 3 * 0.1 and 0.4 < 0.5.
  EXPECT_THROW(make(10, 10.0, "gaussian", 0.1), std::invalid_argument);
  EXPECT_THROW(make(10, 10.0, "lucy", 0.4), std::invalid_argument);
  EXPECT_THROW(CoarseGrainer(make_grid(0.0, 10.0, 0.0, 10, "bin", 0.0)), std::invalid_argument);
  EXPECT_NO_THROW(make(10, 10.0, "bin", 5.0));  // the width of plain bins is ignored
  EXPECT_NO_THROW(make(10, 10.0, "lucy", 0.6));
  try {
    make(10, 10.0, "tophat", 0.0);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("tophat"), std::string::npos) << e.what();
  }

  const CoarseGrainer cg = make(10, 10.0, "bin", 0.0);
  Particles p;
  p.add(1.0, 0.0, 0.0, 0.0);
  p.add(std::nan(""), 0.0, 0.0, 0.0);
  EXPECT_THROW(grain(cg, p), std::invalid_argument);
  Moments wrong(7);
  EXPECT_THROW(cg.accumulate(wrong, p.x.data(), p.v.data(), nullptr, 1), std::invalid_argument);
  EXPECT_THROW(cg.fields(wrong), std::invalid_argument);
  EXPECT_THROW(wrong += Moments(10), std::invalid_argument);
}

// Known answer 1. A square lattice commensurate with the bins (4 columns per bin) maps onto
// itself under a shift by one bin, and so does every kernel's weight pattern: every bin gets
// the same count, and since every particle's weights add up to one, that count is N/bins —
// exact for every kernel up to round-off (1e-12 relative), including supports wider than the
// box (many periodic images).
TEST(CoarseGrainer, UniformLatticeGivesExactDensityForEveryKernel) {
  const double Lx = 40.0, Ly = 10.0, x_lo = -20.0, a = 0.5;
  const int bins = 20;
  Particles lattice;
  for (int i = 0; i < 80; ++i) {
    for (int j = 0; j < 20; ++j) lattice.add(x_lo + (i + 0.26) * a, -5.0 + (j + 0.5) * a, 0, 0);
  }
  const double N = lattice.size();
  const double n0 = N / (Lx * Ly);
  ASSERT_EQ(n0, 4.0);
  // Widths in sigma (bins are 2 wide): down to a support of 1.2 bins, up to supports wider
  // than the box.
  const std::vector<std::pair<std::string, double>> kernels = {
      {"bin", 0.0},       {"gaussian", 0.8}, {"gaussian", 3.0},
      {"gaussian", 10.0}, {"lucy", 1.5},     {"lucy", 25.0}};
  for (const auto& [kernel, width] : kernels) {
    SCOPED_TRACE(kernel + " width " + std::to_string(width));
    const CoarseGrainer cg(make_grid(x_lo, Lx, Ly, bins, kernel, width));
    const FieldSnapshot f = cg.fields(grain(cg, lattice));
    double integral = 0.0;
    for (int i = 0; i < bins; ++i) {
      EXPECT_NEAR(f.n[i] / n0, 1.0, 1e-12) << "bin " << i;
      EXPECT_NEAR(f.count[i], N / bins, 1e-12 * N);
      EXPECT_NEAR(f.x[i], x_lo + (i + 0.5) * 2.0, 1e-13);
      integral += f.n[i] * cg.grid().bin_width() * Ly;
    }
    EXPECT_NEAR(integral / N, 1.0, 1e-13);
  }
}

// Known answer 1b. A lattice that is not commensurate with the bins (97 columns, spacing
// a = 0.41, on 20 bins of 2): plain bins do not smooth at all (4 or 5 columns a bin), smooth
// kernels give a uniform density up to the quadrature error of the lattice sum of a
// particle's normalised weight phi(x) (its continuum integral is the same for every bin, by
// translation by one bin). That error comes from the kernel's non-smooth points (Euler-
// Maclaurin with jumps):
//   Gaussian cut at 3 width: value jumps of height g(3 width) = exp(-9/2)/(sqrt(2 pi) width),
//     at its own edges and, through the normalisation, where other centres enter the support;
//     a value jump J errs by at most J a / 2, which sums to 2 a g(3 width) = 1.8e-3 relative
//     for width 2 (measured 7.2e-4).
//   Lucy (radius h): C^2, with third-derivative jumps 120/h^4 at the centre and 30/h^4 at each
//     edge, as many again through the normalisation; a jump J3 errs by at most J3 a^4/720 (the
//     periodic Bernoulli function B4 is at most 1/30), in all a^4 / (2 h^4) = 5.6e-5 for h = 4
//     (measured 4.2e-6).
// Whatever the lattice, the total stays N to round-off.
TEST(CoarseGrainer, SmoothKernelsSmoothAnIncommensurateLatticeToQuadratureError) {
  const double Lx = 40.0, Ly = 10.0, x_lo = -20.0;
  const int bins = 20, columns = 97, rows = 20;
  const double a = Lx / columns;
  Particles lattice;
  for (int i = 0; i < columns; ++i) {
    for (int j = 0; j < rows; ++j) lattice.add(x_lo + (i + 0.5) * a, -5.0 + (j + 0.5) * 0.5, 0, 0);
  }
  const double N = lattice.size();
  const double n0 = N / (Lx * Ly);
  const double gaussian_width = 2.0;
  const double gaussian_jump = std::exp(-4.5) / (std::sqrt(2.0 * kPi) * gaussian_width);
  struct Case {
    std::string kernel;
    double width, tolerance;
  };
  for (const Case& c : {Case{"gaussian", gaussian_width, 2.0 * gaussian_jump * a},
                        Case{"lucy", 4.0, 0.5 * std::pow(a / 4.0, 4)}, Case{"bin", 0.0, 0.5}}) {
    SCOPED_TRACE(c.kernel);
    const CoarseGrainer cg(make_grid(x_lo, Lx, Ly, bins, c.kernel, c.width));
    const FieldSnapshot f = cg.fields(grain(cg, lattice));
    double worst = 0.0, integral = 0.0;
    for (int i = 0; i < bins; ++i) {
      worst = std::max(worst, std::abs(f.n[i] / n0 - 1.0));
      integral += f.n[i] * cg.grid().bin_width() * Ly;
    }
    std::printf("[ measured ] %-8s max |n/n0 - 1| = %.3g (bound %.3g)\n", c.kernel.c_str(), worst,
                c.tolerance);
    EXPECT_LT(worst, c.tolerance);
    if (c.kernel == "bin") {
      EXPECT_GT(worst, 0.01);
    }  // 4 or 5 columns per bin: not uniform
    EXPECT_NEAR(integral / N, 1.0, 1e-13);
  }
}

// Known answer 2. 200 000 particles, Maxwellian with T = 0.7 about v = (0.3, -0.1) (20 bins of
// 10 000): v_x, v_y and T within 4 of their own standard errors in every bin and for every
// kernel (60 checks a kernel; a Gaussian deviate exceeds 4 sigma with probability 6e-5).
// The standard errors themselves are tested against the scatter in the sparse-bin test.
TEST(CoarseGrainer, DriftingMaxwellianGivesItsFlowAndTemperature) {
  const double Lx = 100.0, Ly = 20.0, x_lo = -50.0, T = 0.7;
  const int bins = 20;
  std::mt19937_64 rng(20240611);
  const Particles p = maxwellian(
      200000, x_lo, Lx, Ly, T, [](double) { return 0.3; }, [](double) { return -0.1; }, rng);
  for (const auto& k : kKernels) {
    SCOPED_TRACE(k.name);
    const CoarseGrainer cg(make_grid(x_lo, Lx, Ly, bins, k.name, k.width_in_bins * Lx / bins));
    const Moments m = grain(cg, p);
    const FieldSnapshot f = cg.fields(m);
    for (int i = 0; i < bins; ++i) {
      const double n_eff = m.weight[i] * m.weight[i] / m.weight2[i];
      EXPECT_NEAR(f.v_x[i], 0.3, 4.0 * f.v_x_stderr[i]) << "bin " << i;
      EXPECT_NEAR(f.v_y[i], -0.1, 4.0 * f.v_y_stderr[i]) << "bin " << i;
      EXPECT_NEAR(f.T[i], T, 4.0 * f.T_stderr[i]) << "bin " << i;
      // The standard errors are those of ~1e4 particles: sqrt(T / N_eff), T / sqrt(N_eff).
      EXPECT_NEAR(f.v_x_stderr[i], std::sqrt(T / n_eff), 0.05 * f.v_x_stderr[i]);
      if (k.name == "bin") {
        EXPECT_EQ(n_eff, f.count[i]);
      }
    }
  }
}

// Known answer 2b. A sinusoidal flow v_x = 0.2 sin(kx), v_y = 0.15 cos(kx) (the shear mode,
// docs/physics.md §6) on top of the drift: the local mean is removed, so T stays 0.7, not
// 0.7 + (0.2^2 + 0.15^2)/4 = 0.7156 as with the global mean only (10 standard errors of the
// whole sample away). What a kernel of finite width cannot resolve remains: it smooths the
// flow by F(k) = <cos(k r)> and keeps the flow's variance over its width as heat, (m/2) Var_w
// of the drift — for the bins 1e-4, for these kernels up to 2e-3 (about half a standard error;
// asserted below 0.6). Both are part of the expected values, computed from the kernel formulas by
// quadrature.
TEST(CoarseGrainer, LocalMeanFlowIsRemovedFromTheTemperature) {
  const double Lx = 100.0, Ly = 20.0, x_lo = -50.0, T = 0.7, a = 0.2, b = 0.15;
  const double V_x = 0.3, V_y = -0.1;
  const double k = 2.0 * kPi / Lx;
  const int bins = 20;
  const int N = 200000;
  std::mt19937_64 rng(77);
  const Particles p = maxwellian(
      N, x_lo, Lx, Ly, T, [&](double x) { return V_x + a * std::sin(k * x); },
      [&](double x) { return V_y + b * std::cos(k * x); }, rng);

  // The temperature about the global mean only: the flow's energy counted as heat.
  double px = 0.0, py = 0.0, mv2 = 0.0;
  for (int i = 0; i < N; ++i) {
    px += p.v[3 * i];
    py += p.v[3 * i + 1];
    mv2 += p.v[3 * i] * p.v[3 * i] + p.v[3 * i + 1] * p.v[3 * i + 1];
  }
  const double T_global = 0.5 * (mv2 - (px * px + py * py) / N) / (N - 1);
  EXPECT_NEAR(T_global, T + (a * a + b * b) / 4.0, 4.0 * T / std::sqrt(N));
  EXPECT_GT(T_global - T, 8.0 * T / std::sqrt(N));

  for (const auto& kc : kKernels) {
    SCOPED_TRACE(kc.name);
    const double dx = Lx / bins;
    const double width = kc.width_in_bins * dx;
    const CoarseGrainer cg(make_grid(x_lo, Lx, Ly, bins, kc.name, width));
    const FieldSnapshot f = cg.fields(grain(cg, p));
    const double F1 = smoothing_factor(kc.name, width, dx, k);
    const double F2 = smoothing_factor(kc.name, width, dx, 2.0 * k);
    for (int i = 0; i < bins; ++i) {
      const double s = std::sin(k * f.x[i]), c = std::cos(k * f.x[i]);
      const double c2 = std::cos(2.0 * k * f.x[i]);
      const double var_x = a * a * ((1.0 - c2 * F2) / 2.0 - s * s * F1 * F1);
      const double var_y = b * b * ((1.0 + c2 * F2) / 2.0 - c * c * F1 * F1);
      EXPECT_NEAR(f.v_x[i], V_x + a * s * F1, 4.0 * f.v_x_stderr[i]) << "bin " << i;
      EXPECT_NEAR(f.v_y[i], V_y + b * c * F1, 4.0 * f.v_y_stderr[i]) << "bin " << i;
      EXPECT_NEAR(f.T[i], T + 0.5 * (var_x + var_y), 4.0 * f.T_stderr[i]) << "bin " << i;
      EXPECT_LT(0.5 * (var_x + var_y), 0.6 * f.T_stderr[i]);
    }
    // The thermal energy per particle of the whole box is T too (4 standard errors of N).
    const BoxEnergies e = cg.energies(grain(cg, p));
    EXPECT_NEAR(e.thermal / N, T + 0.25 * (a * a + b * b) * (1.0 - F1 * F1),
                4.0 * T / std::sqrt(N));
  }
}

// Known answer 3. Three particles per bin, 100 samples of 1000 bins (1e5 bin estimates): the
// Bessel-corrected T = sum m |c - v_b|^2 / (2 (N_b - 1)) averages to the true T within 4
// standard errors of the mean (sqrt(Var/1e5), Var = T^2/(N_b - 1) for Gaussian velocities),
// while the naive 1/(2 N_b) form is low by the factor 2/3 (> 100 standard errors). The
// scatter over the samples checks the standard errors the fields report: Var v_b = T/(m N_b)
// and Var T_b = T^2/(N_b - 1), each within 3 % (the relative error of a variance from 1e5
// samples is sqrt((kurtosis - 1)/1e5) < 0.8 %).
TEST(CoarseGrainer, TemperatureIsUnbiasedInSparseBins) {
  const double Lx = 1000.0, Ly = 3.0, T = 0.7, V = 0.4;
  const int bins = 1000, per_bin = 3, samples = 100;
  const CoarseGrainer cg(make_grid(0.0, Lx, Ly, bins, "bin", 0.0));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, std::sqrt(T));
  double sum_T = 0.0, sum_T2 = 0.0, sum_naive = 0.0, sum_v = 0.0, sum_v2 = 0.0;
  long count = 0;
  for (int s = 0; s < samples; ++s) {
    Particles p;
    for (int b = 0; b < bins; ++b) {
      for (int j = 0; j < per_bin; ++j) p.add(b + u(rng), 0.0, V + gauss(rng), gauss(rng));
    }
    const Moments m = grain(cg, p);
    const FieldSnapshot f = cg.fields(m);
    for (int b = 0; b < bins; ++b) {
      ASSERT_EQ(f.count[b], per_bin);
      const double naive = f.T[b] * (per_bin - 1) / per_bin;
      sum_T += f.T[b];
      sum_T2 += f.T[b] * f.T[b];
      sum_naive += naive;
      sum_v += f.v_x[b] - V;
      sum_v2 += (f.v_x[b] - V) * (f.v_x[b] - V);
      ++count;
    }
  }
  const double mean_T = sum_T / count;
  const double mean_naive = sum_naive / count;
  const double var_T = sum_T2 / count - mean_T * mean_T;
  const double var_v = sum_v2 / count - (sum_v / count) * (sum_v / count);
  const double se_mean = std::sqrt(T * T / (per_bin - 1) / count);
  std::printf("[ measured ] <T> = %.5f +- %.5f, naive <T> = %.5f (true %.2f, naive bias %.4f)\n",
              mean_T, se_mean, mean_naive, T, mean_naive - T);
  EXPECT_NEAR(mean_T, T, 4.0 * se_mean);
  EXPECT_NEAR(mean_naive, T * (per_bin - 1) / per_bin, 4.0 * se_mean);
  EXPECT_GT(T - mean_naive, 100.0 * se_mean);
  EXPECT_NEAR(var_T / (T * T / (per_bin - 1)), 1.0, 0.03);
  EXPECT_NEAR(var_v / (T / per_bin), 1.0, 0.03);
}

// Known answer 3b. The same for a Gaussian kernel (width dx/2) on a Poisson gas of 3
// particles per bin with two masses (1 and 4): the weights differ and so do the masses, and
// T_b = sum w m |c - v_b|^2 / (2 (W - sum w^2 m / sum w m)) is unbiased given the positions,
// so its mean over 1e5 bin estimates is T within 4 standard errors; the form without the
// correction (1/(2W)) is low by many. Bins with N_eff <= 1 (no particle within 3 width, or
// one) report NaN and are left out — a choice by position only, so no bias.
TEST(CoarseGrainer, KernelTemperatureIsUnbiasedWithUnequalWeightsAndMasses) {
  const double Lx = 1000.0, Ly = 3.0, T = 0.7;
  const int bins = 1000, samples = 100;
  const CoarseGrainer cg(make_grid(0.0, Lx, Ly, bins, "gaussian", 0.5));
  std::mt19937_64 rng(11);
  double sum_T = 0.0, sum_T2 = 0.0, sum_naive = 0.0;
  long count = 0, undefined = 0;
  for (int s = 0; s < samples; ++s) {
    const Particles p = maxwellian(
        3 * bins, 0.0, Lx, Ly, T, [](double) { return 0.1; }, [](double) { return 0.2; }, rng,
        {1.0, 4.0});
    const Moments m = grain(cg, p);
    const FieldSnapshot f = cg.fields(m);
    for (int b = 0; b < bins; ++b) {
      if (std::isnan(f.T[b])) {
        ++undefined;
        continue;
      }
      const double D = m.weight[b] - m.mass_weight2[b] / m.mass[b];
      sum_T += f.T[b];
      sum_T2 += f.T[b] * f.T[b];
      sum_naive += f.T[b] * D / m.weight[b];
      ++count;
    }
  }
  const double mean_T = sum_T / count;
  const double se_mean = std::sqrt((sum_T2 / count - mean_T * mean_T) / count);
  const double mean_naive = sum_naive / count;
  std::printf("[ measured ] <T> = %.5f +- %.5f, uncorrected <T> = %.5f, %ld undefined bins\n",
              mean_T, se_mean, mean_naive, undefined);
  EXPECT_NEAR(mean_T, T, 4.0 * se_mean);
  EXPECT_GT(T - mean_naive, 20.0 * se_mean);
  EXPECT_LT(undefined, count / 100);
}

// Known answer 4a. Moments of two halves of a sample, added as the MPI reduction adds them,
// give the fields of the whole: weights exactly (sums of the same numbers), the rest to
// round-off (1e-12 relative, the summation order differs).
TEST(CoarseGrainer, MomentsOfPartsAddUpToTheWhole) {
  const double Lx = 50.0, Ly = 10.0, x_lo = -25.0;
  std::mt19937_64 rng(3);
  const Particles p = maxwellian(
      20000, x_lo, Lx, Ly, 0.5, [](double x) { return 0.3 * std::sin(x); },
      [](double) { return -0.2; }, rng, {1.0, 2.0});
  const int half = p.size() / 2;
  for (const auto& k : kKernels) {
    SCOPED_TRACE(k.name);
    const CoarseGrainer cg(make_grid(x_lo, Lx, Ly, 25, k.name, k.width_in_bins * 2.0));
    const Moments whole = grain(cg, p);
    Moments sum = cg.accumulate(p.x.data(), p.v.data(), p.m.data(), half);
    const Moments second = cg.accumulate(p.x.data() + 3 * half, p.v.data() + 3 * half,
                                         p.m.data() + half, p.size() - half);
    sum += second;
    EXPECT_EQ(sum.particles, whole.particles);
    if (k.name == "bin") {
      EXPECT_EQ(sum.weight, whole.weight);
    }
    const FieldSnapshot a = cg.fields(sum), b = cg.fields(whole);
    for (int i = 0; i < cg.grid().bins; ++i) {
      EXPECT_NEAR(a.n[i], b.n[i], 1e-12 * b.n[i]);
      EXPECT_NEAR(a.v_x[i], b.v_x[i], 1e-12);
      EXPECT_NEAR(a.v_y[i], b.v_y[i], 1e-12);
      EXPECT_NEAR(a.T[i], b.T[i], 1e-12 * b.T[i]);
      EXPECT_NEAR(a.T_stderr[i], b.T_stderr[i], 1e-12 * b.T_stderr[i]);
      for (const auto& [column, of_sum, of_whole] :
           {std::tuple{"kinetic_energy", a.kinetic_energy[i], b.kinetic_energy[i]},
            std::tuple{"energy_flux_x", a.energy_flux_x[i], b.energy_flux_x[i]},
            std::tuple{"kinetic_energy_stderr", a.kinetic_energy_stderr[i],
                       b.kinetic_energy_stderr[i]},
            std::tuple{"energy_flux_x_stderr", a.energy_flux_x_stderr[i],
                       b.energy_flux_x_stderr[i]}}) {
        EXPECT_NEAR(of_sum, of_whole, 1e-10 * (std::abs(of_whole) + 1e-3)) << column << " " << i;
      }
    }
    // The contacts' energy flux shares add up as well.
    std::vector<double> shares(std::size_t(p.size()));
    for (std::size_t i = 0; i < shares.size(); ++i) shares[i] = std::sin(0.1 * double(i));
    const std::vector<double> zero(shares.size(), 0.0);
    Moments whole_c(cg.grid().bins), part_c(cg.grid().bins), rest_c(cg.grid().bins);
    cg.accumulate(whole_c, p.x.data(), p.v.data(), p.m.data(), p.size(), 3, zero.data(),
                  zero.data(), shares.data());
    cg.accumulate(part_c, p.x.data(), p.v.data(), p.m.data(), half, 3, zero.data(), zero.data(),
                  shares.data());
    cg.accumulate(rest_c, p.x.data() + 3 * half, p.v.data() + 3 * half, p.m.data() + half,
                  p.size() - half, 3, zero.data() + half, zero.data() + half, shares.data() + half);
    part_c += rest_c;
    const FieldSnapshot c_sum = cg.fields(part_c), c_whole = cg.fields(whole_c);
    for (int i = 0; i < cg.grid().bins; ++i) {
      EXPECT_NEAR(c_sum.contact_energy_flux_x[i], c_whole.contact_energy_flux_x[i], 1e-12);
      EXPECT_NEAR(c_sum.contact_energy_flux_x_stderr[i], c_whole.contact_energy_flux_x_stderr[i],
                  1e-12);
    }
    // Accumulating chunk after chunk into the same moments is accumulating the whole.
    Moments chunked(cg.grid().bins);
    cg.accumulate(chunked, p.x.data(), p.v.data(), p.m.data(), half);
    cg.accumulate(chunked, p.x.data() + 3 * half, p.v.data() + 3 * half, p.m.data() + half,
                  p.size() - half);
    EXPECT_EQ(chunked.px, whole.px);  // the same additions in the same order
    EXPECT_EQ(chunked.mv2, whole.mv2);
  }
}

// Known answer 4b. The real reduction over MPI_COMM_WORLD. Each rank grains every size-th
// particle of the same sample; after allreduce every rank holds the fields of the whole (to
// round-off, 1e-12). In the plain test binary the world has one rank, where MPI_SUM must
// leave the packed buffer bit for bit; under `mpirun -n P` it tests a true reduction.
// MPI is initialised here if nobody has (LAMMPS tests in the same binary may have), and
// finalised only at exit (if still open): MPI cannot be initialised twice in a process and a
// later test may need it, while mpirun reports a rank that exits without MPI_Finalize as a
// failure. If another test has already finalised MPI, this one is skipped.
TEST(CoarseGrainer, AllreduceOverMpiGivesTheFieldsOfTheWhole) {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (finalized) GTEST_SKIP() << "MPI already finalised in this process";
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) {
    ASSERT_EQ(MPI_Init(nullptr, nullptr), MPI_SUCCESS);
    std::atexit(finalize_mpi_if_open);
  }
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);

  const double Lx = 50.0, Ly = 10.0, x_lo = -25.0;
  std::mt19937_64 rng(4);  // the same sample on every rank
  const Particles p = maxwellian(
      10000, x_lo, Lx, Ly, 0.5, [](double x) { return 0.3 * std::sin(x); },
      [](double) { return -0.2; }, rng, {1.0, 2.0});
  for (const auto& k : kKernels) {
    SCOPED_TRACE(k.name);
    const CoarseGrainer cg(make_grid(x_lo, Lx, Ly, 25, k.name, k.width_in_bins * 2.0));
    const Moments whole = grain(cg, p);
    Moments mine(cg.grid().bins);
    for (int i = rank; i < p.size(); i += size) {
      cg.accumulate(mine, &p.x[3 * i], &p.v[3 * i], &p.m[i], 1);
    }
    const Moments before = mine;
    granvv::md::allreduce(mine, MPI_COMM_WORLD);
    EXPECT_EQ(mine.particles, whole.particles);
    if (size == 1) {
      const Moments& reduced = mine;
      const auto x = reduced.arrays(), y = before.arrays();
      for (std::size_t a = 0; a < x.size(); ++a) EXPECT_EQ(*x[a], *y[a]) << "array " << a;
    }
    const FieldSnapshot f = cg.fields(mine), g = cg.fields(whole);
    for (int i = 0; i < cg.grid().bins; ++i) {
      EXPECT_NEAR(f.n[i], g.n[i], 1e-12 * g.n[i]);
      EXPECT_NEAR(f.v_x[i], g.v_x[i], 1e-12);
      EXPECT_NEAR(f.v_y[i], g.v_y[i], 1e-12);
      EXPECT_NEAR(f.T[i], g.T[i], 1e-12 * g.T[i]);
    }
  }
}

// Known answer 5. The energy split and momentum. For every kernel:
//   thermal_biased + macro_x + macro_y = total, and
//   thermal + (macro_x - noise_x) + (macro_y - noise_y) = total      (1e-12 relative),
// momentum and mass equal the particle sums (1e-12). The physics: in a quiet gas (no flow)
// the macroscopic energy is nothing but the noise floor, T/2 per bin and component for plain
// bins (its relative scatter over 200 bins is sqrt(2/200) = 0.1; tolerance 4 of that); with a
// shear flow v_y = 0.15 cos(kx) the transverse flow energy net of noise is
// (M/2)(V_y^2 + b^2 F^2 / 2) within 4 of its sampling error.
TEST(CoarseGrainer, EnergySplitAndMomentum) {
  const double Lx = 100.0, Ly = 20.0, x_lo = -50.0, T = 0.7, b = 0.15, V_y = -0.1;
  const double k = 2.0 * kPi / Lx;
  const int N = 100000;
  std::mt19937_64 rng(99);
  const Particles shear = maxwellian(
      N, x_lo, Lx, Ly, T, [](double) { return 0.3; },
      [&](double x) { return V_y + b * std::cos(k * x); }, rng, {1.0, 3.0});
  double M = 0.0, Px = 0.0, Py = 0.0, K = 0.0;
  for (int i = 0; i < N; ++i) {
    const double vx = shear.v[3 * i], vy = shear.v[3 * i + 1];
    M += shear.m[i];
    Px += shear.m[i] * vx;
    Py += shear.m[i] * vy;
    K += 0.5 * shear.m[i] * (vx * vx + vy * vy);
  }
  for (const auto& kc : kKernels) {
    SCOPED_TRACE(kc.name);
    const int bins = 200;
    const double dx = Lx / bins;
    const CoarseGrainer cg(make_grid(x_lo, Lx, Ly, bins, kc.name, kc.width_in_bins * dx));
    const Moments m = grain(cg, shear);
    const BoxEnergies e = cg.energies(m);
    EXPECT_EQ(e.particles, N);
    EXPECT_NEAR(e.mass, M, 1e-12 * M);
    EXPECT_NEAR(e.momentum_x, Px, 1e-12 * std::sqrt(2.0 * M * K));
    EXPECT_NEAR(e.momentum_y, Py, 1e-12 * std::sqrt(2.0 * M * K));
    EXPECT_NEAR(e.kinetic_total, K, 1e-12 * K);
    EXPECT_NEAR(e.thermal_biased + e.kinetic_macro_x + e.kinetic_macro_y, K, 1e-12 * K);
    EXPECT_NEAR(
        e.thermal + (e.kinetic_macro_x - e.macro_noise_x) + (e.kinetic_macro_y - e.macro_noise_y),
        K, 1e-12 * K);
    EXPECT_GT(e.thermal, e.thermal_biased);

    // The transverse flow energy, net of its noise floor, against the imposed shear mode.
    const FieldSnapshot f = cg.fields(m);
    const double F = smoothing_factor(kc.name, kc.width_in_bins * dx, dx, k);
    double variance = 0.0;
    for (int i = 0; i < bins; ++i) {
      const double Mi = m.mass[i];
      // Var of (1/2) M_i v_i^2: from the mean velocity (M_i v^2 T) and from the bin's mass
      // (Poisson in the particle count, masses 1 or 3: Var M_i = N_i <m^2>).
      variance += Mi * f.v_y[i] * f.v_y[i] * f.T[i] +
                  f.count[i] * 5.0 * std::pow(0.5 * f.v_y[i] * f.v_y[i], 2);
    }
    const double expected_y = 0.5 * M * (V_y * V_y + 0.5 * b * b * F * F);
    EXPECT_NEAR(e.kinetic_macro_y - e.macro_noise_y, expected_y, 4.0 * std::sqrt(variance));
    if (kc.name == "bin") {
      double noise = 0.0;
      for (int i = 0; i < bins; ++i) noise += 0.5 * f.T[i] * m.mass_weight2[i] / m.mass[i];
      EXPECT_NEAR(e.macro_noise_y, noise, 1e-12 * noise);
    }
  }

  // A quiet gas: the macroscopic energy is the sampling noise of the bin means.
  const Particles quiet = maxwellian(
      N, x_lo, Lx, Ly, T, [](double) { return 0.0; }, [](double) { return 0.0; }, rng);
  const int bins = 200;
  const CoarseGrainer cg(make_grid(x_lo, Lx, Ly, bins, "bin", 0.0));
  const BoxEnergies e = cg.energies(grain(cg, quiet));
  EXPECT_NEAR(e.macro_noise_y / (0.5 * T * bins), 1.0, 0.05);
  EXPECT_NEAR(e.kinetic_macro_y / e.macro_noise_y, 1.0, 4.0 * std::sqrt(2.0 / bins));
  EXPECT_NEAR(e.kinetic_macro_x / e.macro_noise_x, 1.0, 4.0 * std::sqrt(2.0 / bins));
}

// Known answer 7. The kinetic energy (1/2) sum m |v|^2 and its flux (1/2) sum m |v|^2 v_x per
// unit area, and the disks' contact transfer of energy summed per bin: exact sums on hand-placed
// particles (bins), the whole box's energy and flux conserved by every kernel (each particle's
// weights add up to one), each bin's stated error against the scatter of 16 equal bins, and a
// drifting Maxwellian's enthalpy flux U (rho U^2/2 + n T + p), p = n T in 2D: E[|v|^2 v_x] = U (U^2
// + 4 T/m) for a drift U along x, within 4 standard errors of the particles' own scatter.
TEST(CoarseGrainer, EnergyFluxIsTheBoxFrameKineticFlux) {
  const double Lx = 4.0, Ly = 2.0;
  const CoarseGrainer bins(make_grid(0.0, Lx, Ly, 4, "bin", 0.0));
  Particles few;
  few.add(0.5, 0.0, 1.0, 2.0, 2.0);   // bin 0: (1/2) 2 (1 + 4) 1 = 5
  few.add(0.7, 0.3, -3.0, 0.0, 1.0);  // bin 0: (1/2) 9 (-3) = -13.5
  few.add(2.5, -0.2, 0.0, 5.0, 1.0);  // bin 2: no x velocity, no flux
  few.add(3.9, 0.1, 2.0, -1.0, 0.5);  // bin 3: (1/2) 0.5 5 2 = 2.5
  const FieldSnapshot f = bins.fields(grain(bins, few));
  const double area = Ly * Lx / 4;
  ASSERT_EQ(f.energy_flux_x.size(), 4u);
  EXPECT_DOUBLE_EQ(f.energy_flux_x[0], (5.0 - 13.5) / area);
  EXPECT_EQ(f.energy_flux_x[1], 0.0);
  EXPECT_EQ(f.energy_flux_x[2], 0.0);
  EXPECT_DOUBLE_EQ(f.energy_flux_x[3], 2.5 / area);
  EXPECT_DOUBLE_EQ(f.kinetic_energy[0], (5.0 + 4.5) / area);
  EXPECT_DOUBLE_EQ(f.kinetic_energy[2], 12.5 / area);
  EXPECT_DOUBLE_EQ(f.kinetic_energy[3], 1.25 / area);
  EXPECT_TRUE(std::isnan(f.contact_energy_flux_x[0]));  // no contact transfer given
  // With each disk's share of the contact transfer of energy: their sum per bin and area.
  const std::vector<double> zero(4, 0.0), shares = {0.5, -0.25, 2.0, 1.0};
  Moments with(4);
  bins.accumulate(with, few.x.data(), few.v.data(), few.m.data(), few.size(), 3, zero.data(),
                  zero.data(), shares.data());
  const FieldSnapshot c = bins.fields(with);
  EXPECT_DOUBLE_EQ(c.contact_energy_flux_x[0], 0.25 / area);
  EXPECT_EQ(c.contact_energy_flux_x[1], 0.0);
  EXPECT_DOUBLE_EQ(c.contact_energy_flux_x[2], 2.0 / area);
  EXPECT_DOUBLE_EQ(c.contact_energy_flux_x_stderr[0], std::sqrt(2.0 * (0.25 + 0.0625)) / area);

  std::mt19937_64 rng(31);
  const double U = 0.3, T = 1.0;
  const int N = 200000;
  const Particles gas = maxwellian(
      N, 0.0, 40.0, 10.0, T, [U](double) { return U; }, [](double) { return 0.0; }, rng);
  double sum = 0.0, sum2 = 0.0, kinetic = 0.0;
  for (int i = 0; i < gas.size(); ++i) {
    const double vx = gas.v[3 * i], vy = gas.v[3 * i + 1];
    const double j = 0.5 * gas.m[i] * (vx * vx + vy * vy) * vx;
    sum += j, sum2 += j * j;
    kinetic += 0.5 * gas.m[i] * (vx * vx + vy * vy);
  }
  for (const auto& k : kKernels) {
    SCOPED_TRACE(k.name);
    const CoarseGrainer cg(make_grid(0.0, 40.0, 10.0, 16, k.name, k.width_in_bins * 2.5));
    const FieldSnapshot g = cg.fields(grain(cg, gas));
    double total = 0.0, energy = 0.0;
    for (double j : g.energy_flux_x) total += j * 2.5 * 10.0;
    for (double e : g.kinetic_energy) energy += e * 2.5 * 10.0;
    EXPECT_NEAR(total, sum, 1e-9 * std::sqrt(sum2));
    EXPECT_NEAR(energy, kinetic, 1e-12 * kinetic);
    if (k.name != "bin") continue;
    // The 16 bins of a uniform gas are 16 independent samples: their scatter is the error each
    // bin states (16 values give a standard deviation to about 18 %).
    for (const auto& [values, errors] : {std::pair{g.energy_flux_x, g.energy_flux_x_stderr},
                                         std::pair{g.kinetic_energy, g.kinetic_energy_stderr}}) {
      double mean = 0.0, var = 0.0, stated = 0.0;
      for (double v : values) mean += v / 16.0;
      for (double v : values) var += (v - mean) * (v - mean) / 15.0;
      for (double e : errors) stated += e / 16.0;
      EXPECT_GT(stated / std::sqrt(var), 0.6);
      EXPECT_LT(stated / std::sqrt(var), 1.6);
    }
  }
  const double mean = sum / N;
  const double stderr_mean = std::sqrt((sum2 / N - mean * mean) / N);
  EXPECT_NEAR(mean, 0.5 * U * (U * U + 4.0 * T), 4.0 * stderr_mean);
  EXPECT_GT(std::abs(mean), 10.0 * stderr_mean);  // the drift's flux is resolved
}

// Known answer 6. Atoms a little outside the box (LAMMPS between neighbour-list rebuilds,
// docs/physics.md §10), or whole periods away, count in the bin of their periodic image: the
// moments equal those of the wrapped sample (plain bins exactly; smooth kernels to round-off,
// 1e-12, since x - x_lo differs in its last bits). The edges: x_lo + Lx is x_lo (bin 0), a hair
// below x_lo is in the last bin, a hair above x_lo + Lx in the first.
TEST(CoarseGrainer, ParticlesOutsideTheBoxAreWrapped) {
  const double Lx = 20.0, Ly = 5.0, x_lo = -10.0;
  const int bins = 10;
  std::mt19937_64 rng(8);
  const Particles inside = maxwellian(
      2000, x_lo, Lx, Ly, 1.0, [](double x) { return std::cos(x); }, [](double) { return 0.0; },
      rng);
  Particles outside = inside;
  for (int i = 0; i < outside.size(); ++i) {
    outside.x[3 * i] += Lx * ((i % 5) - 2);  // shifted by -2 .. +2 periods
  }
  for (const auto& k : kKernels) {
    SCOPED_TRACE(k.name);
    const CoarseGrainer cg(make_grid(x_lo, Lx, Ly, bins, k.name, k.width_in_bins * 2.0));
    const Moments a = grain(cg, inside), b = grain(cg, outside);
    for (int i = 0; i < bins; ++i) {
      if (k.name == "bin") {
        EXPECT_EQ(a.weight[i], b.weight[i]) << "bin " << i;
      }
      EXPECT_NEAR(a.weight[i], b.weight[i], 1e-12 * a.weight[i]);
      EXPECT_NEAR(a.px[i], b.px[i], 1e-12 * a.weight[i]);
      EXPECT_NEAR(a.mv2[i], b.mv2[i], 1e-12 * a.mv2[i]);
    }
  }

  const CoarseGrainer cg(make_grid(x_lo, Lx, Ly, bins, "bin", 0.0));
  const auto bin_of = [&](double x) {
    Particles one;
    one.add(x, 0.0, 0.0, 0.0);
    const Moments m = grain(cg, one);
    for (int i = 0; i < bins; ++i) {
      if (m.weight[i] == 1.0) return i;
    }
    return -1;
  };
  EXPECT_EQ(bin_of(x_lo + Lx), 0);
  EXPECT_EQ(bin_of(x_lo - 1e-9), bins - 1);
  // The next double below x_lo wraps to x_lo + Lx after rounding: still the last bin.
  EXPECT_EQ(bin_of(std::nextafter(x_lo, -1e300)), bins - 1);
  EXPECT_EQ(bin_of(x_lo + Lx + 1e-9), 0);
  EXPECT_EQ(bin_of(x_lo + Lx - 1e-9), bins - 1);
  EXPECT_EQ(bin_of(x_lo + 2.5 + 7 * Lx), 1);
  EXPECT_EQ(bin_of(x_lo + 2.5 - 7 * Lx), 1);
}

}  // namespace
