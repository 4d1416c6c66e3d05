#include "hydro/batched_tridiagonal.hpp"

#include <cstring>
#include <limits>

#include "hydro/wide_loops.hpp"

namespace granvv::hydro {

namespace {

// Two doubles operated on lane by lane (one SSE2 register on x86-64): each lane's arithmetic is
// the scalar arithmetic, rounding for rounding, so packing changes no result. The factorisation
// packs two systems into the lanes, the solve the even and odd rows of one system.
using Pair = double __attribute__((vector_size(16)));
using PairMask = decltype(Pair{} > 0.0);  // lanes of all ones (true) or zeros

Pair load_pair(const double* p) {
  Pair v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
void store_pair(double* p, Pair v) {
  std::memcpy(p, &v, sizeof v);
}
Pair splat(double x) {
  return Pair{x, x};
}

// The systems 2p and 2p + 1 share pack p; an odd K's last pack carries its last system in both
// lanes (the second lane's results are not stored).
template <std::size_t K>
struct Lanes {
  static constexpr std::size_t packs = (K + 1) / 2;
  static constexpr std::size_t system(std::size_t pack, std::size_t lane) {
    return 2 * pack + lane < K ? 2 * pack + lane : K - 1;
  }
  template <typename Array>
  static Pair gather(const Array& rows, std::size_t pack, int i) {
    return Pair{rows[system(pack, 0)][i], rows[system(pack, 1)][i]};
  }
  static void scatter(const std::array<double*, K>& rows, std::size_t pack, int i, Pair v) {
    rows[2 * pack][i] = v[0];
    if (2 * pack + 1 < K) rows[2 * pack + 1][i] = v[1];
  }
};

// The forward half of a solve, L y = b in place on x, two rows per step. Row by row,
// y_i = b_i - l_{i-1} y_{i-1} is one chain of dependent multiply-adds; two rows at once,
// y_i = (b_i - l_{i-1} b_{i-1}) + l_{i-1} l_{i-2} y_{i-2}, are two chains (even and odd rows, the
// two lanes of y) of half the length. The spike row is a sum, also split in two. start() needs
// the factors' rows 0 and 1, each step() the rows up to its second one, finish() all of them;
// the factorisation runs it behind its own sweep (factorize_periodic's first_rhs).
struct ForwardSweep {
  double* x = nullptr;
  const double *l = nullptr, *q = nullptr, *s = nullptr;
  Pair y{}, sum{}, carried{};
  int next = 0;  // the first row of the next pair (0: not started)

  void start(const PeriodicLdlFactors& f, double* rhs) {
    x = rhs;
    l = f.multiplier.data();
    q = f.multiplier_pair.data();
    s = f.spike.data();
    const double b1 = x[1];
    const double y1 = b1 - l[0] * x[0];
    x[1] = y1;
    y = Pair{x[0], y1};
    carried = Pair{0.0, b1};  // (., b_{i-1}) of the first pair of rows
    sum = load_pair(s) * y;
    next = 2;
  }
  void step() {
    const int i = next;
    const Pair b = load_pair(x + i);        // (b_i, b_{i+1})
    const Pair b_before{carried[1], b[0]};  // (b_{i-1}, b_i)
    y = (b - load_pair(l + i - 1) * b_before) + load_pair(q + i - 2) * y;
    store_pair(x + i, y);
    sum += load_pair(s + i) * y;
    carried = b;
    next = i + 2;
  }
  // The remaining rows; row n - 1 is left holding y_{n-1} = b_{n-1} - sum_i s_i y_i.
  void finish(int n) {
    while (next + 1 <= n - 2) step();
    const int i = next;
    if (i == n - 2) {
      const double even = x[i] - l[i - 1] * y[1];
      x[i] = even;
      sum[0] += s[i] * even;
    }
    x[n - 1] = x[n - 1] - (sum[0] + sum[1]);
  }
};

}  // namespace

template <std::size_t K>
GRANVV_WIDE_LOOPS bool factorize_periodic(int n,
                                          const std::array<PeriodicTridiagonalView, K>& systems,
                                          const std::array<PeriodicLdlFactors*, K>& factors,
                                          double* first_rhs) {
  using L = Lanes<K>;
  constexpr std::size_t P = L::packs;
  std::array<const double*, K> a, e;
  std::array<double*, K> r, l, q, s;
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
  }
  // Per pack: d_i, s_i, the running d_{n-1}, l_{i-1}, and whether every pivot so far is > 0.
  std::array<Pair, P> pivot, spike, last, multiplier;
  PairMask positive = {-1, -1};
  ForwardSweep sweep;
  for (std::size_t p = 0; p < P; ++p) {
    pivot[p] = L::gather(a, p, 0);
    positive &= pivot[p] > 0.0;
    const Pair corner = L::gather(e, p, n - 1);
    const Pair inverse = 1.0 / pivot[p];
    L::scatter(r, p, 0, inverse);
    multiplier[p] = L::gather(e, p, 0) * inverse;
    L::scatter(l, p, 0, multiplier[p]);
    spike[p] = corner * inverse;
    L::scatter(s, p, 0, spike[p]);
    last[p] = L::gather(a, p, n - 1) - spike[p] * corner;
  }
  // Row i's multiplier, pair product and spike, once 1/d_i is known (values kept in registers:
  // the factor arrays are written, never read back).
  const auto finish_row = [&](std::size_t p, int i, Pair inverse) {
    L::scatter(r, p, i, inverse);
    const Pair li = L::gather(e, p, i) * inverse;
    L::scatter(l, p, i, li);
    L::scatter(q, p, i - 1, multiplier[p] * li);
    multiplier[p] = li;
    const Pair fill = -spike[p] * L::gather(e, p, i - 1);  // s_i d_i
    spike[p] = fill * inverse;
    L::scatter(s, p, i, spike[p]);
    last[p] -= fill * spike[p];
  };
  // The K chains d_{i-1} -> d_i are independent: one pass over the rows keeps them all in flight,
  // two to a register. Each chain takes two rows per division on it: with
  // d_i d_{i-1} = A(i,i) d_{i-1} - e_{i-1}^2,
  //   1/d_i = d_{i-1} / (A(i,i) d_{i-1} - e_{i-1}^2),  d_{i+1} = A(i+1,i+1) - e_i^2 / d_i,
  // and 1/d_{i+1} is divided off the chain (a relative perturbation of A(i,i) and e_{i-1} per
  // rounding, as in the row-by-row recurrence: backward stable alike).
  int i = 1;
  for (; i + 3 < n; i += 2) {
    for (std::size_t p = 0; p < P; ++p) {
      const Pair before = L::gather(e, p, i - 1), coupling = L::gather(e, p, i);
      const Pair product = L::gather(a, p, i) * pivot[p] - before * before;  // d_i d_{i-1}
      const Pair inverse = pivot[p] / product;
      pivot[p] = L::gather(a, p, i + 1) - (coupling * coupling) * inverse;
      positive &= (inverse > 0.0) & (pivot[p] > 0.0);
      finish_row(p, i, inverse);
      finish_row(p, i + 1, 1.0 / pivot[p]);
    }
    // The first system's forward sweep, a pair of rows behind: rows i - 1 and i.
    if (first_rhs != nullptr) {
      if (i == 1) {
        sweep.start(*factors[0], first_rhs);
      } else {
        sweep.step();
      }
    }
  }
  if (i + 2 < n) {  // one row left before n - 2
    for (std::size_t p = 0; p < P; ++p) {
      const Pair coupling = L::gather(e, p, i - 1);
      pivot[p] = L::gather(a, p, i) - (coupling * coupling) * L::gather(r, p, i - 1);
      positive &= pivot[p] > 0.0;
      finish_row(p, i, 1.0 / pivot[p]);
    }
  }
  constexpr double kLargest = std::numeric_limits<double>::max();
  for (std::size_t p = 0; p < P; ++p) {
    const int i = n - 2;
    const Pair coupling = L::gather(e, p, i - 1);
    pivot[p] = L::gather(a, p, i) - (coupling * coupling) * L::gather(r, p, i - 1);
    positive &= pivot[p] > 0.0;
    const Pair inverse = 1.0 / pivot[p];
    L::scatter(r, p, i, inverse);
    const Pair fill = L::gather(e, p, i) - spike[p] * coupling;  // s_{n-2} d_{n-2}
    const Pair spike_last = fill * inverse;
    L::scatter(s, p, i, spike_last);
    last[p] -= fill * spike_last;
    positive &= (last[p] > 0.0) & (last[p] <= kLargest);  // > 0 and finite
    L::scatter(r, p, n - 1, 1.0 / last[p]);
  }
  if (first_rhs != nullptr) {
    if (sweep.next == 0) sweep.start(*factors[0], first_rhs);
    sweep.finish(n);
  }
  return positive[0] != 0 && positive[1] != 0;
}

template <std::size_t K>
GRANVV_WIDE_LOOPS void back_substitute_periodic(
    int n, const std::array<const PeriodicLdlFactors*, K>& factors,
    const std::array<double*, K>& x) {
  std::array<const double*, K> r, l, q, s;
  std::array<Pair, K> y, carried;
  std::array<double, K> x_last;
  // L^T x = D^-1 y, from the last unknown upwards, with g_i = y_i / d_i - s_i x_{n-1}:
  // x_i = g_i - l_i x_{i+1} = (g_i - l_i g_{i+1}) + l_i l_{i+1} x_{i+2}, two chains (the lanes
  // hold rows i - 1 and i).
  for (std::size_t k = 0; k < K; ++k) {
    r[k] = factors[k]->inverse_pivot.data();
    l[k] = factors[k]->multiplier.data();
    q[k] = factors[k]->multiplier_pair.data();
    s[k] = factors[k]->spike.data();
    x_last[k] = x[k][n - 1] * r[k][n - 1];
    x[k][n - 1] = x_last[k];
    const auto g = [&](int row) { return x[k][row] * r[k][row] - s[k][row] * x_last[k]; };
    const double even = g(n - 2);  // x_{n-2}
    x[k][n - 2] = even;
    const double g_before = g(n - 3);
    const double odd = g_before - l[k][n - 3] * even;  // x_{n-3}
    x[k][n - 3] = odd;
    y[k] = Pair{odd, even};
    carried[k] = Pair{g_before, 0.0};  // (g_{i+1}, .) of the first pair of rows below
  }
  int i = n - 4;
  for (; i >= 1; i -= 2) {
    for (std::size_t k = 0; k < K; ++k) {
      const Pair g = load_pair(x[k] + i - 1) * load_pair(r[k] + i - 1) -
                     load_pair(s[k] + i - 1) * splat(x_last[k]);  // (g_{i-1}, g_i)
      const Pair g_after{g[1], carried[k][0]};                    // (g_i, g_{i+1})
      y[k] = (g - load_pair(l[k] + i - 1) * g_after) + load_pair(q[k] + i - 1) * y[k];
      store_pair(x[k] + i - 1, y[k]);
      carried[k] = g;
    }
  }
  if (i == 0) {
    for (std::size_t k = 0; k < K; ++k) {
      x[k][0] = (x[k][0] * r[k][0] - s[k][0] * x_last[k]) - l[k][0] * y[k][0];
    }
  }
}

template <std::size_t K>
GRANVV_WIDE_LOOPS void solve_periodic(int n,
                                      const std::array<const PeriodicLdlFactors*, K>& factors,
                                      const std::array<double*, K>& x) {
  std::array<ForwardSweep, K> sweep;
  for (std::size_t k = 0; k < K; ++k) sweep[k].start(*factors[k], x[k]);
  for (int i = 2; i + 1 <= n - 2; i += 2) {
    for (std::size_t k = 0; k < K; ++k) sweep[k].step();
  }
  for (std::size_t k = 0; k < K; ++k) sweep[k].finish(n);
  back_substitute_periodic<K>(n, factors, x);
}

template bool factorize_periodic<1>(int, const std::array<PeriodicTridiagonalView, 1>&,
                                    const std::array<PeriodicLdlFactors*, 1>&, double*);
template bool factorize_periodic<2>(int, const std::array<PeriodicTridiagonalView, 2>&,
                                    const std::array<PeriodicLdlFactors*, 2>&, double*);
template bool factorize_periodic<3>(int, const std::array<PeriodicTridiagonalView, 3>&,
                                    const std::array<PeriodicLdlFactors*, 3>&, double*);
template void solve_periodic<1>(int, const std::array<const PeriodicLdlFactors*, 1>&,
                                const std::array<double*, 1>&);
template void solve_periodic<2>(int, const std::array<const PeriodicLdlFactors*, 2>&,
                                const std::array<double*, 2>&);
template void solve_periodic<3>(int, const std::array<const PeriodicLdlFactors*, 3>&,
                                const std::array<double*, 3>&);

template void back_substitute_periodic<1>(int, const std::array<const PeriodicLdlFactors*, 1>&,
                                          const std::array<double*, 1>&);

}  // namespace granvv::hydro
