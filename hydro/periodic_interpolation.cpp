#include "hydro/periodic_interpolation.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace granvv::hydro {

const std::vector<std::string>& interpolation_names() {
  static const std::vector<std::string> names = {"linear", "cubic"};
  return names;
}

Interpolation interpolation_from_name(const std::string& name) {
  if (name == "linear") return Interpolation::linear;
  if (name == "cubic") return Interpolation::monotone_cubic;
  throw std::invalid_argument("unknown interpolation " + name);
}

namespace {

struct Table {
  std::vector<double> x, y, slope;  // x, y with the first point repeated one period on
};

// Fritsch & Butland (1984): at an interior extremum or flat spot the slope is 0; elsewhere the
// weighted harmonic mean of the two secants (Brodlie's weights), which is monotone.
std::vector<double> monotone_slopes(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size() - 1;  // intervals; point n is point 0 a period on
  std::vector<double> h(n), d(n), m(n + 1);
  for (std::size_t i = 0; i < n; ++i) {
    h[i] = x[i + 1] - x[i];
    d[i] = (y[i + 1] - y[i]) / h[i];
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t l = (i + n - 1) % n;  // the interval before point i, periodically
    if (d[l] * d[i] <= 0.0) {
      m[i] = 0.0;
    } else {
      m[i] = 3.0 * (h[l] + h[i]) / ((2.0 * h[i] + h[l]) / d[l] + (h[i] + 2.0 * h[l]) / d[i]);
    }
  }
  m[n] = m[0];
  return m;
}

}  // namespace

std::function<double(double)> periodic_interpolant(const std::vector<double>& x,
                                                   const std::vector<double>& y,
                                                   Interpolation interpolation) {
  if (x.size() != y.size() || x.size() < 2) {
    throw std::invalid_argument("periodic_interpolant: needs at least 2 points, x and y alike");
  }
  for (std::size_t i = 1; i < x.size(); ++i) {
    if (!(x[i] > x[i - 1])) throw std::invalid_argument("periodic_interpolant: x not increasing");
  }
  if (!(x.back() < x.front() + 1.0)) {
    throw std::invalid_argument("periodic_interpolant: x spans more than one period");
  }
  auto t = std::make_shared<Table>();
  t->x = x;
  t->y = y;
  t->x.push_back(x.front() + 1.0);
  t->y.push_back(y.front());
  if (interpolation == Interpolation::monotone_cubic) t->slope = monotone_slopes(t->x, t->y);
  return [t](double at) {
    const double x0 = t->x.front();
    const double u = at - std::floor(at - x0) - x0;  // in [0, 1): the period from x0
    const double z = x0 + u;
    auto it = std::upper_bound(t->x.begin(), t->x.end(), z);
    const std::size_t i =
        std::min<std::size_t>(std::max<std::ptrdiff_t>(it - t->x.begin() - 1, 0), t->x.size() - 2);
    const double h = t->x[i + 1] - t->x[i], s = (z - t->x[i]) / h;
    const double y0 = t->y[i], y1 = t->y[i + 1];
    if (t->slope.empty()) return y0 + s * (y1 - y0);
    const double s2 = s * s, s3 = s2 * s;  // cubic Hermite basis
    return (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * h * t->slope[i] +
           (-2 * s3 + 3 * s2) * y1 + (s3 - s2) * h * t->slope[i + 1];
  };
}

}  // namespace granvv::hydro
