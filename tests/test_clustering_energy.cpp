// Paper Figs. 1-2 (cases/clustering.toml): from a few hundred small random Fourier modes the
// gas clusters; the thermal energy keeps following Haff's law until the major peak nears its
// singularity, while the macroscopic kinetic energy levels off (flow by inertia).
#include <gtest/gtest.h>

#include <cmath>

#include "hydro/haff.hpp"
#include "scene/case_config.hpp"
#include "scene/hydro_scene.hpp"

namespace granvv::app {
namespace {

TEST(ClusteringEnergy, ThermalFollowsHaffWhileKineticLevelsOff) {
  const auto config =
      CaseConfig::from_file(std::string(GRANVV_SOURCE_DIR) + "/cases/clustering.toml", {});
  const HydroOutcome out = run_hydro_scene(hydro_scene_from(config), {});
  const auto& s = out.run.series;
  ASSERT_EQ(out.run.status, hydro::RunStatus::singularity) << out.run.stop_reason;
  EXPECT_EQ(out.unstable_modes, 79);
  EXPECT_LT(out.run.energy_drift, 1e-12);

  const double t0 = hydro::haff_time_scale({config.real("physics.K"), config.real("physics.q")});
  auto at = [&](double t) {
    size_t i = 0;
    while (i + 1 < s.t.size() && s.t[i] < t) ++i;
    return i;
  };
  // Thermal energy against Haff until the density first reaches 10 (the major peak's
  // approach): the mean density is 1, so E_th = <T> and Haff's law applies to it directly.
  // Tolerance 3 %: the inhomogeneity n^2 T^{3/2} raises the cooling a little as peaks grow.
  const double t_cluster = out.run.crossing_times.at(10.0);
  for (size_t i = 0; s.t[i] <= t_cluster; ++i) {
    EXPECT_NEAR(s.energy_thermal[i] / hydro::haff_temperature(s.t[i], t0), 1.0, 0.03)
        << "t = " << s.t[i];
  }
  // Between t = 2 and the clustering time, E_th ~ t^{-2} (Haff, t >> t0) while E_kin decays
  // at most like t^{-0.2}: the kinetic energy levels off, as in the paper's Fig. 2.
  auto log_slope = [&](const std::vector<double>& y, double a, double b) {
    return std::log(y[at(b)] / y[at(a)]) / std::log(s.t[at(b)] / s.t[at(a)]);
  };
  EXPECT_NEAR(log_slope(s.energy_thermal, 2.0, t_cluster), -2.0, 0.05);
  EXPECT_GT(log_slope(s.energy_kinetic, 2.0, t_cluster), -0.2);
  // ... so the kinetic energy overtakes the thermal energy before the singularity.
  EXPECT_GT(s.energy_kinetic.back(), s.energy_thermal.back());
  EXPECT_LT(s.energy_kinetic[at(1.0)], s.energy_thermal[at(1.0)]);
}

}  // namespace
}  // namespace granvv::app
