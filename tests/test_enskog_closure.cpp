// The Enskog closure (hydro/enskog_closure.hpp, docs/physics.md §9): each factor against its
// formula written out here, the closure's coefficients as the dilute ones times the factors,
// the sound speed against a finite-difference derivative of the pressure along the adiabat,
// the dilute limit bit for bit, the exact cooling factor, the parameter checks, and a run that
// reaches the freezing area fraction stopping with its reason.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "fields/constants.hpp"
#include "hydro/dilute_closure.hpp"
#include "hydro/driver.hpp"
#include "hydro/enskog_closure.hpp"
#include "hydro/enskog_factors.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "support/run_control.hpp"
#include "support/runge_kutta.hpp"

namespace granvv::hydro {
namespace {

using granvv::testing::rk4;

// The formulas, written out independently of hydro/enskog_factors.hpp.
double chi_formula(double phi) {
  return (1 - 7 * phi / 16) / ((1 - phi) * (1 - phi));
}

TEST(EnskogFactors, EachFactorIsItsFormula) {
  // Known values: chi(1/2) = (25/32) / (1/4) = 25/8 exactly; every factor is 1 at phi = 0.
  EXPECT_EQ(enskog::chi(0.5), 3.125);
  EXPECT_EQ(enskog::pressure_factor(0.5, 1.0), 4.125);  // 1 + 2 (1/2)(25/8)
  for (double f : {enskog::chi(0.0), enskog::pressure_factor(0.0, 0.9),
                   enskog::viscosity_factor(0.0), enskog::shear_viscosity_factor(0.0),
                   enskog::conductivity_factor(0.0), enskog::cooling_factor(0.0)}) {
    EXPECT_EQ(f, 1.0);
  }
  EXPECT_EQ(enskog::sound_speed_factor(0.0, 0.9), 2.0);  // the dilute 2D gas: c^2 = 2T
  // At a few area fractions, to rounding (1e-14 relative).
  for (double phi : {0.01, 0.05, 0.27, 0.5, 0.68}) {
    for (double r : {1.0, 0.9, 0.5}) {
      const double x = chi_formula(phi);
      EXPECT_NEAR(enskog::chi(phi), x, 1e-14 * x) << phi;
      EXPECT_NEAR(enskog::pressure_factor(phi, r), 1 + (1 + r) * phi * x, 1e-14 * x) << phi;
    }
    const double x = chi_formula(phi);
    const double eta = 1 / x + 2 * phi + (1 + 24 / kPi) * phi * phi * x;
    const double eta_xy = 1 / x + 2 * phi + (1 + 8 / kPi) * phi * phi * x;
    const double kappa = 1 / x + 3 * phi + (9.0 / 4 + 4 / kPi) * phi * phi * x;
    EXPECT_NEAR(enskog::viscosity_factor(phi), eta, 1e-14 * eta) << phi;
    EXPECT_NEAR(enskog::shear_viscosity_factor(phi), eta_xy, 1e-14 * eta_xy) << phi;
    EXPECT_NEAR(enskog::conductivity_factor(phi), kappa, 1e-14 * kappa) << phi;
    EXPECT_NEAR(enskog::cooling_factor(phi), x, 1e-14 * x) << phi;
    // The bulk viscosity (16/pi) phi^2 chi is the difference of the two viscosities.
    EXPECT_NEAR(eta - eta_xy, 16 / kPi * phi * phi * x, 1e-13 * eta);
  }
}

TEST(EnskogFactors, DerivativesAreFiniteDifferences) {
  // Central differences, step 1e-6: truncation ~1e-12, rounding ~1e-10 relative; tolerance 1e-8.
  const double h = 1e-6;
  for (double phi : {0.05, 0.3, 0.6}) {
    const double dchi = (enskog::chi(phi + h) - enskog::chi(phi - h)) / (2 * h);
    EXPECT_NEAR(enskog::chi_derivative(phi) / dchi, 1.0, 1e-8) << phi;
    const double r = 0.8;
    const double dfp =
        (enskog::pressure_factor(phi + h, r) - enskog::pressure_factor(phi - h, r)) / (2 * h);
    EXPECT_NEAR(enskog::pressure_factor_derivative(phi, r) / dfp, 1.0, 1e-8) << phi;
  }
}

// Temperature at density n1 on the adiabat through (n0, T0): the internal energy per particle
// is T, so dT = p dn / n^2 with the dense p = n T F_p.
double adiabat(double phi0, double r, double n0, double T0, double n1) {
  return rk4([&](double n, double T) { return T * enskog::pressure_factor(phi0 * n, r) / n; }, T0,
             n0, n1, 400);
}

TEST(EnskogClosure, SoundSpeedIsTheDerivativeOfPressureAlongTheAdiabat) {
  // c^2 = dp/dn at fixed entropy, by central differences (relative step 1e-5: truncation
  // ~3e-9 at phi = 0.6, rounding ~1e-10) of p = n T F_p along the adiabat; tolerance 1e-7. Up to
  // phi = 0.6, where the dense terms dominate (c^2 / T = 26.9 against 2 for the dilute gas).
  const double phi0 = 0.3, q = 0.05, r = 1 - 2 * q;
  const EnskogClosure closure({1e-3, q}, phi0, CoolingRate::small_q);
  for (const auto& [n, T] : {std::pair{1.0, 1.0}, {0.3, 2.0}, {2.0, 0.01}}) {
    const double h = 1e-5 * n;
    const auto p = [&](double m) {
      return m * adiabat(phi0, r, n, T, m) * enskog::pressure_factor(phi0 * m, r);
    };
    const double c2_fd = (p(n + h) - p(n - h)) / (2 * h);
    std::vector<double> c;
    closure.sound_speed({n}, {T}, c);
    EXPECT_NEAR(c[0] * c[0] / c2_fd, 1.0, 1e-7) << "n = " << n << ", T = " << T;
    // d ln T / d ln n = F_p along the adiabat.
    const double dlnT =
        (std::log(adiabat(phi0, r, n, T, n + h)) - std::log(adiabat(phi0, r, n, T, n - h))) /
        (std::log(n + h) - std::log(n - h));
    EXPECT_NEAR(dlnT, enskog::pressure_factor(phi0 * n, r), 1e-7);
  }
}

TEST(EnskogClosure, CoefficientsAreTheDiluteOnesTimesTheFactors) {
  const Physics physics{2e-3, 0.05};
  const double phi0 = 0.2, n = 1.5, T = 0.64, phi = 0.3, r = 0.9;  // T^{1/2} = 0.8
  for (const CoolingRate cooling : {CoolingRate::small_q, CoolingRate::exact}) {
    const EnskogClosure closure(physics, phi0, cooling);
    CellCoefficients cell;
    std::vector<double> c, rate;
    closure.cell_coefficients({n}, {T}, cell);
    closure.sound_speed({n}, {T}, c);
    closure.cooling_rate({n}, {T}, rate);
    const double x = chi_formula(phi), f_p = 1 + (1 + r) * phi * x;
    EXPECT_NEAR(cell.pressure[0], n * T * f_p, 1e-14);
    EXPECT_NEAR(cell.adiabatic_modulus[0], n * c[0] * c[0], 1e-14);
    EXPECT_NEAR(cell.viscosity[0], 2e-3 / 4 * 0.8 * enskog::viscosity_factor(phi), 1e-18);
    EXPECT_NEAR(cell.shear_viscosity[0], 2e-3 / 4 * 0.8 * enskog::shear_viscosity_factor(phi),
                1e-18);
    EXPECT_NEAR(cell.conductivity[0], 2e-3 * 0.8 * enskog::conductivity_factor(phi), 1e-17);
    // (8q/K) g n T^{3/2} chi: g = 1 - q = 0.95 for the exact 1 - r^2 = 4q(1 - q).
    const double g = cooling == CoolingRate::exact ? 0.95 : 1.0;
    EXPECT_NEAR(rate[0], 8 * 0.05 / 2e-3 * g * n * 0.512 * x, 1e-12 * rate[0]);
  }
}

TEST(EnskogClosure, VanishingAreaFractionIsTheDiluteClosureBitForBit) {
  // phi0 = 1e-300: every factor rounds to 1 (phi <= 1e-290), so each coefficient is the dilute
  // one to the last bit, and so is a run (docs/physics.md §9 gives the single_mode comparison).
  const Physics physics{2e-3, 0.03};
  for (const CoolingRate cooling : {CoolingRate::small_q, CoolingRate::exact}) {
    const DiluteClosure dilute(physics, cooling);
    const EnskogClosure enskog(physics, 1e-300, cooling);
    const std::vector<double> n{0.3, 1.0, 7.5, 1e5}, T{2.0, 1.0, 0.013, 1e-7};
    CellCoefficients a, b;
    std::vector<double> ca, cb, ra, rb, ta, tb;
    dilute.cell_coefficients(n, T, a), enskog.cell_coefficients(n, T, b);
    dilute.sound_speed(n, T, ca), enskog.sound_speed(n, T, cb);
    dilute.cooling_rate(n, T, ra), enskog.cooling_rate(n, T, rb);
    dilute.cool(n, T, 0.01, ta), enskog.cool(n, T, 0.01, tb);
    EXPECT_EQ(a.pressure, b.pressure);
    EXPECT_EQ(a.adiabatic_modulus, b.adiabatic_modulus);
    EXPECT_EQ(a.viscosity, b.viscosity);
    EXPECT_EQ(a.shear_viscosity, b.shear_viscosity);
    EXPECT_EQ(a.conductivity, b.conductivity);
    EXPECT_EQ(ca, cb);
    EXPECT_EQ(ra, rb);
    EXPECT_EQ(ta, tb);
    // The linear theory to rounding (the Haff time is computed as 2/Lambda, not K/(4q)).
    const HcsLinearisation hd = dilute.hcs_linearisation(), he = enskog.hcs_linearisation();
    for (const auto& [x, y] : {std::pair{hd.haff_time, he.haff_time},
                               {hd.epsilon, he.epsilon},
                               {hd.pressure_density, he.pressure_density},
                               {hd.pressure_temperature, he.pressure_temperature},
                               {hd.viscosity, he.viscosity},
                               {hd.shear_viscosity, he.shear_viscosity},
                               {hd.conductivity, he.conductivity},
                               {hd.cooling_density, he.cooling_density},
                               {hd.cooling_temperature, he.cooling_temperature},
                               {hd.clustering_cutoff_mode, he.clustering_cutoff_mode},
                               {hd.shear_cutoff_mode, he.shear_cutoff_mode}}) {
      EXPECT_NEAR(y / x, 1.0, 1e-15);
    }
  }
}

TEST(EnskogClosure, ExactCoolingMultipliesTheSinkByOneMinusQ) {
  // 1 - r^2 = 4q(1 - q) for r = 1 - 2q: the Haff time grows by 1/(1 - q), for both closures.
  const Physics physics{4e-4, 0.1};
  const DiluteClosure small(physics), exact(physics, CoolingRate::exact);
  EXPECT_DOUBLE_EQ(small.cooling_coefficient(), 2000.0);  // 8q/K
  EXPECT_DOUBLE_EQ(exact.cooling_coefficient(), 1800.0);  // 8q(1 - q)/K
  EXPECT_DOUBLE_EQ(small.hcs_linearisation().haff_time, 1e-3);
  EXPECT_DOUBLE_EQ(exact.hcs_linearisation().haff_time, 1e-3 / 0.9);
  const double r = 1 - 2 * physics.q;
  EXPECT_NEAR((1 - r * r) / (4 * physics.q), inelastic_loss_factor(CoolingRate::exact, 0.1), 1e-15);
  const EnskogClosure dense_small(physics, 0.1, CoolingRate::small_q);
  const EnskogClosure dense_exact(physics, 0.1, CoolingRate::exact);
  EXPECT_NEAR(dense_exact.hcs_linearisation().haff_time / dense_small.hcs_linearisation().haff_time,
              1 / 0.9, 1e-15);
  // Enskog's Haff time is the dilute one over chi(phi0).
  EXPECT_NEAR(dense_small.hcs_linearisation().haff_time,
              small.hcs_linearisation().haff_time / chi_formula(0.1), 1e-15);
}

TEST(EnskogClosure, AreaFractionMustLieBelowFreezing) {
  const Physics physics{1e-3, 0.05};
  for (double phi0 : {0.0, -0.1, 0.69, 0.8, std::nan("")}) {
    const ClosureParameters p{physics, {{"area_fraction", phi0}}};
    const auto problem = closure_parameter_problem("enskog", p);
    ASSERT_TRUE(problem.has_value()) << phi0;
    EXPECT_EQ(problem->parameter, "area_fraction");
    EXPECT_NE(problem->reason.find("(0, 0.69)"), std::string::npos) << problem->reason;
    EXPECT_THROW(make_closure("enskog", p), std::invalid_argument) << phi0;
  }
  EXPECT_FALSE(closure_parameter_problem("enskog", {physics, {{"area_fraction", 0.3}}}));
  EXPECT_FALSE(closure_parameter_problem("dilute", {physics, {}}));
  EXPECT_EQ(make_closure("enskog", {physics, {{"area_fraction", 0.3}}})->name(), "enskog");
}

TEST(EnskogClosure, ValidityEndsAtTheFreezingAreaFraction) {
  const EnskogClosure closure({1e-3, 0.05}, 0.3, CoolingRate::small_q);
  EXPECT_EQ(closure.validity_problem({1.0, 2.2, 0.5}), "");              // phi = 0.66
  const std::string reason = closure.validity_problem({1.0, 2.3, 0.5});  // phi = 0.69
  EXPECT_NE(reason.find("freezing fraction 0.69"), std::string::npos) << reason;
  EXPECT_NE(reason.find("cell 1"), std::string::npos) << reason;
  EXPECT_EQ(DiluteClosure({1e-3, 0.05}).validity_problem({1e9}), "");
}

TEST(EnskogClosure, RunThatReachesFreezingStopsWithItsReason) {
  // The single mode a = -0.05 (paper Eq. 7) at phi0 = 0.3 compresses towards the flow-by-inertia
  // singularity; at n = 2.3 the area fraction reaches 0.69 and the run stops there, finite.
  const Physics physics{4e-4, 0.01};
  const EnskogClosure closure(physics, 0.3, CoolingRate::small_q);
  const auto fields =
      make_initial_fields(initial_parameters("single_mode", {{"velocity_amplitude", -0.05},
                                                             {"mode", 1LL},
                                                             {"transverse_amplitude", 0.0},
                                                             {"transverse_mode", 1LL}}),
                          closure);
  const RunResult r =
      run_hydro(closure, discretize(fields, 200, 0.5, false), testing::run_control(10));
  ASSERT_EQ(r.status, RunStatus::closure_limit) << r.stop_reason;
  EXPECT_EQ(to_string(r.status), "closure_limit");
  EXPECT_NE(r.stop_reason.find("freezing"), std::string::npos) << r.stop_reason;
  const double n_last = r.series.n_max.back();
  EXPECT_GE(0.3 * n_last, enskog::kFreezingAreaFraction);
  EXPECT_LT(0.3 * r.series.n_max[r.series.n_max.size() - 2], enskog::kFreezingAreaFraction);
  for (double T : r.snapshots.back().state.cell_T) EXPECT_TRUE(std::isfinite(T) && T > 0);
  EXPECT_LT(r.energy_drift, 1e-12);
}

}  // namespace
}  // namespace granvv::hydro
