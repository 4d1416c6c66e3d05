#include "hydro/linear_stability.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>

#include "fields/constants.hpp"
#include "hydro/dilute_closure.hpp"

namespace granvv::hydro {

namespace {

void require_valid(const Physics& physics) {
  if (!(std::isfinite(physics.K) && physics.K > 0.0)) {
    throw std::invalid_argument("linear stability: Knudsen number K must be finite and > 0, got " +
                                std::to_string(physics.K));
  }
  if (!(std::isfinite(physics.q) && physics.q >= 0.0)) {
    throw std::invalid_argument("linear stability: inelasticity q must be finite and >= 0, got " +
                                std::to_string(physics.q));
  }
}

// Double-double arithmetic (value = hi + lo, |lo| <= ulp(hi)/2), just enough to decide
// pi^2 k^2 K^2 < c q to ~1e-30 relative.
struct DoubleDouble {
  double hi;
  double lo;
};

DoubleDouble two_product(double a, double b) {
  const double p = a * b;
  return {p, std::fma(a, b, -p)};
}

DoubleDouble quick_two_sum(double a, double b) {
  const double s = a + b;
  return {s, b - (s - a)};
}

DoubleDouble multiply(DoubleDouble x, DoubleDouble y) {
  DoubleDouble p = two_product(x.hi, y.hi);
  p.lo += x.hi * y.lo + x.lo * y.hi;
  return quick_two_sum(p.hi, p.lo);
}

// pi^2 = (pi_hi + pi_lo)^2 with pi_hi the double nearest pi and pi_lo the double nearest pi -
// pi_hi.
DoubleDouble pi_squared() {
  constexpr double pi_hi = 3.141592653589793116;
  constexpr double pi_lo = 1.2246467991473532e-16;
  DoubleDouble p = two_product(pi_hi, pi_hi);
  p.lo += 2.0 * pi_hi * pi_lo;
  return quick_two_sum(p.hi, p.lo);
}

// Sign of pi^2 k^2 K^2 - factor * q, decided in double-double; 0 for a tie within 1e-29 relative.
int compare_with_cutoff(const Physics& physics, int k, double factor) {
  const double kd = std::abs(static_cast<double>(k));  // exact for every int
  const DoubleDouble lhs =
      multiply(multiply(pi_squared(), two_product(kd, kd)), two_product(physics.K, physics.K));
  const double rhs = factor * physics.q;  // factor is 1 or 4: exact
  const double s = lhs.hi - rhs;          // exact when lhs.hi and rhs are close (Sterbenz)
  const double diff = s + lhs.lo;
  const double tie_band = 1e-29 * std::max(std::abs(rhs), std::abs(lhs.hi));
  if (std::abs(diff) <= tie_band) return 0;
  return diff > 0.0 ? 1 : -1;
}

bool mode_below_cutoff(const Physics& physics, int k, double factor) {
  require_valid(physics);
  if (k == 0 || physics.q == 0.0) return false;
  return compare_with_cutoff(physics, k, factor) < 0;
}

// The modes k >= 1 with pi^2 k^2 K^2 < factor q, from the dilute closure's cutoff mode
// sqrt(factor q)/(pi K), settled by the exact test. Call with physics checked by require_valid.
int count_below_cutoff(const Physics& physics, double factor, double cutoff) {
  if (physics.q == 0.0) return 0;
  if (!(cutoff < static_cast<double>(INT_MAX) - 2.0)) {
    throw std::overflow_error(
        "linear stability: more than INT_MAX unstable modes (K = " + std::to_string(physics.K) +
        ", q = " + std::to_string(physics.q) + ")");
  }
  // floor(cutoff) is off by at most one from the exact count; settle it with the exact test.
  int k = static_cast<int>(std::floor(cutoff));
  while (k >= 1 && !mode_below_cutoff(physics, k, factor)) --k;
  while (mode_below_cutoff(physics, k + 1, factor)) ++k;
  return k;
}

int count_below(double cutoff) {
  if (!(cutoff > 0.0)) return 0;
  if (!(cutoff < static_cast<double>(INT_MAX) - 2.0)) {
    throw std::overflow_error("linear stability: more than INT_MAX unstable modes (cutoff mode " +
                              std::to_string(cutoff) + ")");
  }
  // Modes k = 1, 2, ... with k < cutoff.
  const double below = std::ceil(cutoff) - 1.0;
  return static_cast<int>(below);
}

std::array<HcsMode, 3> modes_of(const Eigen::Matrix3cd& a) {
  const Eigen::ComplexEigenSolver<Eigen::Matrix3cd> solver(a, /*computeEigenvectors=*/true);
  if (solver.info() != Eigen::Success) {
    throw std::runtime_error("linear stability: eigen-decomposition of the HCS operator failed");
  }
  std::array<HcsMode, 3> modes;
  for (int j = 0; j < 3; ++j) {
    Eigen::Vector3cd v = solver.eigenvectors().col(j);
    const double largest = v.cwiseAbs().maxCoeff();
    int pivot = 0;
    while (pivot < 2 && std::abs(v(pivot)) < (1.0 - 1e-12) * largest) ++pivot;
    const std::complex<double> scale = v(pivot);
    v /= scale;
    v(pivot) = 1.0;
    modes[static_cast<std::size_t>(j)] = HcsMode{solver.eigenvalues()(j), v};
  }
  std::sort(modes.begin(), modes.end(), [](const HcsMode& x, const HcsMode& y) {
    if (x.rate.real() != y.rate.real()) return x.rate.real() > y.rate.real();
    return x.rate.imag() > y.rate.imag();
  });
  return modes;
}

}  // namespace

double hcs_epsilon(const Closure& closure) {
  return closure.hcs_linearisation().epsilon;
}

double hcs_epsilon(const Physics& physics) {
  return hcs_epsilon(DiluteClosure(physics));
}

double mode_wavenumber(int k) {
  return 2.0 * kPi * static_cast<double>(k);
}

Eigen::Matrix3cd hcs_linear_operator_kx(const Closure& closure, double kx) {
  const HcsLinearisation h = closure.hcs_linearisation();
  const double eps = h.epsilon;
  const std::complex<double> ik(0.0, kx);
  Eigen::Matrix3cd a;
  // With mu = 0 the (theta, nu) entry is -(Lambda_n + 0) = -Lambda_n exactly (Lambda_n >= +0).
  // clang-format off
  a << 0.0,                   -ik,                              0.0,
       -ik * h.pressure_density, eps - h.viscosity * kx * kx,  -ik * h.pressure_temperature,
       -(h.cooling_density + h.mu * kx * kx), -ik * h.compression_heating, -(h.conductivity * kx * kx + h.cooling_temperature);
  // clang-format on
  return a;
}

Eigen::Matrix3cd hcs_linear_operator_kx(const Physics& physics, double kx) {
  require_valid(physics);
  return hcs_linear_operator_kx(DiluteClosure(physics), kx);
}

Eigen::Matrix3cd hcs_linear_operator(const Closure& closure, int k) {
  return hcs_linear_operator_kx(closure, mode_wavenumber(k));
}

Eigen::Matrix3cd hcs_linear_operator(const Physics& physics, int k) {
  return hcs_linear_operator_kx(physics, mode_wavenumber(k));
}

std::array<HcsMode, 3> hcs_modes_kx(const Closure& closure, double kx) {
  return modes_of(hcs_linear_operator_kx(closure, kx));
}

std::array<HcsMode, 3> hcs_modes_kx(const Physics& physics, double kx) {
  return modes_of(hcs_linear_operator_kx(physics, kx));
}

std::array<HcsMode, 3> hcs_modes(const Closure& closure, int k) {
  return modes_of(hcs_linear_operator(closure, k));
}

std::array<HcsMode, 3> hcs_modes(const Physics& physics, int k) {
  return modes_of(hcs_linear_operator(physics, k));
}

double shear_rate(const Closure& closure, int k) {
  const HcsLinearisation h = closure.hcs_linearisation();
  const double kx = mode_wavenumber(k);
  return h.epsilon - h.shear_viscosity * kx * kx;
}

double shear_rate(const Physics& physics, int k) {
  return shear_rate(DiluteClosure(physics), k);
}

double clustering_cutoff_mode(const Physics& physics) {
  return clustering_cutoff_mode(DiluteClosure(physics));
}

double shear_cutoff_mode(const Physics& physics) {
  return shear_cutoff_mode(DiluteClosure(physics));
}

double clustering_cutoff_mode(const Closure& closure) {
  return closure.hcs_linearisation().clustering_cutoff_mode;
}

double shear_cutoff_mode(const Closure& closure) {
  return closure.hcs_linearisation().shear_cutoff_mode;
}

int clustering_unstable_modes(const Closure& closure) {
  return count_below(clustering_cutoff_mode(closure));
}

int shear_unstable_modes(const Closure& closure) {
  return count_below(shear_cutoff_mode(closure));
}

bool clustering_mode_unstable(const Physics& physics, int k) {
  return mode_below_cutoff(physics, k, 1.0);
}

bool shear_mode_unstable(const Physics& physics, int k) {
  return mode_below_cutoff(physics, k, 4.0);
}

int clustering_unstable_modes(const Physics& physics) {
  require_valid(physics);
  return count_below_cutoff(physics, 1.0, clustering_cutoff_mode(physics));
}

int shear_unstable_modes(const Physics& physics) {
  require_valid(physics);
  return count_below_cutoff(physics, 4.0, shear_cutoff_mode(physics));
}

Eigen::Vector3cd hcs_linear_evolution(const Closure& closure, int k,
                                      const Eigen::Vector3cd& initial, double s) {
  const Eigen::Matrix3cd as = hcs_linear_operator(closure, k) * s;
  const Eigen::Matrix3cd propagator = as.exp();
  return propagator * initial;
}

Eigen::Vector3cd hcs_linear_evolution(const Physics& physics, int k,
                                      const Eigen::Vector3cd& initial, double s) {
  require_valid(physics);
  return hcs_linear_evolution(DiluteClosure(physics), k, initial, s);
}

}  // namespace granvv::hydro
