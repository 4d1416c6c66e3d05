// The Garzo-Dufty closure (hydro/garzo_dufty_closure.hpp): its reduced coefficients against
// the numbers the paper's dilute closure is measured by (the elastic coefficients are 2.5 % and
// 5.4 % low in eta at r = 0.9 and 0.8, 2.0 % and 10.3 % in kappa, and a pressure-balanced mode
// sees kappa - mu n/T = 0.858 of the elastic kappa at r = 0.9), its limits (r -> 1: the Enskog
// closure; phi0 -> 0 and r -> 1: the dilute closure), and the fields it hands the operator.
// The registered-closure conformance suite (tests/test_closure.cpp) and the linear growth of
// seeded eigenmodes (tests/test_linear_growth.cpp) run it too.
#include <gtest/gtest.h>

#include <cmath>

#include "hydro/closure.hpp"
#include "hydro/dilute_closure.hpp"
#include "hydro/enskog_closure.hpp"
#include "hydro/garzo_dufty_closure.hpp"
#include "hydro/garzo_dufty_coefficients.hpp"

namespace granvv::hydro {
namespace {

using garzo_dufty::dilute_coefficients;

TEST(GarzoDuftyCoefficients, ElasticClosureIsLowByTheMeasuredAmounts) {
  // The numbers are given to the quoted digit: tolerance half a unit of the last digit.
  const auto r09 = dilute_coefficients(0.9), r08 = dilute_coefficients(0.8);
  EXPECT_NEAR(1.0 - 1.0 / r09.viscosity, 0.025, 0.0005);
  EXPECT_NEAR(1.0 - 1.0 / r08.viscosity, 0.054, 0.0005);
  EXPECT_NEAR(1.0 - 1.0 / r09.conductivity, 0.020, 0.0005);
  EXPECT_NEAR(1.0 - 1.0 / r08.conductivity, 0.103, 0.0005);
  // What a pressure-balanced mode sees (p_T/p_n = 1 in the dilute gas): kappa* - mu*.
  EXPECT_NEAR(r09.conductivity - r09.mu, 0.858, 0.0005);
  // The elastic closure's conductivity is 17 % and 33 % too high for that mode.
  EXPECT_NEAR(1.0 / (r09.conductivity - r09.mu), 1.17, 0.005);
  EXPECT_NEAR(1.0 / (r08.conductivity - r08.mu), 1.33, 0.005);
  // van Noije & Ernst's a2 of disks at r = 0.9, -0.0269 (physics.md §9 quotes -0.027).
  EXPECT_NEAR(r09.a2, -0.02686, 5e-6);
}

TEST(GarzoDuftyCoefficients, ElasticLimitIsTheElasticGas) {
  const auto elastic = dilute_coefficients(1.0);
  EXPECT_EQ(elastic.a2, 0.0);
  EXPECT_EQ(elastic.cooling, 0.0);
  EXPECT_EQ(elastic.mu, 0.0);
  EXPECT_NEAR(elastic.viscosity, 1.0, 1e-15);
  EXPECT_NEAR(elastic.conductivity, 1.0, 1e-15);
  // Nearly elastic: each departs linearly in 1 - r (mu* ~ (1 - r) too).
  const auto near = dilute_coefficients(1.0 - 2e-6), nearer = dilute_coefficients(1.0 - 1e-6);
  EXPECT_NEAR((near.viscosity - 1.0) / (nearer.viscosity - 1.0), 2.0, 1e-4);
  EXPECT_NEAR((near.conductivity - 1.0) / (nearer.conductivity - 1.0), 2.0, 1e-4);
  EXPECT_NEAR(near.mu / nearer.mu, 2.0, 1e-4);
}

TEST(GarzoDuftyCoefficients, CoolingRateIsTheExactLossTimesTheSonineCorrection) {
  // zeta* = (d+2)/(4d) (1 - r^2) (1 + 3 a2/16), d = 2; and the closure's sink with the exact
  // loss is (8q/K)(1 - q)(1 + 3 a2/16) n T^{3/2} = 2 (1 - r^2)/K (...): the same rate.
  const double r = 0.8;
  const auto c = dilute_coefficients(r);
  EXPECT_NEAR(c.cooling, 0.5 * (1 - r * r) * (1 + 3 * c.a2 / 16), 1e-15);
  const Physics physics{0.01, (1 - r) / 2};
  const GarzoDuftyClosure closure(physics, 0.0, CoolingRate::exact);
  std::vector<double> rate;
  closure.cooling_rate({1.0}, {1.0}, rate);
  // zeta T with nu0 = p/eta0 = 4 n T^{1/2}/K: 4 zeta*/K at n = T = 1.
  EXPECT_NEAR(rate[0], 4.0 * c.cooling / physics.K, 1e-12 * rate[0]);
}

CellCoefficients cells_of(const Closure& closure, const std::vector<double>& n,
                          const std::vector<double>& T) {
  CellCoefficients out;
  closure.cell_coefficients(n, T, out);
  return out;
}

const std::vector<double> kN{0.4, 1.0, 2.5}, kT{2.0, 1.0, 0.05};

void expect_relatively_near(const std::vector<double>& a, const std::vector<double>& b,
                            double tolerance, const char* what) {
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i], b[i], tolerance * std::abs(b[i])) << what << " at " << i;
  }
}

