#pragma once
// Symmetric positive-definite periodic tridiagonal systems solved several at a time, for the
// implicit parts of the Lagrangian scheme (hydro/lagrangian_operator). The factorisation of such a
// system is a chain of dependent divisions, one per row, so a single system runs at the latency of
// the divider; K independent systems factorised in one sweep keep K chains in flight at once.
//
// Factorisation, in the natural order of the unknowns: A = L D L^T (Cholesky without square
// roots, backward stable for any SPD matrix), with L unit lower bidiagonal, l_i = L(i+1, i), except
// that the periodic corner A(n-1, 0) fills the last row of L: the spike s_i = L(n-1, i). For
// i < n-2 (A(i, i+1) = e_i, corner c = A(n-1, 0)):
//   d_0 = A(0,0),  d_i = A(i,i) - e_{i-1}^2 / d_{i-1},  l_i = e_i / d_i,
//   s_0 = c / d_0,  s_i = -s_{i-1} e_{i-1} / d_i,  s_{n-2} = (e_{n-2} - s_{n-3} e_{n-3}) / d_{n-2},
//   d_{n-1} = A(n-1,n-1) - sum_{i<n-1} s_i^2 d_i.
// This is the Sherman-Morrison treatment of the corner (hydro/periodic_tridiagonal) written as one
// elimination: no second solve for the correction vector. A is positive definite exactly when
// every d_i > 0.
#include <array>
#include <cstddef>
#include <vector>

namespace granvv::hydro {

// A(i,i) = diag[i], A(i,i+1) = A(i+1,i) = upper[i], i+1 taken mod n (upper[n-1] is the corner).
struct PeriodicTridiagonalView {
  const double* diag;
  const double* upper;
};

// The factors L D L^T of one periodic system of n unknowns (header comment).
struct PeriodicLdlFactors {
  std::vector<double> inverse_pivot;    // 1 / d_i, n entries
  std::vector<double> multiplier;       // l_i, i < n - 2
  std::vector<double> multiplier_pair;  // l_i l_{i+1}, i < n - 3 (two rows per step of a solve)
  std::vector<double> spike;            // s_i, i < n - 1
};

// Factorise K independent systems of n >= 3 unknowns in one interleaved sweep. Returns false if
// any of them is not positive definite (its factors are then meaningless). With first_rhs, the
// forward half of the first system's solve (L y = b, on first_rhs in place) runs in the same
// sweep, its chain beside the factorisation's; back_substitute_periodic completes it, bitwise as
// solve_periodic would.
template <std::size_t K>
bool factorize_periodic(int n, const std::array<PeriodicTridiagonalView, K>& systems,
                        const std::array<PeriodicLdlFactors*, K>& factors,
                        double* first_rhs = nullptr);

// Solve K independent systems in place: x[k] holds the right-hand side on entry, the solution on
// return (forward sweep L y = b, scaling by 1/d, back sweep L^T x = D^-1 y, each sweep two rows
// at a time so that even and odd rows form two independent chains).
template <std::size_t K>
void solve_periodic(int n, const std::array<const PeriodicLdlFactors*, K>& factors,
                    const std::array<double*, K>& x);
// The second half of solve_periodic, on x as the forward half (factorize_periodic's first_rhs)
// left it.
template <std::size_t K>
void back_substitute_periodic(int n, const std::array<const PeriodicLdlFactors*, K>& factors,
                              const std::array<double*, K>& x);

}  // namespace granvv::hydro
