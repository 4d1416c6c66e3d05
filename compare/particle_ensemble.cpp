#include "compare/particle_ensemble.hpp"

#include <cmath>
#include <stdexcept>

#include "compare/pressure_comparison.hpp"

namespace granvv::compare {

namespace {

// Per member: its samples' pressures and their errors, and its compressibilities and theirs.
struct MemberPressures {
  std::vector<std::vector<double>> p, p_error, z, z_error;
};

MemberPressures member_pressures(const std::vector<MemberSamples>& members) {
  MemberPressures out;
  for (const MemberSamples& m : members) {
    std::vector<double> p = normal_pressure(m.pressure_xx, m.pressure_yy), p_error, z, z_error;
    for (std::size_t i = 0; i < p.size(); ++i) {
      p_error.push_back(m.pressure_stderr[i]);
      z.push_back(m.compressibility[i]);
      z_error.push_back(m.pressure_stderr[i] * z.back() / p[i]);
    }
    out.p.push_back(std::move(p));
    out.p_error.push_back(std::move(p_error));
    out.z.push_back(std::move(z));
    out.z_error.push_back(std::move(z_error));
  }
  return out;
}

}  // namespace

SampleAverage ensemble_pressure(const std::vector<MemberSamples>& members) {
  const MemberPressures m = member_pressures(members);
  return sample_average(m.p, m.p_error);
}

SampleAverage ensemble_compressibility(const std::vector<MemberSamples>& members) {
  const MemberPressures m = member_pressures(members);
  return sample_average(m.z, m.z_error);
}

ParticleEnsemble reduce_particle_ensemble(const std::vector<MemberSamples>& members,
                                          double mode_energy_threshold, double t_end) {
  if (members.empty()) throw std::invalid_argument("reduce_particle_ensemble: no members");
  std::vector<std::vector<double>> ts, Ts, fractions;
  for (const MemberSamples& m : members) {
    ts.push_back(m.t);
    Ts.push_back(m.T);
    fractions.push_back(m.mode_energy_fraction);
  }
  ParticleEnsemble e;
  const MemberPressures p = member_pressures(members);
  e.pressure = sample_average(p.p, p.p_error);
  e.compressibility = sample_average(p.z, p.z_error);
  e.mode_energy_fraction = ensemble_statistics(fractions);
  e.homogeneous =
      homogeneous_window(ts.front(), e.mode_energy_fraction.mean, mode_energy_threshold, t_end);
  try {
    e.haff = fit_haff_ensemble(ts, Ts, 0.0, e.homogeneous.t_max);
  } catch (const std::invalid_argument&) {  // too few samples, or no cooling: no fit
    e.haff.t0 = e.haff.t0_error = e.haff.T0 = std::nan("");
  }
  e.T = ensemble_statistics(Ts);
  return e;
}

}  // namespace granvv::compare
