// The hydro closures (hydro/closure.hpp): the dilute closure against paper Eqs. (1)-(2) at known
// values, and every registered closure against its own definitions: the adiabatic modulus
// against a finite-difference derivative of p along an adiabat (dT = p dn / n^2, the 2D gas's
// thermal energy T per particle), c^2 = B/n, the exact cooling step against the cooling rate,
// and the HCS linearisation against finite differences of the closure at n = T = 1.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "hydro/closure.hpp"
#include "hydro/dilute_closure.hpp"
#include "hydro/lagrangian_operator.hpp"
#include "hydro/linear_stability.hpp"
#include "hydro/time_series.hpp"
#include "support/runge_kutta.hpp"

namespace granvv::hydro {
namespace {

using granvv::testing::rk4;

// Everything a closure says about one state (n, T), through its array interface.
struct Point {
  double p, B, eta, eta_xy, kappa, mu, c, rate;
};

Point at(const Closure& closure, double n, double T) {
  CellCoefficients cell;
  std::vector<double> c, rate;
  closure.cell_coefficients({n}, {T}, cell);
  closure.sound_speed({n}, {T}, c);
  closure.cooling_rate({n}, {T}, rate);
  return {cell.pressure[0],
          cell.adiabatic_modulus[0],
          cell.viscosity[0],
          cell.shear_viscosity[0],
          cell.conductivity[0],
          cell.mu[0],
          c[0],
          rate[0]};
}

// Temperature at density n1 on the adiabat through (n0, T0): dT/dn = p(n, T) / n^2.
double adiabat(const Closure& closure, double n0, double T0, double n1) {
  return rk4([&](double n, double T) { return at(closure, n, T).p / (n * n); }, T0, n0, n1, 200);
}

TEST(DiluteClosure, CoefficientsOfPaperEquations) {
  // K = 4e-4, q = 0.01 (paper Fig. 1), n = 2, T = 1/4 (T^{1/2} = 1/2 exactly).
  const DiluteClosure dilute(Physics{4e-4, 0.01});
  const Point x = at(dilute, 2.0, 0.25);
  EXPECT_EQ(x.p, 0.5);                                    // n T
  EXPECT_EQ(x.B, 1.0);                                    // 2 n T (adiabatic index 2)
  EXPECT_DOUBLE_EQ(x.c, std::sqrt(0.5));                  // (2T)^{1/2}
  EXPECT_DOUBLE_EQ(x.eta, 5e-5);                          // (K/4) T^{1/2}
  EXPECT_DOUBLE_EQ(x.eta_xy, 5e-5);                       // the same in 2D
  EXPECT_DOUBLE_EQ(x.kappa, 2e-4);                        // K T^{1/2}
  EXPECT_DOUBLE_EQ(dilute.cooling_coefficient(), 200.0);  // 8q/K
  EXPECT_DOUBLE_EQ(x.rate, 50.0);                         // (8q/K) n T^{3/2} = 200 * 2 / 8
  EXPECT_EQ(dilute.name(), "dilute");
  const HcsLinearisation h = dilute.hcs_linearisation();
  EXPECT_DOUBLE_EQ(h.haff_time, 0.01);  // K/(4q)
  EXPECT_DOUBLE_EQ(h.epsilon, 100.0);   // 4q/K
  EXPECT_TRUE(std::isinf(DiluteClosure(Physics{4e-4, 0.0}).hcs_linearisation().haff_time));
}

TEST(DiluteClosure, ArrayInterfaceEqualsTheFormulasBitwise) {
  const DiluteClosure dilute(Physics{2e-3, 0.03});
  const std::vector<double> n{0.3, 1.0, 7.5, 1e5}, T{2.0, 1.0, 0.013, 1e-7};
  CellCoefficients cell;
  std::vector<double> c, rate, cooled;
  dilute.cell_coefficients(n, T, cell);
  dilute.sound_speed(n, T, c);
  dilute.cooling_rate(n, T, rate);
  dilute.cool(n, T, 0.01, cooled);
  for (size_t i = 0; i < n.size(); ++i) {
    EXPECT_EQ(cell.pressure[i], n[i] * T[i]);
    EXPECT_EQ(cell.adiabatic_modulus[i], 2.0 * (n[i] * T[i]));
    EXPECT_EQ(cell.viscosity[i], 0.25 * 2e-3 * std::sqrt(T[i]));
    EXPECT_EQ(cell.shear_viscosity[i], cell.viscosity[i]);
    EXPECT_EQ(cell.conductivity[i], 2e-3 * std::sqrt(T[i]));
    EXPECT_EQ(cell.mu[i], 0.0);  // the paper's Eq. (2): no heat flux down the density gradient
    EXPECT_EQ(c[i], std::sqrt(2.0 * T[i]));
    EXPECT_EQ(rate[i], dilute.cooling_coefficient() * n[i] * T[i] * std::sqrt(T[i]));
    const double g = 1.0 + 0.5 * dilute.cooling_coefficient() * n[i] * std::sqrt(T[i]) * 0.01;
    EXPECT_EQ(cooled[i], T[i] / (g * g));
  }
}

TEST(DiluteClosure, AdiabatIsTProportionalToN) {
  // Independent check of the adiabat integrator: for p = n T, dT/dn = T/n gives T ~ n (RK4,
  // 200 steps over a factor 2 in n: error ~ 1e-12).
  const DiluteClosure dilute(Physics{4e-4, 0.01});
  EXPECT_NEAR(adiabat(dilute, 1.5, 0.4, 3.0), 0.8, 1e-11);
}

// Three parameter sets; the area fraction (read by "enskog" only) keeps phi0 n below freezing
// at the densest test point n = 40 (phi up to 0.4; tests/test_enskog_closure.cpp goes to 0.6),
// and set 1 cools with the exact 1 - r^2.
ClosureParameters parameter_set(int i) {
  const Physics sets[] = {{4e-4, 0.01}, {0.05, 0.2}, {1e-3, 1e-4}};
  const double area_fractions[] = {0.01, 0.005, 0.002};
  return {sets[i],
          {{"area_fraction", area_fractions[i]}},
          i == 1 ? CoolingRate::exact : CoolingRate::small_q};
}

class EveryClosure : public ::testing::TestWithParam<std::tuple<std::string, int>> {
 protected:
  std::unique_ptr<Closure> closure =
      make_closure(std::get<0>(GetParam()), parameter_set(std::get<1>(GetParam())));
};

TEST_P(EveryClosure, AdiabaticModulusIsTheDerivativeOfPressureAlongAnAdiabat) {
  // Central differences with relative step 1e-4: truncation ~1e-8 relative, rounding of the
  // adiabat ~1e-12 / 1e-4; tolerance 1e-7.
  for (const auto& [n, T] : {std::pair{1.0, 1.0}, {0.2, 3.0}, {40.0, 1e-3}}) {
    const double h = 1e-4 * n;
    const double p_plus = at(*closure, n + h, adiabat(*closure, n, T, n + h)).p;
    const double p_minus = at(*closure, n - h, adiabat(*closure, n, T, n - h)).p;
    const double B_fd = n * (p_plus - p_minus) / (2.0 * h);
    const Point x = at(*closure, n, T);
    EXPECT_NEAR(x.B / B_fd, 1.0, 1e-7) << "n = " << n << ", T = " << T;
    // c^2 = B / n, to rounding.
    EXPECT_NEAR(x.c * x.c * n / x.B, 1.0, 1e-14);
  }
}

TEST_P(EveryClosure, OperatorCouplingIsThePressureResponseToTheCellsCompression) {
  // alpha = B dt / (2 dx): a cell of fixed mass compressed by dv over the half step dt/2
  // (dx -> dx + dt dv/2) along its adiabat changes p by -alpha dv. Central difference in dv
  // (relative width change 1e-5): tolerance 1e-7.
  const double mass = 0.004, dx = 0.002, T = 0.7, dt = 1e-5;
  LagrangianOperator op(*closure, 3);  // three equal cells: the smallest periodic mesh
  FrozenCoefficients frozen;
  op.freeze({mass, mass, mass}, {dx, dx, dx}, {T, T, T}, dt, {}, frozen);
  const double dv = 1e-5 * dx / (0.5 * dt);
  const auto pressure_at_width = [&](double width) {
    return at(*closure, mass / width, adiabat(*closure, mass / dx, T, mass / width)).p;
  };
  const double dp = pressure_at_width(dx + 0.5 * dt * dv) - pressure_at_width(dx - 0.5 * dt * dv);
  EXPECT_NEAR(frozen.acoustic_coupling[0] / (-dp / (2.0 * dv)), 1.0, 1e-7);
  EXPECT_EQ(frozen.cell.pressure[0], at(*closure, mass / dx, T).p);
}

TEST_P(EveryClosure, CoolingStepIntegratesTheCoolingRate) {
  // cool() over dt against RK4 of dT/dt = -Lambda(n, T) at fixed n (4000 steps: error
  // ~1e-14); tolerance 1e-10 relative.
  for (const auto& [n, T] : {std::pair{1.0, 1.0}, {5.0, 0.3}, {0.5, 2.0}}) {
    const HcsLinearisation h = closure->hcs_linearisation();
    const double dt = std::isfinite(h.haff_time) ? 0.7 * h.haff_time : 1.0;
    std::vector<double> cooled;
    closure->cool({n}, {T}, dt, cooled);
    const double n_fixed = n;
    const double reference =
        rk4([&](double, double y) { return -at(*closure, n_fixed, y).rate; }, T, 0.0, dt, 4000);
    EXPECT_NEAR(cooled[0] / reference, 1.0, 1e-10) << "n = " << n << ", T = " << T;
  }
}

TEST_P(EveryClosure, HcsLinearisationIsTheClosureAtNEqualsOneAndTEqualsOne) {
  const HcsLinearisation h = closure->hcs_linearisation();
  const Point x = at(*closure, 1.0, 1.0);
  // Haff: dT/dt = -Lambda(1, T) from T = 1 gives T_H = (1 + t/t0)^-2 with t0 = 2/Lambda(1, 1).
  EXPECT_NEAR(h.haff_time * x.rate / 2.0, 1.0, 4e-15);
  EXPECT_NEAR(h.epsilon * h.haff_time, 1.0, 4e-15);
  EXPECT_DOUBLE_EQ(h.compression_heating, x.p);
  EXPECT_DOUBLE_EQ(h.viscosity, x.eta);
  EXPECT_DOUBLE_EQ(h.shear_viscosity, x.eta_xy);
  EXPECT_DOUBLE_EQ(h.conductivity, x.kappa);
  EXPECT_DOUBLE_EQ(h.mu, x.mu);
  // Derivatives by central differences (step 1e-5: truncation 1e-10 relative).
  const double d = 1e-5;
  const Point n_plus = at(*closure, 1.0 + d, 1.0), n_minus = at(*closure, 1.0 - d, 1.0);
  const Point T_plus = at(*closure, 1.0, 1.0 + d), T_minus = at(*closure, 1.0, 1.0 - d);
  EXPECT_NEAR(h.pressure_density, (n_plus.p - n_minus.p) / (2 * d), 1e-9 * x.p);
  EXPECT_NEAR(h.pressure_temperature, (T_plus.p - T_minus.p) / (2 * d), 1e-9 * x.p);
  EXPECT_NEAR(h.cooling_density, (n_plus.rate - n_minus.rate) / (2 * d), 1e-9 * x.rate);
  EXPECT_NEAR(h.cooling_temperature, (T_plus.rate - T_minus.rate) / (2 * d) - x.rate,
              1e-9 * x.rate);
  // The hard-disk temperature scaling the collision-clock theory assumes (closure.hpp):
  // p ~ T, eta, kappa ~ T^{1/2}, mu, Lambda ~ T^{3/2} at fixed n (mu = 0 in some closures).
  const Point hot = at(*closure, 1.7, 4.0), cold = at(*closure, 1.7, 1.0);
  EXPECT_NEAR(hot.p / cold.p, 4.0, 1e-14);
  EXPECT_NEAR(hot.eta / cold.eta, 2.0, 1e-14);
  EXPECT_NEAR(hot.eta_xy / cold.eta_xy, 2.0, 1e-14);
  EXPECT_NEAR(hot.kappa / cold.kappa, 2.0, 1e-14);
  EXPECT_NEAR(hot.rate / cold.rate, 8.0, 1e-14);
  EXPECT_NEAR(hot.mu, 8.0 * cold.mu, 1e-14 * std::abs(hot.mu));
}

INSTANTIATE_TEST_SUITE_P(Registered, EveryClosure,
                         ::testing::Combine(::testing::ValuesIn(closure_names()),
                                            ::testing::Values(0, 1, 2)));

TEST_P(EveryClosure, ModeCountsAreTheSignsOfTheDispersionRelation) {
  // Below the clustering cutoff det A > 0 (one real growing rate and two decaying ones), above
  // it det A < 0; below the
  // shear cutoff the shear rate is positive. Checked at the last unstable and first stable mode.
  const int clustering = clustering_unstable_modes(*closure);
  const int shear = shear_unstable_modes(*closure);
  ASSERT_GT(clustering, 0);
  EXPECT_GT(hcs_linear_operator(*closure, clustering).determinant().real(), 0.0);
  EXPECT_LT(hcs_linear_operator(*closure, clustering + 1).determinant().real(), 0.0);
  EXPECT_GT(hcs_modes(*closure, clustering)[0].rate.real(), 0.0);
  EXPECT_GT(shear_rate(*closure, shear), 0.0);
  EXPECT_LT(shear_rate(*closure, shear + 1), 0.0);
}

TEST(ClosureRegistry, NamesTheDiluteClosureAndRejectsUnknownNames) {
  EXPECT_EQ(make_closure("dilute", {Physics{4e-4, 0.01}, {}})->name(), "dilute");
  try {
    make_closure("van_der_waals", {Physics{4e-4, 0.01}, {}});
    FAIL() << "an unknown closure was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("known: dilute"), std::string::npos) << e.what();
  }
}

TEST(TimeSeriesColumns, RecordFillsEveryColumnInTheResultsFileOrder) {
  // The order of /hydro/timeseries in results.h5 (docs/outputs.md).
  const std::vector<std::string> expected{"t",
                                          "dt",
                                          "n_max",
                                          "x_peak",
                                          "dvdx_peak",
                                          "T_min",
                                          "T_mean",
                                          "energy",
                                          "energy_thermal",
                                          "energy_kinetic",
                                          "energy_kinetic_y",
                                          "energy_cooled",
                                          "momentum",
                                          "haff_T",
                                          "phi_max",
                                          "knudsen_n_max",
                                          "knudsen_v_max",
                                          "knudsen_T_max",
                                          "collision_flow_max"};
  std::vector<std::string> names;
  for (const auto& column : time_series_columns()) names.push_back(column.name);
  EXPECT_EQ(names, expected);

  TimeSeriesSample sample;
  sample.t = 0.5;
  sample.dt = 1e-3;
  sample.diagnostics.n_max = 3.0;
  sample.diagnostics.energy_thermal = 0.25;
  sample.diagnostics.energy_kinetic = 0.125;
  sample.energy_cooled = 0.75;
  sample.haff_T = 0.01;
  sample.area_fraction_known = true;
  TimeSeries series;
  series.record(sample);
  series.record(sample);
  for (const auto& column : time_series_columns()) {
    EXPECT_EQ((series.*column.values).size(), 2u) << column.name;
    EXPECT_EQ((series.*column.values).back(), column.value(sample)) << column.name;
  }
  EXPECT_EQ(series.n_max.back(), 3.0);
  EXPECT_EQ(series.energy.back(), 0.375);
  EXPECT_EQ(series.energy_cooled.back(), 0.75);
  EXPECT_EQ(series.haff_T.back(), 0.01);
}

}  // namespace
}  // namespace granvv::hydro
