// Conservation laws of the Lagrangian scheme (paper Eqs. 1-3): mass and momentum exactly,
// total energy plus the energy removed by cooling to round-off, because the work on each
// cell is the kinetic energy its nodes lose (compatible discretisation). For every registered
// closure (the Enskog one at phi0 = 0.1) and both cooling rates.
#include <gtest/gtest.h>

#include <cmath>

#include "hydro/closure.hpp"
#include "hydro/dilute_closure.hpp"
#include "hydro/driver.hpp"
#include "hydro/haff.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "support/run_control.hpp"

namespace granvv::hydro {
namespace {

RunResult run_scene(const Closure& closure, const InitialParameters& ip, int cells, double t_end,
                    bool transverse = false) {
  return run_hydro(closure, discretize(make_initial_fields(ip, closure), cells, 0.5, transverse),
                   testing::run_control(t_end));
}

class ClosureConservation : public ::testing::TestWithParam<std::tuple<std::string, CoolingRate>> {
 protected:
  std::unique_ptr<Closure> closure_for(const Physics& p) const {
    return make_closure(std::get<0>(GetParam()),
                        {p, {{"area_fraction", 0.1}}, std::get<1>(GetParam())});
  }
};

TEST_P(ClosureConservation, SingleModeConservesMassMomentumAndEnergyToRoundOff) {
  const InitialParameters ip =  // paper Eq. (7), a = -0.05
      initial_parameters("single_mode", {{"velocity_amplitude", -0.05},
                                         {"mode", 1LL},
                                         {"transverse_amplitude", 0.0},
                                         {"transverse_mode", 1LL}});
  const RunResult r = run_scene(*closure_for({4e-4, 0.01}), ip, 400, 2.0);
  ASSERT_EQ(r.status, RunStatus::completed) << r.stop_reason;
  // Round-off: ~1e-16 per operation, a few hundred steps, sums over 400 cells.
  EXPECT_LT(r.energy_drift, 1e-12);
  EXPECT_LT(r.momentum_drift, 1e-13);
  EXPECT_LT(r.mass_drift, 1e-14);
  // The cooling sink is real: most of the thermal energy is gone by t = 2 (t0 = 0.01).
  EXPECT_GT(r.series.energy_cooled.back(), 0.9);
}

TEST_P(ClosureConservation, RandomModesWithTransverseFlowConserveEnergy) {
  const ParameterSet random_modes = {
      {"random_modes", 40LL}, {"random_amplitude", 2e-3}, {"seed", 1LL}};
  Physics p{2e-3, 0.01};
  const RunControl control = testing::run_control(0.5);
  const auto closure = closure_for(p);
  auto state = discretize(find_initial_condition("random_modes").generate(random_modes, *closure),
                          300, 0.5, true);
  for (int j = 0; j < state.cells(); ++j)
    state.node_vy[j] = 0.01 * std::sin(2 * M_PI * 3 * state.node_x[j]);
  const RunResult r = run_hydro(*closure, state, control);
  ASSERT_EQ(r.status, RunStatus::completed) << r.stop_reason;
  EXPECT_LT(r.energy_drift, 1e-12);
  EXPECT_LT(r.momentum_drift, 1e-13);
  EXPECT_GT(r.series.energy_kinetic_y.front(), 0.0);
}

TEST_P(ClosureConservation, HomogeneousStateFollowsHaffsLaw) {
  const InitialParameters ip =
      initial_parameters("uniform", {{"transverse_amplitude", 0.0}, {"transverse_mode", 1LL}});
  const auto closure = closure_for({4e-4, 0.01});
  const double t0 = haff_time_scale(*closure);
  const RunResult r = run_scene(*closure, ip, 64, 100 * t0);
  ASSERT_EQ(r.status, RunStatus::completed);
  double worst = 0.0;
  for (size_t i = 0; i < r.series.t.size(); ++i) {
    worst = std::max(worst, std::abs(r.series.T_mean[i] / haff_temperature(r.series.t[i], t0) - 1));
  }
  // The cooling step is the exact solution at fixed density, so only round-off remains.
  EXPECT_LT(worst, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Registered, ClosureConservation,
                         ::testing::Combine(::testing::ValuesIn(closure_names()),
                                            ::testing::Values(CoolingRate::small_q,
                                                              CoolingRate::exact)));

// The controls have no defaults of their own (the case schema holds them): an unset control
// is refused rather than run with a zero time step.
TEST(HydroConservation, RunRefusesAControlWithoutTimeStepBounds) {
  RunControl control;
  control.t_end = 0.1;
  const auto state = discretize(uniform_fields(), 16, 0.5, false);
  EXPECT_THROW(run_hydro(DiluteClosure({4e-4, 0.01}), state, control), std::invalid_argument);
  control = testing::run_control(0.1);
  control.series_every = 0;
  EXPECT_THROW(run_hydro(DiluteClosure({4e-4, 0.01}), state, control), std::invalid_argument);
}

// A time step below the round-off of the clock (dt < t eps) would leave t unchanged forever: the
// run stops as failed with the reason instead of looping.
TEST(HydroConservation, AStepThatCannotAdvanceTheClockFailsTheRun) {
  auto state = discretize(uniform_fields(), 16, 0.5, false);
  state.t = 1e17;  // eps t = 22 > dt_max
  RunControl control = testing::run_control(2e17);
  control.time_step.dt_max = 1.0;
  const RunResult r = run_hydro(DiluteClosure({4e-4, 0.01}), state, control);
  EXPECT_EQ(r.status, RunStatus::failed);
  EXPECT_NE(r.stop_reason.find("no longer advances"), std::string::npos) << r.stop_reason;
  EXPECT_EQ(r.steps, 0);
}

}  // namespace
}  // namespace granvv::hydro
