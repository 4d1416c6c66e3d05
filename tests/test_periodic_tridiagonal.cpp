// The O(N) periodic tridiagonal solver (hydro/periodic_tridiagonal) against a dense LDL^T solve
// of the same matrix (Eigen), on well-conditioned and on badly scaled SPD systems like the
// scheme's (coefficients spread over many decades in a density peak), and its refusals.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <vector>

#include "hydro/periodic_tridiagonal.hpp"

namespace {

using granvv::hydro::PeriodicTridiagonalSolver;

struct System {
  std::vector<double> diag, upper, rhs;
};

Eigen::MatrixXd dense(const System& s) {
  const int n = static_cast<int>(s.diag.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    a(i, i) = s.diag[i];
    a(i, j) += s.upper[i];
    a(j, i) += s.upper[i];
  }
  return a;
}

// A periodic SPD system shaped like the scheme's: a mass term m_i > 0 plus a sum of positive
// couplings g_i between neighbours (A = M + sum g_i (e_i - e_{i+1})(e_i - e_{i+1})^T), with log10
// of m and g uniform over `decades`.
System scheme_like(int n, double decades, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, decades);
  System s{std::vector<double>(n), std::vector<double>(n), std::vector<double>(n)};
  std::vector<double> g(n);
  for (int i = 0; i < n; ++i) g[i] = std::pow(10.0, u(rng));
  for (int i = 0; i < n; ++i) {
    const int l = (i + n - 1) % n;
    s.diag[i] = std::pow(10.0, u(rng)) + g[i] + g[l];
    s.upper[i] = -g[i];
    s.rhs[i] = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
  }
  return s;
}

double max_abs(const Eigen::VectorXd& v) {
  return v.cwiseAbs().maxCoeff();
}

TEST(PeriodicTridiagonal, MatchesDenseSolveOnWellConditionedSystems) {
  // Two decades of spread: condition numbers below ~1e3, so forward errors of a backward-stable
  // solve stay below 1e3 * 1e-16; 1e-12 leaves a margin of ten.
  for (int n : {3, 4, 7, 64, 501}) {
    const System s = scheme_like(n, 2.0, 17 + n);
    PeriodicTridiagonalSolver solver(n);
    ASSERT_TRUE(solver.factorize(s.diag, s.upper)) << n;
    std::vector<double> x;
    solver.solve(s.rhs, x);
    const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(s.rhs.data(), n);
    const Eigen::VectorXd exact = dense(s).ldlt().solve(b);
    const Eigen::VectorXd got = Eigen::Map<const Eigen::VectorXd>(x.data(), n);
    EXPECT_LE(max_abs(got - exact) / max_abs(exact), 1e-12) << "n = " << n;
  }
}

TEST(PeriodicTridiagonal, BackwardStableOnBadlyScaledSystems) {
  // Twelve decades of spread, as between the thin cells of a density peak and the rest: the
  // residual relative to |A| |x| must be at round-off (a few 1e-16; bound 1e-13).
  const int n = 2000;
  for (unsigned seed : {1u, 2u, 3u}) {
    const System s = scheme_like(n, 12.0, seed);
    PeriodicTridiagonalSolver solver(n);
    ASSERT_TRUE(solver.factorize(s.diag, s.upper));
    std::vector<double> x;
    solver.solve(s.rhs, x);
    const Eigen::MatrixXd a = dense(s);
    const Eigen::VectorXd xv = Eigen::Map<const Eigen::VectorXd>(x.data(), n);
    const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(s.rhs.data(), n);
    const Eigen::VectorXd scale = a.cwiseAbs() * xv.cwiseAbs() + b.cwiseAbs();
    EXPECT_LE(((a * xv - b).cwiseAbs().array() / scale.array()).maxCoeff(), 1e-13) << seed;
  }
}

TEST(PeriodicTridiagonal, SolvesInPlaceAndRepeatsWithOneFactorisation) {
  const int n = 50;
  const System s = scheme_like(n, 3.0, 5);
  PeriodicTridiagonalSolver solver(n);
  ASSERT_TRUE(solver.factorize(s.diag, s.upper));
  std::vector<double> apart, inplace = s.rhs;
  solver.solve(s.rhs, apart);
  solver.solve(inplace, inplace);
  for (int i = 0; i < n; ++i) EXPECT_EQ(apart[i], inplace[i]);
}

TEST(PeriodicTridiagonal, RefusesMatricesThatAreNotPositiveDefinite) {
  PeriodicTridiagonalSolver solver(5);
  // The periodic second difference with a zero mass term is singular (constants in its kernel).
  EXPECT_FALSE(solver.factorize(std::vector<double>(5, 2.0), std::vector<double>(5, -1.0)));
  // Indefinite: a negative diagonal entry away from the corner.
  std::vector<double> diag(5, 4.0);
  diag[2] = -1.0;
  EXPECT_FALSE(solver.factorize(diag, std::vector<double>(5, -1.0)));
  // Indefinite only through the corner: diag 2.5 with upper -1 is SPD as a plain tridiagonal
  // matrix (smallest eigenvalue 0.77) and still with corner +2 (0.086), but not with corner
  // +3 (smallest eigenvalue -0.80; numpy.linalg.eigvalsh).
  std::vector<double> upper(5, -1.0);
  upper[4] = 2.0;
  EXPECT_TRUE(solver.factorize(std::vector<double>(5, 2.5), upper));
  upper[4] = 3.0;
  EXPECT_FALSE(solver.factorize(std::vector<double>(5, 2.5), upper));
  // A positive-definite one is accepted after the refusals.
  EXPECT_TRUE(solver.factorize(std::vector<double>(5, 4.0), std::vector<double>(5, -1.0)));
}

}  // namespace
