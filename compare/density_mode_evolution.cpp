#include "compare/density_mode_evolution.hpp"

#include <cmath>
#include <complex>
#include <limits>

#include "compare/density_modes.hpp"
#include "compare/ensemble_statistics.hpp"
#include "hydro/linear_stability.hpp"

namespace granvv::compare {

DensityModes density_modes(int modes, const hydro::Closure& closure,
                           const std::vector<fields::FieldSeries>& members,
                           const fields::FieldSeries& hydro_on_bins,
                           const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
                           const std::vector<double>& collision_clock, double n0) {
  DensityModes out;
  const int count = static_cast<int>(members.size());
  for (int k = 1; k <= modes; ++k) {
    out.theory_rate.push_back(hydro::hcs_modes(closure, k)[0].rate.real());
  }
  std::vector<std::vector<Eigen::Vector3cd>> initial(count);
  for (int r = 0; r < count; ++r) {
    const auto& f = members[r].snapshots.front();
    for (int k = 1; k <= modes; ++k) {
      initial[r].push_back(hcs_perturbation(f.n, f.v_x, f.T, k));
    }
  }
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto& hb = hydro_on_bins.snapshots[pairs[i].second];
    std::vector<double> hydro_row, md_row, md_err, theory_row;
    const std::size_t s_index = pairs[i].first;
    for (int k = 1; k <= modes; ++k) {
      hydro_row.push_back(std::abs(bin_fourier_coefficient(hb.n, k)));
      std::vector<std::vector<double>> power;  // one |n_k|^2 per member
      double theory2 = 0.0;
      for (int r = 0; r < count; ++r) {
        const auto& snaps = members[r].snapshots;
        if (s_index >= snaps.size()) continue;
        std::vector<double> relative;
        for (double n : snaps[s_index].n) relative.push_back(n / n0);
        power.push_back({std::norm(bin_fourier_coefficient(relative, k))});
        const Eigen::Vector3cd evolved =
            hydro::hcs_linear_evolution(closure, k, initial[r][k - 1], collision_clock[i]);
        theory2 += std::norm(evolved[0]);
      }
      // rms over members; its error from the scatter of |n_k|^2 (d sqrt(p) = dp / 2 sqrt(p)).
      const auto st = ensemble_statistics(power);
      const double rms = std::sqrt(st.mean[0]);
      md_row.push_back(rms);
      md_err.push_back(rms > 0 ? 0.5 * st.standard_error[0] / rms
                               : std::numeric_limits<double>::quiet_NaN());
      theory_row.push_back(std::sqrt(theory2 / count));
    }
    out.hydro.push_back(hydro_row);
    out.md.push_back(md_row);
    out.md_error.push_back(md_err);
    out.theory.push_back(theory_row);
  }
  return out;
}

}  // namespace granvv::compare
