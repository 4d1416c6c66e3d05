// Paper Figs. 1-2: n, v, T each 1 (or 0) plus a sum of random Fourier modes k = 1..M with
// amplitudes uniform in [0, A] and uniform random phases. Uses the raw 64-bit Mersenne
// Twister output so that a seed gives the same scene on every platform.
#include <cmath>
#include <random>

#include "fields/constants.hpp"
#include "hydro/initial_condition_registry.hpp"

namespace granvv::hydro {

InitialConditionType random_modes_initial_condition() {
  InitialConditionType type;
  type.name = "random_modes";
  type.parameters = {
      {"random_modes", 300LL, ParameterRange::at_least(1),
       "number of Fourier modes in the perturbation"},
      {"random_amplitude", 1e-3, ParameterRange::at_least(0),
       "rms relative amplitude of the perturbation"},
      {"seed", 1LL, ParameterRange::at_least(0), "random seed"},
  };
  type.generate = [](const ParameterSet& p, const Closure&) {
    std::mt19937_64 rng(static_cast<unsigned long long>(p.integer("seed")));
    auto uniform01 = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
    struct Series {
      std::vector<double> amplitude, phase;
    };
    const int modes = static_cast<int>(p.integer("random_modes"));
    const double amplitude = p.real("random_amplitude");
    auto draw = [&]() {
      Series s;
      for (int k = 1; k <= modes; ++k) {
        s.amplitude.push_back(amplitude * uniform01());
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
    InitialFields f = uniform_fields();
    f.n = [dn, sum](double x) { return 1.0 + sum(dn, x); };
    f.v = [dv, sum](double x) { return sum(dv, x); };
    f.dv = [dv, dsum](double x) { return dsum(dv, x); };
    f.T = [dT, sum](double x) { return 1.0 + sum(dT, x); };
    return f;
  };
  return type;
}

}  // namespace granvv::hydro
