#include "md_bridge/moment_reduction.hpp"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace granvv::md {

void allreduce(Moments& m, MPI_Comm comm) {
  const auto arrays = m.arrays();
  const std::size_t bins = static_cast<std::size_t>(m.bins());
  // Layout: the per-bin arrays one after another, then the particle counts.
  std::vector<double> buffer;
  buffer.reserve(arrays.size() * bins + 3);
  for (const auto* a : arrays) buffer.insert(buffer.end(), a->begin(), a->end());
  buffer.push_back(m.particles);
  buffer.push_back(m.virial_particles);
  buffer.push_back(m.contact_flux_particles);

  const int rc = MPI_Allreduce(MPI_IN_PLACE, buffer.data(), static_cast<int>(buffer.size()),
                               MPI_DOUBLE, MPI_SUM, comm);
  if (rc != MPI_SUCCESS) {
    throw std::runtime_error("coarse-graining: MPI_Allreduce of the moments failed (code " +
                             std::to_string(rc) + ")");
  }
  auto it = buffer.cbegin();
  for (auto* a : arrays) {
    std::copy(it, it + static_cast<std::ptrdiff_t>(bins), a->begin());
    it += static_cast<std::ptrdiff_t>(bins);
  }
  m.particles = *it++;
  m.virial_particles = *it++;
  m.contact_flux_particles = *it;
}

}  // namespace granvv::md
