// The batched periodic LDL^T solver (hydro/batched_tridiagonal) against LAPACK as the oracle:
// dpttrf/dpttrs with the Sherman-Morrison corner correction (hydro/periodic_tridiagonal), on
// random SPD periodic systems, diagonally dominant and nearly singular, small and large.
//
// Tolerance. Both solvers are backward stable: each returns the exact solution of a system whose
// matrix and right side are perturbed by a relative amount eta (the normwise backward error,
// measured here). Two such solutions differ by at most about 2 kappa (eta_1 + eta_2) relative to
// |x| (Rigal-Gaches perturbation bound; |b| <= |A| |x|), with kappa the condition number. kappa is
// bounded from the construction of the matrix (A = M + a graph Laplacian, so
// lambda_min >= min m_i and lambda_max <= |A|_inf), and eta is checked to be at round-off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "hydro/batched_tridiagonal.hpp"
#include "hydro/periodic_tridiagonal.hpp"

namespace {

using granvv::hydro::back_substitute_periodic;
using granvv::hydro::factorize_periodic;
using granvv::hydro::PeriodicLdlFactors;
using granvv::hydro::PeriodicTridiagonalSolver;
using granvv::hydro::PeriodicTridiagonalView;
using granvv::hydro::solve_periodic;

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

struct System {
  std::vector<double> diag, upper, rhs;
  double smallest_eigenvalue_bound = 0.0;
  int size() const { return static_cast<int>(diag.size()); }
  PeriodicTridiagonalView view() const { return {diag.data(), upper.data()}; }
};

// A = M + sum_i g_i (e_i - e_{i+1})(e_i - e_{i+1})^T (periodic), the form of the scheme's
// matrices, with m_i = mass_scale * U(1, 2) and g_i = 10^U(0, coupling_decades). The Laplacian
// part is positive semi-definite, so lambda_min >= min m_i. A random sign of each coupling is a
// similarity by a diagonal of +-1 only when n is even; odd n keeps the scheme's signs.
System random_system(int n, double mass_scale, double coupling_decades, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  System s;
  s.diag.resize(n);
  s.upper.resize(n);
  s.rhs.resize(n);
  std::vector<double> g(n), mass(n);
  for (int i = 0; i < n; ++i) g[i] = std::pow(10.0, coupling_decades * unit(rng));
  for (int i = 0; i < n; ++i) mass[i] = mass_scale * (1.0 + unit(rng));
  for (int i = 0; i < n; ++i) {
    const int l = (i + n - 1) % n;
    s.diag[i] = mass[i] + g[i] + g[l];
    const bool flip = n % 2 == 0 && unit(rng) < 0.5;
    s.upper[i] = flip ? g[i] : -g[i];
    s.rhs[i] = 2.0 * unit(rng) - 1.0;
  }
  s.smallest_eigenvalue_bound = *std::min_element(mass.begin(), mass.end());
  return s;
}

std::vector<double> multiply(const System& s, const std::vector<double>& x) {
  const int n = s.size();
  std::vector<double> y(n);
  for (int i = 0; i < n; ++i) {
    const int l = (i + n - 1) % n, r = (i + 1) % n;
    y[i] = s.diag[i] * x[i] + s.upper[i] * x[r] + s.upper[l] * x[l];
  }
  return y;
}

double norm(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x * x;
  return std::sqrt(sum);
}

double matrix_norm(const System& s) {  // |A|_inf >= |A|_2 for a symmetric matrix
  const int n = s.size();
  double largest = 0.0;
  for (int i = 0; i < n; ++i) {
    largest = std::max(
        largest, std::abs(s.diag[i]) + std::abs(s.upper[i]) + std::abs(s.upper[(i + n - 1) % n]));
  }
  return largest;
}

// Normwise backward error |b - A x| / (|A| |x| + |b|).
double backward_error(const System& s, const std::vector<double>& x) {
  std::vector<double> residual = multiply(s, x);
  for (int i = 0; i < s.size(); ++i) residual[i] -= s.rhs[i];
  return norm(residual) / (matrix_norm(s) * norm(x) + norm(s.rhs));
}

std::vector<double> lapack_solution(const System& s) {
  PeriodicTridiagonalSolver oracle(s.size());
  EXPECT_TRUE(oracle.factorize(s.diag, s.upper));
  std::vector<double> x;
  oracle.solve(s.rhs, x);
  return x;
}

std::vector<double> batched_solution(const System& s) {
  PeriodicLdlFactors factors;
  EXPECT_TRUE(factorize_periodic<1>(s.size(), {s.view()}, {&factors}));
  std::vector<double> x = s.rhs;
  solve_periodic<1>(s.size(), {&factors}, {x.data()});
  return x;
}

void expect_equal_to_oracle(const System& s, const char* what) {
  const int n = s.size();
  const std::vector<double> expected = lapack_solution(s);
  const std::vector<double> got = batched_solution(s);
  const double eta_oracle = backward_error(s, expected), eta = backward_error(s, got);
  // Round-off of a tridiagonal solve: a few rounding errors per row, and the periodic row's sum
  // over n terms; 8 (1 + log2 n) epsilon is a generous bound for both.
  const double round_off = 8.0 * (1.0 + std::log2(double(n))) * kEpsilon;
  EXPECT_LE(eta_oracle, round_off) << what << " n = " << n;
  EXPECT_LE(eta, round_off) << what << " n = " << n;
  const double kappa = matrix_norm(s) / s.smallest_eigenvalue_bound;
  std::vector<double> difference(n);
  for (int i = 0; i < n; ++i) difference[i] = got[i] - expected[i];
  const double bound = 2.0 * kappa * (eta + eta_oracle) / (1.0 - kappa * std::max(eta, eta_oracle));
  EXPECT_LE(norm(difference) / norm(expected), std::max(bound, kEpsilon))
      << what << " n = " << n << " kappa <= " << kappa;
}

TEST(BatchedTridiagonal, EqualsLapackOnDiagonallyDominantSystems) {
  // Mass term comparable to the couplings (one decade of spread): kappa below ~50.
  for (int n : {3, 4, 5, 7, 64, 2000}) {
    for (unsigned seed : {1u, 2u, 3u}) {
      expect_equal_to_oracle(random_system(n, 1.0, 1.0, 100 * n + seed), "dominant");
    }
  }
}

TEST(BatchedTridiagonal, EqualsLapackOnNearlySingularSystems) {
  // Mass term 1e-6 of the couplings, which spread over four decades (a density peak's thin cells
  // next to wide ones): kappa up to ~1e10, so the two solutions may differ far above epsilon,
  // within the bound the backward errors give.
  for (int n : {3, 4, 5, 7, 64, 2000}) {
    for (unsigned seed : {1u, 2u, 3u}) {
      expect_equal_to_oracle(random_system(n, 1e-6, 4.0, 7 * n + seed), "nearly singular");
    }
  }
}

TEST(BatchedTridiagonal, InterleavedSystemsGetTheirOwnSolutionsBitForBit) {
  // Interleaving changes the order in which independent chains run, not their arithmetic.
  const int n = 501;
  const System s1 = random_system(n, 1.0, 2.0, 11), s2 = random_system(n, 1e-3, 3.0, 12),
               s3 = random_system(n, 10.0, 1.0, 13);
  PeriodicLdlFactors f1, f2, f3;
  ASSERT_TRUE(factorize_periodic<3>(n, {s1.view(), s2.view(), s3.view()}, {&f1, &f2, &f3}));
  std::vector<double> x1 = s1.rhs, x2 = s2.rhs, x3 = s3.rhs;
  solve_periodic<2>(n, {&f1, &f2}, {x1.data(), x2.data()});
  solve_periodic<1>(n, {&f3}, {x3.data()});
  EXPECT_EQ(x1, batched_solution(s1));
  EXPECT_EQ(x2, batched_solution(s2));
  EXPECT_EQ(x3, batched_solution(s3));
  PeriodicLdlFactors g1, g2;
  ASSERT_TRUE(factorize_periodic<2>(n, {s1.view(), s2.view()}, {&g1, &g2}));
  EXPECT_EQ(g2.inverse_pivot, f2.inverse_pivot);
  EXPECT_EQ(g2.spike, f2.spike);
}

TEST(BatchedTridiagonal, ForwardSweepInsideTheFactorisationIsTheSolveBitForBit) {
  // The operator's momentum system: its forward sweep runs in the factorisation's sweep
  // (first_rhs), the back substitution after; every size from the smallest, both parities, one
  // to three systems in the sweep.
  for (int n : {3, 4, 5, 6, 7, 8, 9, 64, 65, 2000}) {
    const System s1 = random_system(n, 1.0, 2.0, 5 * n + 1),
                 s2 = random_system(n, 1e-3, 3.0, 5 * n + 2),
                 s3 = random_system(n, 10.0, 1.0, 5 * n + 3);
    const std::vector<double> expected = batched_solution(s1);
    PeriodicLdlFactors f1, f2, f3;
    std::vector<double> x = s1.rhs;
    ASSERT_TRUE(factorize_periodic<1>(n, {s1.view()}, {&f1}, x.data()));
    back_substitute_periodic<1>(n, {&f1}, {x.data()});
    EXPECT_EQ(x, expected) << "1 system, n = " << n;
    x = s1.rhs;
    ASSERT_TRUE(factorize_periodic<2>(n, {s1.view(), s2.view()}, {&f1, &f2}, x.data()));
    back_substitute_periodic<1>(n, {&f1}, {x.data()});
    EXPECT_EQ(x, expected) << "2 systems, n = " << n;
    x = s1.rhs;
    ASSERT_TRUE(
        factorize_periodic<3>(n, {s1.view(), s2.view(), s3.view()}, {&f1, &f2, &f3}, x.data()));
    back_substitute_periodic<1>(n, {&f1}, {x.data()});
    EXPECT_EQ(x, expected) << "3 systems, n = " << n;
    std::vector<double> x2 = s2.rhs;
    solve_periodic<1>(n, {&f2}, {x2.data()});
    EXPECT_EQ(x2, batched_solution(s2)) << "the other system, n = " << n;
  }
}

TEST(BatchedTridiagonal, RefusesMatricesThatAreNotPositiveDefinite) {
  PeriodicLdlFactors f;
  const auto factorizes = [&](std::vector<double> diag, std::vector<double> upper) {
    return factorize_periodic<1>(5, {PeriodicTridiagonalView{diag.data(), upper.data()}}, {&f});
  };
  // The periodic second difference with no mass term is singular (constants in its kernel).
  EXPECT_FALSE(factorizes(std::vector<double>(5, 2.0), std::vector<double>(5, -1.0)));
  // Indefinite through a negative diagonal entry away from the corner.
  std::vector<double> diag(5, 4.0);
  diag[2] = -1.0;
  EXPECT_FALSE(factorizes(diag, std::vector<double>(5, -1.0)));
  // Indefinite only through the corner: diag 2.5, upper -1 is SPD with corner +2 (smallest
  // eigenvalue 0.086) and not with corner +3 (-0.80).
  std::vector<double> upper(5, -1.0);
  upper[4] = 2.0;
  EXPECT_TRUE(factorizes(std::vector<double>(5, 2.5), upper));
  upper[4] = 3.0;
  EXPECT_FALSE(factorizes(std::vector<double>(5, 2.5), upper));
  // One bad system in a batch fails the batch.
  const System good = random_system(5, 1.0, 1.0, 3);
  std::vector<double> singular_diag(5, 2.0), singular_upper(5, -1.0);
  PeriodicLdlFactors f1, f2;
  EXPECT_FALSE(factorize_periodic<2>(
      5, {good.view(), PeriodicTridiagonalView{singular_diag.data(), singular_upper.data()}},
      {&f1, &f2}));
}

}  // namespace
