#include "compare/signal_to_noise.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace granvv::compare {

namespace {
constexpr int kProfileSamples = 4096;
}  // namespace

double profile_maximum(const std::function<double(double)>& f) {
  double largest = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < kProfileSamples; ++i) {
    largest = std::max(largest, f(-0.5 + (i + 0.5) / kProfileSamples));
  }
  return largest;
}

std::function<double(double)> largest_flow_component(std::function<double(double)> v,
                                                     std::function<double(double)> vy) {
  if (!vy) return [v](double x) { return std::abs(v(x)); };
  return [v, vy](double x) { return std::max(std::abs(v(x)), std::abs(vy(x))); };
}

SignalToNoise velocity_signal_to_noise(const std::function<double(double)>& v,
                                       double number_density, double box_width, double box_length,
                                       int bins) {
  const double bin = box_length / bins;
  SignalToNoise s;
  s.noise = 1.0 / std::sqrt(number_density * box_width * bin);
  s.signal = std::max(0.0, profile_maximum([&](double x) { return std::abs(v(x)); }));
  return s;
}

SignalToNoise gradient_signal_to_noise(const std::function<double(double)>& dv, int unstable_modes,
                                       long long particles) {
  const int k_max = unstable_modes;
  SignalToNoise s;
  s.noise = k_max > 0 ? k_max * std::sqrt(k_max / double(particles))
                      : std::numeric_limits<double>::quiet_NaN();
  s.signal = dv ? std::max(0.0, profile_maximum([&](double x) { return std::abs(dv(x)); })) : 0.0;
  return s;
}

SignalToNoise mode_signal_to_noise(const std::function<double(double)>& v, long long particles) {
  double b1 = 0.0;  // midpoint rule: exact for a single mode
  for (int i = 0; i < kProfileSamples; ++i) {
    const double x = -0.5 + (i + 0.5) / kProfileSamples;
    b1 += 2.0 * v(x) * std::sin(2.0 * M_PI * x) / kProfileSamples;
  }
  return {std::abs(b1), std::sqrt(2.0 / double(particles))};
}

}  // namespace granvv::compare
