#include "hydro/initial_conditions.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

#include "hydro/linear_stability.hpp"

namespace granvv::hydro {
namespace {

constexpr double kPi = 3.14159265358979323846;

InitialFields uniform(const InitialParameters&, const Physics&) {
  InitialFields f;
  f.n = [](double) { return 1.0; };
  f.v = [](double) { return 0.0; };
  f.dv = [](double) { return 0.0; };
  f.vy = [](double) { return 0.0; };
  f.T = [](double) { return 1.0; };
  return f;
}

// Paper Eq. (8): n = T = 1, v = a sin(2 pi k x).
InitialFields single_mode(const InitialParameters& p, const Physics& ph) {
  InitialFields f = uniform(p, ph);
  const double a = p.velocity_amplitude, kx = 2.0 * kPi * p.mode;
  f.v = [a, kx](double x) { return a * std::sin(kx * x); };
  f.dv = [a, kx](double x) { return a * kx * std::cos(kx * x); };
  return f;
}

// Paper Figs. 1-2: n, v, T each 1 (or 0) plus a sum of random Fourier modes k = 1..M with
// amplitudes uniform in [0, A] and uniform random phases. Uses the raw 64-bit Mersenne
// Twister output so that a seed gives the same scene on every platform.
InitialFields random_modes(const InitialParameters& p, const Physics& ph) {
  std::mt19937_64 rng(p.seed);
  auto uniform01 = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  struct Series {
    std::vector<double> amplitude, phase;
  };
  auto draw = [&]() {
    Series s;
    for (int k = 1; k <= p.random_modes; ++k) {
      s.amplitude.push_back(p.random_amplitude * uniform01());
      s.phase.push_back(2.0 * kPi * uniform01());
    }
    return s;
  };
  auto sum = [](const Series& s, double x) {
    double y = 0.0;
    for (size_t k = 0; k < s.amplitude.size(); ++k) {
      y += s.amplitude[k] * std::cos(2.0 * kPi * (k + 1) * x + s.phase[k]);
    }
    return y;
  };
  auto dsum = [](const Series& s, double x) {
    double y = 0.0;
    for (size_t k = 0; k < s.amplitude.size(); ++k) {
      const double kx = 2.0 * kPi * (k + 1);
      y -= s.amplitude[k] * kx * std::sin(kx * x + s.phase[k]);
    }
    return y;
  };
  const Series dn = draw(), dv = draw(), dT = draw();
  InitialFields f = uniform(p, ph);
  f.n = [dn, sum](double x) { return 1.0 + sum(dn, x); };
  f.v = [dv, sum](double x) { return sum(dv, x); };
  f.dv = [dv, dsum](double x) { return dsum(dv, x); };
  f.T = [dT, sum](double x) { return 1.0 + sum(dT, x); };
  return f;
}

// A small eigenmode of the linearised equations around the homogeneous cooling state:
// (nu, w, theta) = amplitude * Re(V e^{i kx x}) with V the eigenvector of the chosen branch.
InitialFields linear_mode(const InitialParameters& p, const Physics& ph) {
  const auto modes = hcs_modes(ph, p.mode);
  const Eigen::Vector3cd V = modes.at(p.linear_branch).eigenvector * p.linear_amplitude;
  const double kx = 2.0 * kPi * p.mode;
  auto component = [kx](std::complex<double> c) {
    return [c, kx](double x) { return std::real(c * std::exp(std::complex<double>(0.0, kx * x))); };
  };
  InitialFields f = uniform(p, ph);
  auto nu = component(V[0]), w = component(V[1]), theta = component(V[2]);
  f.n = [nu](double x) { return 1.0 + nu(x); };
  f.v = w;  // T_H(0) = 1, so u = w at t = 0
  f.dv = [V, kx](double x) {
    return std::real(std::complex<double>(0.0, kx) * V[1] *
                     std::exp(std::complex<double>(0.0, kx * x)));
  };
  f.T = [theta](double x) { return 1.0 + theta(x); };
  return f;
}

}  // namespace

const std::map<std::string, InitialConditionGenerator>& initial_condition_registry() {
  static const std::map<std::string, InitialConditionGenerator> registry = {
      {"uniform", uniform},
      {"single_mode", single_mode},
      {"random_modes", random_modes},
      {"linear_mode", linear_mode},
  };
  return registry;
}

InitialFields make_initial_fields(const InitialParameters& p, const Physics& physics) {
  const auto& registry = initial_condition_registry();
  const auto it = registry.find(p.type);
  if (it == registry.end()) throw std::invalid_argument("unknown initial condition " + p.type);
  InitialFields f = it->second(p, physics);
  if (p.transverse_amplitude != 0.0) {
    const double b = p.transverse_amplitude, ky = 2.0 * kPi * p.transverse_mode;
    f.vy = [b, ky](double x) { return b * std::cos(ky * x); };
  }
  return f;
}

LagrangianState discretize(const InitialFields& f, int cells, double node_offset, bool transverse) {
  static const double gauss_x[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  static const double gauss_w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  LagrangianState s;
  const double h = 1.0 / cells;
  for (int j = 0; j < cells; ++j) {
    const double x = -0.5 + (j + node_offset) * h;
    s.node_x.push_back(x);
    s.node_xi.push_back(x);
    s.node_v.push_back(f.v(x));
    if (transverse) s.node_vy.push_back(f.vy(x));
  }
  for (int i = 0; i < cells; ++i) {
    const double centre = s.node_x[i] + 0.5 * h;
    double mass = 0.0, energy = 0.0;
    for (int g = 0; g < 3; ++g) {
      const double x = centre + 0.5 * h * gauss_x[g];
      const double n = f.n(x);
      mass += 0.5 * h * gauss_w[g] * n;
      energy += 0.5 * h * gauss_w[g] * n * f.T(x);
    }
    s.cell_mass.push_back(mass);
    s.cell_T.push_back(energy / mass);
  }
  return s;
}

}  // namespace granvv::hydro
