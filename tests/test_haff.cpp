// Haff's law and the collision clock (hydro/haff.hpp) against the ODE of the homogeneous
// cooling state, dT/dt = -(8q/K) T^{3/2} (paper Eq. 2 with n = 1, v = 0), integrated
// independently, and against their defining integrals.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <functional>
#include <limits>

#include "hydro/dilute_closure.hpp"
#include "hydro/haff.hpp"
#include "support/runge_kutta.hpp"

namespace {

using granvv::hydro::Physics;

using granvv::testing::rk4;

// c = 8q/K of the dilute closure's sink c n T^{3/2}.
double cooling_coefficient(const Physics& p) {
  return granvv::hydro::DiluteClosure(p).cooling_coefficient();
}

TEST(Haff, TimeScaleAndCoolingCoefficientOfThePaperScene) {
  const Physics paper{4e-4, 0.01};
  EXPECT_DOUBLE_EQ(granvv::hydro::haff_time_scale(paper), 0.01);  // K/(4q)
  EXPECT_DOUBLE_EQ(cooling_coefficient(paper), 200.0);            // 8q/K
  // Haff's law solves dT/dt = -c T^{3/2} with T(0) = 1 only if c = 2/t0.
  EXPECT_DOUBLE_EQ(cooling_coefficient(paper) * granvv::hydro::haff_time_scale(paper), 2.0);
  EXPECT_TRUE(std::isinf(granvv::hydro::haff_time_scale(Physics{4e-4, 0.0})));
}

TEST(Haff, TemperatureSolvesTheHomogeneousCoolingOde) {
  // RK4 with 2e5 steps over 10 t0: global error ~ (h/t0)^4 ~ 1e-16 relative; the tolerance
  // 1e-11 leaves room for rounding accumulated over the steps.
  for (const Physics p : {Physics{4e-4, 0.01}, Physics{0.02, 0.2}, Physics{1e-3, 1e-4}}) {
    const double c = cooling_coefficient(p);
    const double t0 = granvv::hydro::haff_time_scale(p);
    const auto rhs = [c](double, double T) { return -c * std::pow(T, 1.5); };
    double T = 1.0;
    double t = 0.0;
    for (const double t_next : {0.1 * t0, t0, 3.0 * t0, 10.0 * t0}) {
      T = rk4(rhs, T, t, t_next, 50000);
      t = t_next;
      EXPECT_NEAR(T / granvv::hydro::haff_temperature(t, t0), 1.0, 1e-11) << "t/t0 = " << t / t0;
    }
  }
  EXPECT_EQ(granvv::hydro::haff_temperature(0.0, 0.01), 1.0);
  EXPECT_EQ(granvv::hydro::haff_temperature(5.0, std::numeric_limits<double>::infinity()), 1.0);
}

TEST(Haff, CollisionClockIsTheIntegralOfTheThermalSpeed) {
  const double t0 = 0.01;
  // Composite Simpson; T_H^{1/2} varies on the scale t0, and the error is about
  // (h/t0)^4 / 30 relative, so h = t0/2000 gives ~1e-15; tolerance 1e-12.
  for (const double t : {0.003, 0.05, 1.0, 7.043}) {
    const int n = 2 * static_cast<int>(std::ceil(1000.0 * t / t0));
    const double h = t / n;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
      const double weight = (i == 0 || i == n) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
      sum += weight * std::sqrt(granvv::hydro::haff_temperature(i * h, t0));
    }
    const double integral = sum * h / 3.0;
    EXPECT_NEAR(granvv::hydro::collision_clock(t, t0) / integral, 1.0, 1e-12) << "t = " << t;
  }
  // t << t0: s = t (1 - t/(2 t0) + t^2/(3 t0^2)); a naive log(1 + t/t0) would lose ~6 digits.
  const double t = 1e-10 * t0;
  EXPECT_NEAR(granvv::hydro::collision_clock(t, t0) / t, 1.0 - 0.5e-10, 1e-15);
  EXPECT_EQ(granvv::hydro::collision_clock(2.5, std::numeric_limits<double>::infinity()), 2.5);
}

TEST(Haff, ConstantRatesInTheCollisionClockAreAlgebraicInTime) {
  // exp(lambda s(t)) = (1 + t/t0)^{lambda t0}: the paper's "growth/decay ... is algebraic".
  const double t0 = 0.01;
  for (const std::complex<double> lambda :
       {std::complex<double>(100.0, 0.0), std::complex<double>(-37.5, 250.0),
        std::complex<double>(0.73, 0.0)}) {
    for (const double t : {0.01, 0.3, 3.18}) {
      const std::complex<double> lhs = std::exp(lambda * granvv::hydro::collision_clock(t, t0));
      const std::complex<double> rhs = std::pow(std::complex<double>(1.0 + t / t0), lambda * t0);
      EXPECT_LT(std::abs(lhs - rhs), 1e-12 * std::abs(rhs)) << lambda << " t = " << t;
    }
  }
  // lambda = eps = 1/t0 makes w = u/T_H^{1/2} grow exactly as 1/T_H^{1/2}: u stays constant.
  EXPECT_NEAR(std::exp(granvv::hydro::collision_clock(2.0, t0) / t0) *
                  std::sqrt(granvv::hydro::haff_temperature(2.0, t0)),
              1.0, 1e-13);
}

TEST(Haff, ExactCoolingStepSolvesTheLossOde) {
  // Against RK4 of dT/dt = -c n T^{3/2} (1e5 steps: truncation far below the 1e-11 tolerance).
  const double c = 200.0;
  for (const double n : {0.2, 1.0, 17.0}) {
    for (const double T : {1.0, 0.37, 2e-3}) {
      const double dt = 0.02;
      const double reference =
          rk4([c, n](double, double y) { return -c * n * std::pow(y, 1.5); }, T, 0.0, dt, 100000);
      EXPECT_NEAR(granvv::hydro::cool_exactly(T, n, c, dt) / reference, 1.0, 1e-11)
          << "n = " << n << " T = " << T;
    }
  }
}

TEST(Haff, ExactCoolingStepComposesAndReproducesHaff) {
  const Physics p{4e-4, 0.01};
  const double c = cooling_coefficient(p);
  const double t0 = granvv::hydro::haff_time_scale(p);
  // Flow property of an autonomous ODE: two steps equal one step of the summed length
  // (rounding only, 1e-14).
  const double T = 0.8;
  const double n = 3.0;
  const double two_steps =
      granvv::hydro::cool_exactly(granvv::hydro::cool_exactly(T, n, c, 0.013), n, c, 0.029);
  EXPECT_NEAR(two_steps / granvv::hydro::cool_exactly(T, n, c, 0.042), 1.0, 1e-14);
  // n = 1, T = 1: Haff's law.
  for (const double t : {0.0, 0.005, 0.5, 7.0}) {
    EXPECT_NEAR(
        granvv::hydro::cool_exactly(1.0, 1.0, c, t) / granvv::hydro::haff_temperature(t, t0), 1.0,
        1e-14);
  }
  EXPECT_EQ(granvv::hydro::cool_exactly(0.5, 2.0, c, 0.0), 0.5);
}

}  // namespace
