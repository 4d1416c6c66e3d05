#include "hydro/flow_by_inertia.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fields/constants.hpp"

namespace granvv::hydro {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kRefinedMinima = 8;

// Golden-section search for a minimum of f inside [a, b]; returns (argmin, min).
// The minimum value converges to rounding level even though the argmin only reaches
// ~sqrt(machine epsilon), because f is flat (quadratic) there.
std::pair<double, double> golden_minimum(const std::function<double(double)>& f, double a,
                                         double b) {
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - r * (b - a);
  double d = a + r * (b - a);
  double fc = f(c);
  double fd = f(d);
  for (int i = 0; i < 100 && b - a > 1e-15 * (1.0 + std::abs(a)); ++i) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - r * (b - a);
      fc = f(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + r * (b - a);
      fd = f(d);
    }
  }
  return fc < fd ? std::make_pair(c, fc) : std::make_pair(d, fd);
}

double wrap_unit(double x) {
  return x - std::floor(x + 0.5);
}

}  // namespace

double density_at_singular_point(double n0_at_singular_point, double t, double tau) {
  return n0_at_singular_point / (1.0 - t / tau);
}

FlowByInertia::FlowByInertia(Exact, Profile v0, Profile dv0, Profile n0, double tau,
                             double singular_label, double v_min, double v_max)
    : v0_(std::move(v0)),
      dv0_(std::move(dv0)),
      n0_(std::move(n0)),
      tau_(tau),
      singular_label_(singular_label),
      v_min_(v_min),
      v_max_(v_max) {}

FlowByInertia::FlowByInertia(Profile v0, Profile dv0, Profile n0, int samples)
    : v0_(std::move(v0)), dv0_(std::move(dv0)), n0_(std::move(n0)) {
  if (!v0_ || !dv0_ || !n0_) {
    throw std::invalid_argument("FlowByInertia: v0, dv0 and n0 must all be given");
  }
  if (samples < 8) {
    throw std::invalid_argument("FlowByInertia: need at least 8 samples, got " +
                                std::to_string(samples));
  }
  const double h = 1.0 / samples;
  std::vector<double> d(static_cast<std::size_t>(samples));
  v_min_ = kInf;
  v_max_ = -kInf;
  for (int i = 0; i < samples; ++i) {
    const double xi = -0.5 + i * h;
    const double v = v0_(xi);
    v_min_ = std::min(v_min_, v);
    v_max_ = std::max(v_max_, v);
    d[static_cast<std::size_t>(i)] = dv0_(xi);
  }
  const auto at = [&](int i) { return d[static_cast<std::size_t>((i + samples) % samples)]; };

  // Discrete local minima of v0' (periodic), lowest first; a flat v0' has none worth refining.
  const auto [lowest, highest] = std::minmax_element(d.begin(), d.end());
  double best_xi = -0.5 + h * static_cast<double>(lowest - d.begin());
  double best = *lowest;
  if (*highest - *lowest > 1e-14 * std::max(1.0, std::abs(*lowest))) {
    std::vector<int> minima;
    for (int i = 0; i < samples; ++i) {
      if (at(i) <= at(i - 1) && at(i) < at(i + 1)) minima.push_back(i);
    }
    std::sort(minima.begin(), minima.end(), [&](int a, int b) { return at(a) < at(b); });
    if (minima.size() > static_cast<std::size_t>(kRefinedMinima)) minima.resize(kRefinedMinima);
    for (const int i : minima) {
      const double xi = -0.5 + i * h;
      const auto [arg, value] = golden_minimum(dv0_, xi - h, xi + h);
      if (value < best) {
        best = value;
        best_xi = arg;
      }
    }
  }
  if (best < 0.0) {
    tau_ = -1.0 / best;
    singular_label_ = wrap_unit(best_xi);
  } else {
    tau_ = kInf;
    singular_label_ = kNaN;
  }
}

FlowByInertia FlowByInertia::single_mode(double a, int mode) {
  if (mode < 1) {
    throw std::invalid_argument("FlowByInertia::single_mode: mode must be >= 1, got " +
                                std::to_string(mode));
  }
  const double kx = 2.0 * kPi * mode;
  const double tau = a == 0.0 ? kInf : 1.0 / (kx * std::abs(a));
  const double label = a < 0.0 ? 0.0 : (a > 0.0 ? -0.5 / mode : kNaN);
  return FlowByInertia(
      Exact{}, [a, kx](double xi) { return a * std::sin(kx * xi); },
      [a, kx](double xi) { return a * kx * std::cos(kx * xi); }, [](double) { return 1.0; }, tau,
      label, -std::abs(a), std::abs(a));
}

double FlowByInertia::singular_position() const {
  if (std::isinf(tau_)) return kNaN;
  return singular_label_ + v0_(singular_label_) * tau_;
}

double FlowByInertia::singular_density(double t) const {
  return density_at_singular_point(n0_(singular_label_), t, tau_);
}

double FlowByInertia::lagrangian_label(double x, double t) const {
  if (!(t >= 0.0 && t < tau_)) {
    throw std::domain_error("FlowByInertia: time " + std::to_string(t) +
                            " outside [0, tau) with tau = " + std::to_string(tau_));
  }
  if (t == 0.0) return x;
  // g(xi) = xi + v0(xi) t - x increases strictly (g' = 1 + t v0' >= 1 - t/tau > 0) and
  // g(x - t v_max) <= 0 <= g(x - t v_min); widen in case sampling missed the extremes of v0.
  const auto g = [&](double xi) { return xi + v0_(xi) * t - x; };
  double lo = x - t * v_max_;
  double hi = x - t * v_min_;
  for (double step = 1e-12 + (hi - lo); g(lo) > 0.0; step *= 2.0) lo -= step;
  for (double step = 1e-12 + (hi - lo); g(hi) < 0.0; step *= 2.0) hi += step;

  double xi = std::clamp(x - t * v0_(x), lo, hi);
  for (int iter = 0; iter < 200; ++iter) {
    const double gx = g(xi);
    if (gx == 0.0) return xi;
    if (gx < 0.0) {
      lo = xi;
    } else {
      hi = xi;
    }
    double next = xi - gx / (1.0 + t * dv0_(xi));
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const double tol = 2.0 * std::numeric_limits<double>::epsilon() * std::abs(next);
    if (std::abs(next - xi) <= tol || hi - lo <= tol) return next;
    xi = next;
  }
  return xi;
}

double FlowByInertia::velocity(double x, double t) const {
  return v0_(lagrangian_label(x, t));
}

double FlowByInertia::density(double x, double t) const {
  const double xi = lagrangian_label(x, t);
  return n0_(xi) / (1.0 + t * dv0_(xi));
}

double FlowByInertia::velocity_gradient(double x, double t) const {
  const double xi = lagrangian_label(x, t);
  const double d = dv0_(xi);
  return d / (1.0 + t * d);
}

}  // namespace granvv::hydro
