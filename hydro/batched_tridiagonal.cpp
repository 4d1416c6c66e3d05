#include "hydro/batched_tridiagonal.hpp"

#include <cmath>

namespace granvv::hydro {

template <std::size_t K>
bool factorize_periodic(int n, const std::array<PeriodicTridiagonalView, K>& systems,
                        const std::array<PeriodicLdlFactors*, K>& factors) {
  std::array<const double*, K> a, e;
  std::array<double*, K> r, l, q, s;
  std::array<double, K> pivot, spike, last;
  bool positive = true;
  for (std::size_t k = 0; k < K; ++k) {
    PeriodicLdlFactors& f = *factors[k];
    f.inverse_pivot.resize(n);
    f.multiplier.resize(n - 2);
    f.multiplier_pair.resize(n - 3);
    f.spike.resize(n - 1);
    a[k] = systems[k].diag;
    e[k] = systems[k].upper;
    r[k] = f.inverse_pivot.data();
    l[k] = f.multiplier.data();
    q[k] = f.multiplier_pair.data();
    s[k] = f.spike.data();
    pivot[k] = a[k][0];
    positive &= pivot[k] > 0.0;
    const double corner = e[k][n - 1];
    r[k][0] = 1.0 / pivot[k];
    l[k][0] = e[k][0] * r[k][0];
    spike[k] = corner * r[k][0];
    s[k][0] = spike[k];
    last[k] = a[k][n - 1] - spike[k] * corner;
  }
  // Row i's multiplier, pair product and spike, once 1/d_i is known (values kept in registers:
  // the factor arrays are written, never read back).
  std::array<double, K> multiplier;  // l_{i-1}
  for (std::size_t k = 0; k < K; ++k) multiplier[k] = l[k][0];
  const auto finish_row = [&](std::size_t k, int i, double inverse) {
    r[k][i] = inverse;
    const double li = e[k][i] * inverse;
    l[k][i] = li;
    q[k][i - 1] = multiplier[k] * li;
    multiplier[k] = li;
    const double fill = -spike[k] * e[k][i - 1];  // s_i d_i
    spike[k] = fill * inverse;
    s[k][i] = spike[k];
    last[k] -= fill * spike[k];
  };
  // The K chains d_{i-1} -> d_i are independent: one pass over the rows keeps them all in flight.
  // Each chain takes two rows per division on it: with d_i d_{i-1} = A(i,i) d_{i-1} - e_{i-1}^2,
  //   1/d_i = d_{i-1} / (A(i,i) d_{i-1} - e_{i-1}^2),  d_{i+1} = A(i+1,i+1) - e_i^2 / d_i,
  // and 1/d_{i+1} is divided off the chain (a relative perturbation of A(i,i) and e_{i-1} per
  // rounding, as in the row-by-row recurrence: backward stable alike).
  int i = 1;
  for (; i + 3 < n; i += 2) {
#pragma GCC unroll 4
    for (std::size_t k = 0; k < K; ++k) {
      const double before = e[k][i - 1], coupling = e[k][i];
      const double product = a[k][i] * pivot[k] - before * before;  // d_i d_{i-1}
      const double inverse = pivot[k] / product;
      pivot[k] = a[k][i + 1] - (coupling * coupling) * inverse;
      positive &= (inverse > 0.0) & (pivot[k] > 0.0);
      finish_row(k, i, inverse);
      finish_row(k, i + 1, 1.0 / pivot[k]);
    }
  }
  if (i + 2 < n) {  // one row left before n - 2
    for (std::size_t k = 0; k < K; ++k) {
      const double coupling = e[k][i - 1];
      pivot[k] = a[k][i] - (coupling * coupling) * r[k][i - 1];
      positive &= pivot[k] > 0.0;
      finish_row(k, i, 1.0 / pivot[k]);
    }
  }
  for (std::size_t k = 0; k < K; ++k) {
    const int i = n - 2;
    const double coupling = e[k][i - 1];
    pivot[k] = a[k][i] - (coupling * coupling) * r[k][i - 1];
    positive &= pivot[k] > 0.0;
    r[k][i] = 1.0 / pivot[k];
    const double fill = e[k][i] - spike[k] * coupling;  // s_{n-2} d_{n-2}
    s[k][i] = fill * r[k][i];
    last[k] -= fill * s[k][i];
    positive &= last[k] > 0.0 && std::isfinite(last[k]);
    r[k][n - 1] = 1.0 / last[k];
  }
  return positive;
}

template <std::size_t K>
void solve_periodic(int n, const std::array<const PeriodicLdlFactors*, K>& factors,
                    const std::array<double*, K>& x) {
  std::array<const double*, K> r, l, q, s;
  std::array<double, K> even, odd, sum_even, sum_odd, carried, x_last;
  // L y = b. Row by row, y_i = b_i - l_{i-1} y_{i-1} is one chain of dependent multiply-adds;
  // two rows at once, y_i = (b_i - l_{i-1} b_{i-1}) + l_{i-1} l_{i-2} y_{i-2}, are two chains
  // (even and odd rows) of half the length. The spike row is a sum, also split in two.
  for (std::size_t k = 0; k < K; ++k) {
    r[k] = factors[k]->inverse_pivot.data();
    l[k] = factors[k]->multiplier.data();
    q[k] = factors[k]->multiplier_pair.data();
    s[k] = factors[k]->spike.data();
    even[k] = x[k][0];
    carried[k] = x[k][1];  // b_1
    odd[k] = carried[k] - l[k][0] * even[k];
    x[k][1] = odd[k];
    sum_even[k] = s[k][0] * even[k];
    sum_odd[k] = s[k][1] * odd[k];
  }
  int i = 2;
  for (; i + 1 <= n - 2; i += 2) {
    for (std::size_t k = 0; k < K; ++k) {
      const double b = x[k][i], b_next = x[k][i + 1];
      even[k] = (b - l[k][i - 1] * carried[k]) + q[k][i - 2] * even[k];
      odd[k] = (b_next - l[k][i] * b) + q[k][i - 1] * odd[k];
      x[k][i] = even[k];
      x[k][i + 1] = odd[k];
      sum_even[k] += s[k][i] * even[k];
      sum_odd[k] += s[k][i + 1] * odd[k];
      carried[k] = b_next;
    }
  }
  if (i == n - 2) {
    for (std::size_t k = 0; k < K; ++k) {
      even[k] = x[k][i] - l[k][i - 1] * odd[k];
      x[k][i] = even[k];
      sum_even[k] += s[k][i] * even[k];
    }
  }
  // L^T x = D^-1 y, from the last unknown upwards, with g_i = y_i / d_i - s_i x_{n-1}:
  // x_i = g_i - l_i x_{i+1} = (g_i - l_i g_{i+1}) + l_i l_{i+1} x_{i+2}, again two chains.
  const auto g = [&](std::size_t k, int row) {
    return x[k][row] * r[k][row] - s[k][row] * x_last[k];
  };
  for (std::size_t k = 0; k < K; ++k) {
    x_last[k] = (x[k][n - 1] - (sum_even[k] + sum_odd[k])) * r[k][n - 1];
    x[k][n - 1] = x_last[k];
    even[k] = g(k, n - 2);  // x_{n-2}
    x[k][n - 2] = even[k];
    carried[k] = g(k, n - 3);
    odd[k] = carried[k] - l[k][n - 3] * even[k];  // x_{n-3}
    x[k][n - 3] = odd[k];
  }
  i = n - 4;
  for (; i >= 1; i -= 2) {
    for (std::size_t k = 0; k < K; ++k) {
      const double g_i = g(k, i), g_before = g(k, i - 1);
      even[k] = (g_i - l[k][i] * carried[k]) + q[k][i] * even[k];
      odd[k] = (g_before - l[k][i - 1] * g_i) + q[k][i - 1] * odd[k];
      x[k][i] = even[k];
      x[k][i - 1] = odd[k];
      carried[k] = g_before;
    }
  }
  if (i == 0) {
    for (std::size_t k = 0; k < K; ++k) x[k][0] = g(k, 0) - l[k][0] * odd[k];
  }
}

template bool factorize_periodic<1>(int, const std::array<PeriodicTridiagonalView, 1>&,
                                    const std::array<PeriodicLdlFactors*, 1>&);
template bool factorize_periodic<2>(int, const std::array<PeriodicTridiagonalView, 2>&,
                                    const std::array<PeriodicLdlFactors*, 2>&);
template bool factorize_periodic<3>(int, const std::array<PeriodicTridiagonalView, 3>&,
                                    const std::array<PeriodicLdlFactors*, 3>&);
template void solve_periodic<1>(int, const std::array<const PeriodicLdlFactors*, 1>&,
                                const std::array<double*, 1>&);
template void solve_periodic<2>(int, const std::array<const PeriodicLdlFactors*, 2>&,
                                const std::array<double*, 2>&);
template void solve_periodic<3>(int, const std::array<const PeriodicLdlFactors*, 3>&,
                                const std::array<double*, 3>&);

}  // namespace granvv::hydro
