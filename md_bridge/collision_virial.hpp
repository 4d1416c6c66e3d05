#pragma once
// The collisional virial of hard disks per particle, as a time average (docs/physics.md §11):
// hard disks exchange momentum only at instants, so their contact virial exists only summed over
// an interval. Each collision of disks i, j with separation r_ij = r_i - r_j at contact and
// impulse Delta p_i on i adds r_ij,a Delta p_i,a (a = x, y; positive for repulsion) to the pair
// sum, half to each disk; divided by the interval it is the particle's share W_aa of the box's
// contact virial, in the form and units of ParticleEngine::local_virial (energy, MD units), whose
// expectation is that of the instantaneous virial of a continuous contact. The contact transfer of
// energy is tallied the same way (LocalVirial::energy_flux_x).
#include <cstddef>
#include <vector>

#include "md_bridge/particle_engine.hpp"

namespace granvv::md {

class CollisionVirialTally {
 public:
  // No interval finished: last() is empty (before the first advance of a run).
  void clear();
  // Starts an interval for `disks` disks, indexed by particle ID (the engine renumbers its
  // disks in cell order during an interval, so its own indices would not do).
  void begin(std::size_t disks);
  // One collision of the particles with IDs i and j: xx = r_ij,x Delta p_i,x,
  // yy = r_ij,y Delta p_i,y and energy_x = r_ij,x (dE_i - dE_j) / 2.
  void add(int i, int j, double xx, double yy, double energy_x) {
    double* a = &sum_[kPerParticle * std::size_t(i)];
    double* b = &sum_[kPerParticle * std::size_t(j)];
    a[0] += 0.5 * xx, a[1] += 0.5 * yy, a[2] += 0.5 * energy_x;
    b[0] += 0.5 * xx, b[1] += 0.5 * yy, b[2] += 0.5 * energy_x;
  }
  // Ends the interval of length `interval` (> 0, else last() is empty): the shares per particle
  // ID.
  void finish(double interval);
  // The shares over the last finished interval, by particle ID.
  const LocalVirial& last() const { return last_; }
  // The sums of the interval in progress (xx, yy, energy_x per particle ID), for a checkpoint
  // inside it; continue() takes them back (begin() first).
  static constexpr std::size_t kPerParticle = 3;
  const std::vector<double>& sums() const { return sum_; }
  void continue_from(std::vector<double> sums) { sum_ = std::move(sums); }

 private:
  std::vector<double> sum_;  // per particle ID: xx, yy, energy_x
  LocalVirial last_;
};

}  // namespace granvv::md