TEST(GarzoDuftyClosure, ElasticLimitIsTheEnskogClosureAndDiluteLimitTheDiluteClosure) {
  // q = 0: the reduced coefficients are 1 to rounding (1e-15); q = 1e-7: they differ from 1
  // by O(q), below 1e-6.
  for (const double q : {0.0, 1e-7}) {
    SCOPED_TRACE(q);
    const double tolerance = q == 0.0 ? 1e-14 : 1e-6;
    const Physics physics{2e-3, q};
    const auto gd = cells_of(GarzoDuftyClosure(physics, 0.2, CoolingRate::exact), kN, kT);
    const auto en = cells_of(EnskogClosure(physics, 0.2, CoolingRate::exact), kN, kT);
    expect_relatively_near(gd.pressure, en.pressure, 1e-15, "p");
    expect_relatively_near(gd.viscosity, en.viscosity, tolerance, "eta");
    expect_relatively_near(gd.shear_viscosity, en.shear_viscosity, tolerance, "eta_xy");
    expect_relatively_near(gd.conductivity, en.conductivity, tolerance, "kappa");
    const auto gd0 = cells_of(GarzoDuftyClosure(physics, 0.0, CoolingRate::exact), kN, kT);
    const auto di = cells_of(DiluteClosure(physics, CoolingRate::exact), kN, kT);
    expect_relatively_near(gd0.pressure, di.pressure, 1e-15, "dilute p");
    expect_relatively_near(gd0.adiabatic_modulus, di.adiabatic_modulus, 1e-15, "dilute B");
    expect_relatively_near(gd0.viscosity, di.viscosity, tolerance, "dilute eta");
    expect_relatively_near(gd0.conductivity, di.conductivity, tolerance, "dilute kappa");
    for (size_t i = 0; i < kN.size(); ++i) {
      // mu ~ (1 - r): 0 at q = 0, about 2.7 q kappa T/n at small q (d mu*/dq = 2 dmu*/d(1-r)).
      EXPECT_LE(std::abs(gd.mu[i]), 10.0 * q * gd.conductivity[i] * kT[i] / kN[i]);
    }
    if (q > 0.0) {
      std::vector<double> a, b;
      GarzoDuftyClosure(physics, 0.2, CoolingRate::exact).cooling_rate(kN, kT, a);
      EnskogClosure(physics, 0.2, CoolingRate::exact).cooling_rate(kN, kT, b);
      expect_relatively_near(a, b, tolerance, "Lambda");
    }
  }
}

TEST(GarzoDuftyClosure, CoefficientsAreTheReducedOnesInThePaperScaling) {
  // Dilute, r = 0.9 (q = 0.05), K = 1e-3: eta = (K/4) T^{1/2} eta*, kappa = K T^{1/2} kappa*,
  // mu = K T^{3/2} mu*/n.
  const Physics physics{1e-3, 0.05};
  const GarzoDuftyClosure closure(physics, 0.0, CoolingRate::small_q);
  const auto c = closure.reduced();
  const auto cell = cells_of(closure, {2.0}, {0.25});
  EXPECT_DOUBLE_EQ(cell.pressure[0], 0.5);
  EXPECT_DOUBLE_EQ(cell.viscosity[0], 0.25e-3 * 0.5 * c.viscosity);
  EXPECT_DOUBLE_EQ(cell.shear_viscosity[0], cell.viscosity[0]);
  EXPECT_DOUBLE_EQ(cell.conductivity[0], 1e-3 * 0.5 * c.conductivity);
  EXPECT_DOUBLE_EQ(cell.mu[0], 1e-3 * 0.125 * c.mu / 2.0);
  // A pressure-balanced mode's conduction kappa - mu n/T, relative to the elastic K T^{1/2}.
  EXPECT_NEAR((cell.conductivity[0] - cell.mu[0] * 2.0 / 0.25) / (1e-3 * 0.5), 0.858, 0.0005);
  const HcsLinearisation h = closure.hcs_linearisation();
  EXPECT_DOUBLE_EQ(h.mu, 1e-3 * c.mu);
  // Clustering cutoff: (kappa - mu) kx^2 = Lambda_n - Lambda_T' = eps (p_n = p_T = 1).
  const double kx = 2 * M_PI * h.clustering_cutoff_mode;
  EXPECT_NEAR((h.conductivity - h.mu) * kx * kx, h.epsilon, 1e-12 * h.epsilon);
}

TEST(GarzoDuftyClosure, RefusesAnAreaFractionOutsideTheFluid) {
  const ClosureParameters frozen{Physics{1e-3, 0.05}, {{"area_fraction", 0.7}}};
  const auto problem = closure_parameter_problem("garzo_dufty", frozen);
  ASSERT_TRUE(problem.has_value());
  EXPECT_EQ(problem->parameter, "area_fraction");
  EXPECT_FALSE(closure_parameter_problem("garzo_dufty", {Physics{1e-3, 0.05}, {}}).has_value());
  EXPECT_THROW(GarzoDuftyClosure(Physics{1e-3, 0.05}, -0.1, CoolingRate::exact),
               std::invalid_argument);
  // Below r = 0.345 the first Sonine kappa* - mu* is negative: refused, naming physics.q.
  const auto strong = closure_parameter_problem("garzo_dufty", {Physics{1e-3, 0.33}, {}});
  ASSERT_TRUE(strong.has_value());
  EXPECT_EQ(strong->parameter, "q");
  EXPECT_FALSE(closure_parameter_problem("garzo_dufty", {Physics{1e-3, 0.32}, {}}).has_value());
  EXPECT_TRUE(closure_has_density_heat_flux("garzo_dufty"));
  EXPECT_FALSE(closure_has_density_heat_flux("dilute"));
  EXPECT_FALSE(closure_has_density_heat_flux("enskog"));
}

}  // namespace
}  // namespace granvv::hydro
