// Linear stability of the homogeneous cooling state (hydro/linear_stability.hpp), checked
// against the paper's nonlinear Eqs. (1)-(2) (numerical linearisation), against independent
// time integration, against the asymptotic long- and short-wave limits, and against the paper's
// instability criterion pi k K < sqrt(q) evaluated in long double.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <complex>
#include <functional>
#include <vector>

#include "fields/constants.hpp"
#include "hydro/haff.hpp"
#include "hydro/linear_stability.hpp"
#include "support/runge_kutta.hpp"

namespace {

using granvv::hydro::Physics;
using cd = std::complex<double>;
using Vec = Eigen::Vector3cd;
using granvv::kPi;
constexpr long double kPiL = 3.141592653589793238462643383279502884L;

double max_real_rate(const std::array<granvv::hydro::HcsMode, 3>& modes) {
  return modes[0].rate.real();
}

// ---------------------------------------------------------------------------------------------
// The paper's Eqs. (1)-(2) in Eulerian form: time derivatives of (n, v, T) at one point, given
// the fields and their first and second x-derivatives there.
struct Point {
  double n, nx, v, vx, vxx, T, Tx, Txx;
};

std::array<double, 3> eulerian_rates(const Point& f, const Physics& p) {
  const double sqT = std::sqrt(f.T);
  const double P = -f.n * f.T + 0.25 * p.K * sqT * f.vx;
  const double Px =
      -(f.nx * f.T + f.n * f.Tx) + 0.25 * p.K * (0.5 / sqT * f.Tx * f.vx + sqT * f.vxx);
  const double conduction = p.K * (0.5 / sqT * f.Tx * f.Tx + sqT * f.Txx);
  const double loss = 8.0 * p.q / p.K * f.n * f.n * f.T * sqT;
  return {-f.v * f.nx - f.n * f.vx,                             // Eq. (1a)
          -f.v * f.vx + Px / f.n,                               // Eq. (1b)
          -f.v * f.Tx + (P * f.vx + conduction - loss) / f.n};  // Eq. (2)
}

// Column j of the collision-clock operator, obtained by a central difference of the nonlinear
// rates around the HCS at time t for the perturbation delta * Re(e_j e^{i kx x}) in (nu, w, theta).
Vec numerical_column(const Physics& p, double kx, double t, int j, double delta) {
  const double t0 = granvv::hydro::haff_time_scale(p);
  const double TH = granvv::hydro::haff_temperature(t, t0);
  const double dTH = -8.0 * p.q / p.K * std::pow(TH, 1.5);  // Haff: dT_H/dt
  Vec amplitude = Vec::Zero();
  amplitude(j) = 1.0;
  // Rates at x with perturbation sign*delta; Re(c e^{i kx x}) and its derivatives.
  const auto rates = [&](double x, double sign) {
    const cd e = std::exp(cd(0.0, kx * x));
    const cd ik(0.0, kx);
    const auto field = [&](cd c) { return std::real(c * e) * sign * delta; };
    const auto d1 = [&](cd c) { return std::real(ik * c * e) * sign * delta; };
    const auto d2 = [&](cd c) { return std::real(ik * ik * c * e) * sign * delta; };
    const cd nu = amplitude(0), u = amplitude(1) * std::sqrt(TH), th = amplitude(2);
    Point f{1.0 + field(nu),        d1(nu),      field(u),   d1(u), d2(u),
            TH * (1.0 + field(th)), TH * d1(th), TH * d2(th)};
    return eulerian_rates(f, p);
  };
  // The response of a real operator to Re(c e^{ikx}) is Re(z e^{ikx}); z = R(0) + i R(-pi/(2kx)).
  std::array<cd, 3> z;
  const double quarter = -0.5 * kPi / kx;
  for (int m = 0; m < 3; ++m) {
    const double at0 = (rates(0.0, 1.0)[m] - rates(0.0, -1.0)[m]) / (2.0 * delta);
    const double atq = (rates(quarter, 1.0)[m] - rates(quarter, -1.0)[m]) / (2.0 * delta);
    z[m] = cd(at0, atq);
  }
  // Physical-time responses -> collision clock and w = u/T_H^{1/2}:
  //   nu_s = nu_t / T_H^{1/2},  w_s = u_t / T_H + eps w,  theta_s = (dT_t - T_H' theta) /
  //   T_H^{3/2}.
  const double eps = 1.0 / t0;
  Vec column;
  column(0) = z[0] / std::sqrt(TH);
  column(1) = z[1] / TH + eps * amplitude(1);
  column(2) = (z[2] - dTH * amplitude(2)) / std::pow(TH, 1.5);
  return column;
}

TEST(LinearStability, OperatorIsTheLinearisationOfThePaperEquations) {
  // Central differences cancel the quadratic terms; the cubic remainder is ~delta^2 times
  // coefficients of size <= ||A||, and rounding ~ 1e-16 |rates| / delta. Tolerance 1e-8 ||A||.
  const double delta = 1e-5;
  for (const Physics p : {Physics{4e-4, 0.01}, Physics{0.05, 0.2}}) {
    for (const int k : {1, 7, 80}) {
      const Eigen::Matrix3cd A = granvv::hydro::hcs_linear_operator(p, k);
      for (const double t : {0.0, 3.0 * granvv::hydro::haff_time_scale(p)}) {
        for (int j = 0; j < 3; ++j) {
          const Vec column = numerical_column(p, 2.0 * kPi * k, t, j, delta);
          EXPECT_LT((column - A.col(j)).norm(), 1e-8 * A.norm())
              << "K=" << p.K << " q=" << p.q << " k=" << k << " t=" << t << " column " << j
              << "\nnumerical " << column.transpose() << "\noperator  " << A.col(j).transpose();
        }
      }
    }
  }
}

TEST(LinearStability, DeterminantVanishesAtThePaperCutoff) {
  for (const Physics p : {Physics{4e-4, 0.01}, Physics{2e-3, 0.05}, Physics{0.01, 0.3}}) {
    const double eps = 4.0 * p.q / p.K;
    for (const int k : {1, 3, 50, 79, 80, 400}) {
      const double kx = 2.0 * kPi * k;
      const cd det = granvv::hydro::hcs_linear_operator(p, k).determinant();
      const double expected = -kx * kx * (p.K * kx * kx - eps);
      // Cofactor expansion of a 3x3: rounding ~1e-16 of the largest product, kx^2 max(eps, Kkx^2).
      const double scale = kx * kx * std::max(eps, p.K * kx * kx);
      EXPECT_NEAR(det.real(), expected, 1e-13 * scale) << "k = " << k;
      EXPECT_NEAR(det.imag(), 0.0, 1e-13 * scale);
    }
    // At the real wave number K kx = 2 sqrt(q) (pi k K = sqrt(q)) one rate is zero and it
    // changes sign across it. Eigenvalue error ~1e-16 ||A||; demand |rate| < 1e-11 ||A||.
    const double kc = 2.0 * std::sqrt(p.q) / p.K;
    const auto at = [&](double kx) {
      const auto modes = granvv::hydro::hcs_modes_kx(p, kx);
      const auto smallest = std::min_element(modes.begin(), modes.end(), [](auto& a, auto& b) {
        return std::abs(a.rate) < std::abs(b.rate);
      });
      return smallest->rate;
    };
    const double norm = granvv::hydro::hcs_linear_operator_kx(p, kc).norm();
    EXPECT_LT(std::abs(at(kc)), 1e-11 * norm);
    EXPECT_GT(at(kc * (1.0 - 1e-4)).real(), 0.0);
    EXPECT_LT(at(kc * (1.0 + 1e-4)).real(), 0.0);
  }
}

// pi k K < c sqrt(q) decided in long double (about 19 digits); 0 when too close to call.
int paper_criterion(const Physics& p, int k, long double c) {
  const long double lhs = kPiL * kPiL * k * k * static_cast<long double>(p.K) * p.K;
  const long double rhs = c * c * static_cast<long double>(p.q);
  if (std::fabs(lhs - rhs) < 1e-17L * rhs) return 0;
  return lhs < rhs ? 1 : -1;
}

TEST(LinearStability, LargestRateIsPositiveExactlyForThePaperUnstableModes) {
  // Valid for q < 1/3 (Routh-Hurwitz, see header). Modes with a rate below 1e-9 ||A|| are too
  // close to marginal for the eigen-solver's sign and are skipped (none for these parameters).
  for (const Physics p :
       {Physics{4e-4, 0.01}, Physics{1e-3, 0.05}, Physics{0.01, 0.3}, Physics{2e-4, 1e-4}}) {
    int checked = 0;
    const int cutoff = static_cast<int>(granvv::hydro::clustering_cutoff_mode(p));
    for (int k = 1; k <= 2 * cutoff + 5; ++k) {
      const auto modes = granvv::hydro::hcs_modes(p, k);
      const double rate = max_real_rate(modes);
      if (std::abs(rate) < 1e-9 * granvv::hydro::hcs_linear_operator(p, k).norm()) continue;
      ++checked;
      EXPECT_EQ(rate > 0.0, paper_criterion(p, k, 1.0L) > 0)
          << "K=" << p.K << " q=" << p.q << " k=" << k << " rate=" << rate;
    }
    EXPECT_GT(checked, cutoff);
  }
}

TEST(LinearStability, StrongInelasticityAddsAnOscillatoryUnstableBand) {
  // Routh-Hurwitz: just above the cutoff a complex pair is unstable iff q > 1/3; scanning
  // kx in (kc, 4 kc) shows it (q = 0.45) or its absence (q = 0.3).
  const auto scan = [](const Physics& p) {
    const double kc = 2.0 * std::sqrt(p.q) / p.K;
    double worst = -1e300;
    cd rate;
    for (int i = 1; i <= 3000; ++i) {
      const auto modes = granvv::hydro::hcs_modes_kx(p, kc * (1.0 + i * 1e-3));
      if (modes[0].rate.real() > worst) {
        worst = modes[0].rate.real();
        rate = modes[0].rate;
      }
    }
    return rate;
  };
  const cd strong = scan(Physics{0.01, 0.45});
  EXPECT_GT(strong.real(), 0.0);
  EXPECT_GT(std::abs(strong.imag()), 0.0);
  EXPECT_LT(scan(Physics{0.01, 0.3}).real(), 0.0);
}

TEST(LinearStability, ModeCountsFollowThePaperCriterion) {
  EXPECT_EQ(granvv::hydro::clustering_unstable_modes(Physics{4e-4, 0.01}), 79);  // paper Fig. 1
  EXPECT_EQ(granvv::hydro::shear_unstable_modes(Physics{4e-4, 0.01}), 159);      // 2 sqrt(q)/(pi K)
  EXPECT_EQ(granvv::hydro::clustering_unstable_modes(Physics{4e-4, 0.0}), 0);
  EXPECT_FALSE(granvv::hydro::clustering_mode_unstable(Physics{4e-4, 0.01}, 0));
  EXPECT_TRUE(granvv::hydro::clustering_mode_unstable(Physics{4e-4, 0.01}, -79));
  EXPECT_THROW(granvv::hydro::clustering_unstable_modes(Physics{0.0, 0.01}), std::invalid_argument);
  EXPECT_THROW(granvv::hydro::clustering_unstable_modes(Physics{1e-12, 0.4}), std::overflow_error);

  // K placed on the boundary of mode k by rounding sqrt(q)/(pi k) to double: the predicates
  // must agree with the long-double evaluation of the same inequality whenever that one can
  // decide (margin above 1e-17 relative); counts must equal brute-force counts.
  int decided = 0;
  for (const double q : {0.01, 0.02, 1e-4, 0.3, 0.123456}) {
    for (int k = 1; k <= 300; ++k) {
      for (const double c : {1.0, 2.0}) {
        const double K = c * std::sqrt(q) / (kPi * k);
        const Physics p{K, q};
        const int expected = paper_criterion(p, k, c);
        const bool unstable = c == 1.0 ? granvv::hydro::clustering_mode_unstable(p, k)
                                       : granvv::hydro::shear_mode_unstable(p, k);
        if (expected != 0) {
          ++decided;
          EXPECT_EQ(unstable, expected > 0) << "q=" << q << " k=" << k << " c=" << c;
        }
        int brute = 0;
        for (int m = 1; m <= k + 2; ++m) brute += paper_criterion(p, m, c) > 0 ? 1 : 0;
        if (expected != 0) {
          EXPECT_EQ(c == 1.0 ? granvv::hydro::clustering_unstable_modes(p)
                             : granvv::hydro::shear_unstable_modes(p),
                    brute)
              << "q=" << q << " k=" << k << " c=" << c;
        }
      }
    }
  }
  EXPECT_GT(decided, 2500);  // of 3000 boundary cases
}

TEST(LinearStability, LongWaveLimitOfTheThreeRates) {
  // kx << eps = 4q/K and K kx^2 << eps (K -> 0 at fixed q, k): second-order perturbation theory
  // around A(kx = 0) = [[0,0,0],[0,eps,0],[-2eps,0,-eps]] gives
  //   velocity mode    eps - kx^2 (K/4 + 1/(2 eps))      (u = const: motion by inertia)
  //   density mode     -kx^2/eps                         (eigenvector theta = -2 nu)
  //   temperature mode -eps + kx^2 (3/(2 eps) - K).
  // The next terms are O(kx^4/eps^3); the tolerance is 4 kx^4/eps^3 (+ rounding 1e-15 eps).
  const double q = 0.01;
  for (const double K : {1e-3, 1e-4, 1e-5}) {
    for (const int k : {1, 2}) {
      const Physics p{K, q};
      const double eps = 4.0 * q / K;
      const double kx = 2.0 * kPi * k;
      const auto modes = granvv::hydro::hcs_modes(p, k);
      const std::array<double, 3> expected = {eps - kx * kx * (K / 4 + 0.5 / eps), -kx * kx / eps,
                                              -eps + kx * kx * (1.5 / eps - K)};
      const double tol = 4.0 * std::pow(kx, 4) / std::pow(eps, 3) + 1e-15 * eps;
      for (int m = 0; m < 3; ++m) {
        EXPECT_NEAR(modes[m].rate.real(), expected[m], tol)
            << "K=" << K << " k=" << k << " m=" << m;
        EXPECT_NEAR(modes[m].rate.imag(), 0.0, tol);
      }
      // Density mode: theta = -2 nu (denser gas cools faster), w = O(kx/eps).
      EXPECT_NEAR(std::abs(modes[1].eigenvector(2) / modes[1].eigenvector(0) + 2.0), 0.0,
                  10.0 * kx * kx / (eps * eps));
    }
  }
}

TEST(LinearStability, ShortWaveLimitIsSoundPlusClusteringMode) {
  // eps << kx << 1/K: sound +-i sqrt(2) kx - eps/4 - 3 K kx^2/8 and the clustering mode
  // (eps - K kx^2)/2 with nu = -theta. First-order perturbation theory; the neglected second
  // order is O(b^2/kx) with b = eps + K kx^2, which is the tolerance.
  for (const Physics p : {Physics{1e-6, 1e-6}, Physics{1e-7, 2.5e-8}}) {
    for (const int k : {300, 500, 1000}) {
      const double eps = 4.0 * p.q / p.K;
      const double kx = 2.0 * kPi * k;
      const double b = eps + p.K * kx * kx;
      const double tol = b * b / kx;
      ASSERT_LT(tol, 0.2 * b) << "not in the short-wave regime";
      const auto modes = granvv::hydro::hcs_modes(p, k);
      const double sound_damping = -eps / 4 - 3 * p.K * kx * kx / 8;
      const double clustering = (eps - p.K * kx * kx) / 2;
      // The clustering mode is the one that does not oscillate.
      int c = 0;
      for (int m = 1; m < 3; ++m) {
        if (std::abs(modes[m].rate.imag()) < std::abs(modes[c].rate.imag())) c = m;
      }
      EXPECT_NEAR(modes[c].rate.real(), clustering, tol) << "k=" << k;
      EXPECT_NEAR(modes[c].rate.imag(), 0.0, tol);
      EXPECT_NEAR(std::abs(modes[c].eigenvector(0) + modes[c].eigenvector(2)), 0.0, 2.0 * b / kx);
      for (int m = 0; m < 3; ++m) {
        if (m == c) continue;
        EXPECT_NEAR(modes[m].rate.real(), sound_damping, tol) << "k=" << k;
        EXPECT_NEAR(std::abs(modes[m].rate.imag()), std::sqrt(2.0) * kx, tol);
      }
    }
  }
}

TEST(LinearStability, ModesAreNormalisedSortedEigenpairs) {
  for (const int k : {0, 1, 10, 79, 80, 1000}) {
    const Physics p{4e-4, 0.01};
    const Eigen::Matrix3cd A = granvv::hydro::hcs_linear_operator(p, k);
    const auto modes = granvv::hydro::hcs_modes(p, k);
    for (int m = 0; m < 3; ++m) {
      const Vec& v = modes[m].eigenvector;
      EXPECT_LT((A * v - modes[m].rate * v).norm(), 1e-12 * A.norm()) << "k=" << k << " m=" << m;
      EXPECT_NEAR(v.cwiseAbs().maxCoeff(), 1.0, 1e-12);
      bool has_unit_pivot = false;
      for (int i = 0; i < 3; ++i) has_unit_pivot = has_unit_pivot || v(i) == cd(1.0, 0.0);
      EXPECT_TRUE(has_unit_pivot);
      if (m > 0) {
        EXPECT_GE(modes[m - 1].rate.real(), modes[m].rate.real());
      }
    }
  }
}

TEST(LinearStability, ShearRateAndCutoff) {
  const Physics p{4e-4, 0.01};
  const double eps = 100.0;
  for (const int k : {1, 100, 159, 160}) {
    const double kx = 2.0 * kPi * k;
    EXPECT_NEAR(granvv::hydro::shear_rate(p, k), eps - p.K * kx * kx / 4.0, 1e-12 * eps);
    EXPECT_EQ(granvv::hydro::shear_rate(p, k) > 0.0, granvv::hydro::shear_mode_unstable(p, k));
  }
  // The shear cutoff is twice the clustering cutoff: K kx = 4 sqrt(q).
  EXPECT_DOUBLE_EQ(granvv::hydro::shear_cutoff_mode(p),
                   2.0 * granvv::hydro::clustering_cutoff_mode(p));
}

TEST(LinearStability, EvolutionMatchesRungeKuttaInTheCollisionClock) {
  // RK4 with h ||A|| <= 2e-3: global error ~ (h ||A||)^4 ||A|| s / 120 < 1e-11 relative.
  const Vec initial(cd(1e-3, 0.0), cd(-2e-3, 5e-4), cd(0.0, 7e-4));
  for (const Physics p : {Physics{4e-4, 0.01}, Physics{1e-2, 0.2}}) {
    for (const int k : {1, 10, 79, 120}) {
      const Eigen::Matrix3cd A = granvv::hydro::hcs_linear_operator(p, k);
      for (const double s : {0.002, 0.03}) {
        const int n = static_cast<int>(std::ceil(s * A.norm() / 2e-3));
        const Vec reference = granvv::testing::rk4<Vec>(
            [&](double, const Vec& y) -> Vec { return A * y; }, initial, 0.0, s, n);
        const Vec evolved = granvv::hydro::hcs_linear_evolution(p, k, initial, s);
        EXPECT_LT((evolved - reference).norm(), 1e-10 * reference.norm())
            << "K=" << p.K << " k=" << k << " s=" << s;
      }
    }
  }
}

TEST(LinearStability, EigenmodesGrowAlgebraicallyInPhysicalTime) {
  // The linearised equations in physical time t and velocity u (derived from Eqs. 1-2 without
  // the collision clock):
  //   nu_t = -i kx u,  u_t = -i kx T_H (nu + theta) - (K/4) T_H^{1/2} kx^2 u,
  //   theta_t = -i kx u - K T_H^{1/2} kx^2 theta - (8q/K) T_H^{1/2} (nu + theta/2).
  // An eigenmode (nu, w, theta) of A must evolve as (1 + t/t0)^{lambda t0} (nu, w, theta) with
  // w = u / T_H^{1/2}. RK4 with h = 1e-3 t0 / max(1, kx t0): error << 1e-9.
  const Physics p{4e-4, 0.01};
  const double t0 = granvv::hydro::haff_time_scale(p);
  for (const int k : {1, 30, 79, 100}) {
    const double kx = 2.0 * kPi * k;
    const cd ik(0.0, kx);
    const auto rhs = [&](double t, const Vec& y) -> Vec {
      const double TH = granvv::hydro::haff_temperature(t, t0);
      const double sq = std::sqrt(TH);
      Vec r;
      r(0) = -ik * y(1);
      r(1) = -ik * TH * (y(0) + y(2)) - 0.25 * p.K * sq * kx * kx * y(1);
      r(2) = -ik * y(1) - p.K * sq * kx * kx * y(2) - 8.0 * p.q / p.K * sq * (y(0) + 0.5 * y(2));
      return r;
    };
    for (const auto& mode : granvv::hydro::hcs_modes(p, k)) {
      const double t = 2.0 * t0;
      const int steps = static_cast<int>(2000.0 * std::max(1.0, kx * t0) * t / t0);
      Vec y = granvv::testing::rk4<Vec>(rhs, mode.eigenvector, 0.0, t, steps);  // u = w at t = 0
      y(1) /= std::sqrt(granvv::hydro::haff_temperature(t, t0));
      const cd factor = std::pow(cd(1.0 + t / t0), mode.rate * t0);
      EXPECT_LT((y - factor * mode.eigenvector).norm(), 1e-9 * std::abs(factor))
          << "k=" << k << " rate=" << mode.rate;
      const Vec evolved = granvv::hydro::hcs_linear_evolution(
          p, k, mode.eigenvector, granvv::hydro::collision_clock(t, t0));
      EXPECT_LT((evolved - factor * mode.eigenvector).norm(), 1e-11 * std::abs(factor));
    }
  }
}

}  // namespace
