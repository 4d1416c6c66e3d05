#include "compare/binned_energies.hpp"

#include <cmath>

namespace granvv::compare {

EnergiesPerParticle box_energies(const fields::FieldSnapshot& f) {
  const std::size_t bins = f.n.size();
  EnergiesPerParticle e;
  for (std::size_t b = 0; b < bins; ++b) {
    const double dx = 1.0 / bins;
    e.thermal += f.n[b] * f.T[b] * dx;
    e.flow += 0.5 * f.n[b] * (f.v_x[b] * f.v_x[b] + f.v_y[b] * f.v_y[b]) * dx;
  }
  return e;
}

EnergiesPerParticle noise_corrected_energies(const fields::FieldSnapshot& f,
                                             const std::vector<double>& count_per_member,
                                             int members) {
  const std::size_t bins = f.n.size();
  double thermal = 0.0, flow = 0.0, mass = 0.0;
  for (std::size_t b = 0; b < bins; ++b) {
    const double dx = 1.0 / bins;
    const double vx = f.v_x[b], vy = f.v_y[b], count = count_per_member[b];
    if (!std::isfinite(vx) || !std::isfinite(f.T[b])) continue;
    const double noise = count > 0 ? 2.0 * f.T[b] / (count * members) : 0.0;
    mass += f.n[b] * dx;
    thermal += f.n[b] * f.T[b] * dx;
    flow += 0.5 * f.n[b] * (vx * vx + vy * vy - noise) * dx;
  }
  return {thermal / mass, flow / mass};
}

}  // namespace granvv::compare
