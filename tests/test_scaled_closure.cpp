// Injected model errors (hydro/scaled_closure.hpp, hydro/transport_factors.hpp): each factor
// multiplies its coefficient and nothing else; the cooling step is the wrapped one run for
// f dt; the generic linear cutoffs equal each closure's own to round-off when every factor is 1
// and follow the dilute closure's closed forms when they are not; and a homogeneous hydro run
// with a scaled cooling sink follows Haff's law with t0 / f.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "hydro/closure.hpp"
#include "hydro/driver.hpp"
#include "hydro/haff.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "hydro/scaled_closure.hpp"
#include "support/run_control.hpp"

namespace granvv::hydro {
namespace {

const Physics kPhysics{1e-3, 0.05};
const std::vector<double> kN{0.5, 1.0, 2.5, 4.0}, kT{1.0, 0.3, 2.0, 0.01};

ClosureParameters parameters(const std::string& name, const TransportFactors& f) {
  ClosureParameters p{kPhysics, {}, CoolingRate::small_q, f};
  if (name != "dilute") p.extra["area_fraction"] = 0.1;
  return p;
}

TEST(ScaledClosure, EachFactorMultipliesItsCoefficientOnly) {
  for (const std::string name : {"dilute", "enskog", "garzo_dufty"}) {
    SCOPED_TRACE(name);
    const auto plain = make_closure(name, parameters(name, {}));
    const auto scaled = make_closure(name, parameters(name, {2.0, 3.0, 0.5, 4.0}));
    EXPECT_EQ(scaled->name(), name);
    CellCoefficients a, b;
    plain->cell_coefficients(kN, kT, a);
    scaled->cell_coefficients(kN, kT, b);
    std::vector<double> ca, cb, ra, rb, Ta, Tb;
    plain->sound_speed(kN, kT, ca);
    scaled->sound_speed(kN, kT, cb);
    plain->cooling_rate(kN, kT, ra);
    scaled->cooling_rate(kN, kT, rb);
    plain->cool(kN, kT, 0.5 * 0.7, Ta);
    scaled->cool(kN, kT, 0.7, Tb);
    for (std::size_t i = 0; i < kN.size(); ++i) {
      EXPECT_EQ(b.pressure[i], a.pressure[i]);
      EXPECT_EQ(b.adiabatic_modulus[i], a.adiabatic_modulus[i]);
      EXPECT_EQ(cb[i], ca[i]);
      EXPECT_DOUBLE_EQ(b.viscosity[i], 2.0 * a.viscosity[i]);
      EXPECT_DOUBLE_EQ(b.shear_viscosity[i], 2.0 * a.shear_viscosity[i]);
      EXPECT_DOUBLE_EQ(b.conductivity[i], 3.0 * a.conductivity[i]);
      EXPECT_DOUBLE_EQ(b.mu[i], 4.0 * a.mu[i]);  // 0 = 0 where the closure has no mu
      EXPECT_DOUBLE_EQ(rb[i], 0.5 * ra[i]);
      EXPECT_EQ(Tb[i], Ta[i]) << "cooling for dt at rate f Lambda is cooling for f dt";
    }
    EXPECT_DOUBLE_EQ(scaled->hcs_linearisation().haff_time,
                     2.0 * plain->hcs_linearisation().haff_time);
    EXPECT_DOUBLE_EQ(scaled->hcs_linearisation().mu, 4.0 * plain->hcs_linearisation().mu);
  }
}

TEST(ScaledClosure, UnitFactorsAreNotWrappedAndGenericCutoffsAreEachClosuresOwn) {
  for (const std::string name : {"dilute", "enskog", "garzo_dufty"}) {
    SCOPED_TRACE(name);
    EXPECT_EQ(dynamic_cast<const ScaledClosure*>(make_closure(name, parameters(name, {})).get()),
              nullptr);
    const HcsLinearisation own = make_closure(name, parameters(name, {}))->hcs_linearisation();
    const HcsLinearisation generic =
        ScaledClosure(make_closure(name, parameters(name, {})), {}).hcs_linearisation();
    EXPECT_NEAR(generic.clustering_cutoff_mode, own.clustering_cutoff_mode,
                1e-12 * own.clustering_cutoff_mode);
    EXPECT_NEAR(generic.shear_cutoff_mode, own.shear_cutoff_mode, 1e-12 * own.shear_cutoff_mode);
  }
}

TEST(ScaledClosure, DiluteCutoffsFollowTheirClosedForms) {
  // Dilute: the clustering mode grows for pi k K sqrt(f_kappa / f_Lambda) < sqrt(q), the shear
  // mode for pi k K sqrt(f_eta / f_Lambda) < 2 sqrt(q) (physics.md §2 with kappa, eta, Lambda
  // scaled).
  const double fe = 1.7, fk = 0.6, fc = 1.3;
  const HcsLinearisation h =
      make_closure("dilute", parameters("dilute", {fe, fk, fc}))->hcs_linearisation();
  EXPECT_NEAR(h.clustering_cutoff_mode,
              std::sqrt(kPhysics.q) / (M_PI * kPhysics.K * std::sqrt(fk / fc)), 1e-10);
  EXPECT_NEAR(h.shear_cutoff_mode,
              2 * std::sqrt(kPhysics.q) / (M_PI * kPhysics.K * std::sqrt(fe / fc)), 1e-10);
}

TEST(ScaledClosure, HomogeneousRunCoolsWithTheScaledHaffTime) {
  // A uniform gas stays uniform; its T follows Haff's law with t0 = K / (4 q f) to the
  // round-off of the exact split cooling step.
  const double f = 1.25;
  const auto closure = make_closure("dilute", parameters("dilute", {1.0, 1.0, f}));
  const auto fields = make_initial_fields(
      initial_parameters("uniform", {{"transverse_amplitude", 0.0}, {"transverse_mode", 1LL}}),
      *closure);
  const RunResult r =
      run_hydro(*closure, discretize(fields, 16, 0.5, false), testing::run_control(50.0));
  ASSERT_EQ(r.status, RunStatus::completed) << r.stop_reason;
  const double t0 = kPhysics.K / (4 * kPhysics.q * f);
  double worst = 0;
  for (std::size_t i = 0; i < r.series.t.size(); ++i) {
    worst = std::max(worst, std::abs(r.series.T_mean[i] / haff_temperature(r.series.t[i], t0) - 1));
  }
  EXPECT_LT(worst, 1e-12);
}

}  // namespace
}  // namespace granvv::hydro
