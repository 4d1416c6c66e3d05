// The hydro's initial cells hold the integrals of the fields they are built from
// (hydro/field_integrals.hpp, discretize): mass, momenta and energy to round-off, for a table's
// interpolant on irregular rows (whose pieces the quadrature integrates exactly) and for smooth
// profiles; a field that is not finite where it is evaluated is named, not run.
#include <gtest/gtest.h>

#include <cmath>

#include "hydro/dilute_closure.hpp"
#include "hydro/driver.hpp"
#include "hydro/field_integrals.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "hydro/profile_table.hpp"
#include "support/run_control.hpp"

namespace granvv::hydro {
namespace {

FieldTotals cell_totals(const LagrangianState& s) {
  FieldTotals t;
  for (int i = 0; i < s.cells(); ++i) t.energy += s.cell_mass[i] * s.cell_T[i];
  for (int j = 0; j < s.cells(); ++j) {
    const double mu = node_mass(s, j), vy = s.has_transverse() ? s.node_vy[j] : 0.0;
    t.momentum_x += mu * s.node_v[j];
    t.momentum_y += mu * vy;
    t.energy += 0.5 * mu * (s.node_v[j] * s.node_v[j] + vy * vy);
  }
  for (const double m : s.cell_mass) t.mass += m;
  return t;
}

// Round-off of sums over a few thousand cells and panels.
constexpr double kRoundOff = 1e-12;

TEST(InitialTotals, IrregularTableOnAnyMeshHoldsItsInterpolantsIntegrals) {
  ProfileTable t;
  t.x = {-0.5, -0.31, -0.2, 0.0, 0.07, 0.45};
  t.n = {0.5, 1.0, 3.0, 4.0, 1.2, 0.5};
  t.v_x = {0.1, -0.2, 0.3, 0.0, -0.1, 0.05};
  t.v_y = {0.0, 0.02, -0.01, 0.03, 0.0, -0.02};
  t.T = {1.0, 2.0, 0.5, 1.5, 1.0, 0.8};
  for (const auto interpolation : {Interpolation::linear, Interpolation::monotone_cubic}) {
    const InitialFields f = profile_fields(t, interpolation);
    const FieldTotals given = field_totals(f, true);
    for (const int cells : {7, 64, 500}) {
      for (const double offset : {0.0, 0.5}) {
        const FieldTotals held = cell_totals(discretize(f, cells, offset, true));
        EXPECT_LE(largest_relative_difference(held, given), kRoundOff)
            << cells << " cells, offset " << offset;
      }
    }
    // The panels' count does not matter for a piecewise polynomial: integrated exactly.
    EXPECT_NEAR(field_totals(f, true, 3).mass, given.mass, kRoundOff);
  }
}

TEST(InitialTotals, SingleModeWithTransverseVelocityHoldsItsIntegrals) {
  const DiluteClosure closure(Physics{4e-4, 0.01});
  const InitialParameters ip = initial_parameters("single_mode", {{"velocity_amplitude", -0.05},
                                                                  {"mode", 1LL},
                                                                  {"transverse_amplitude", 0.02},
                                                                  {"transverse_mode", 2LL}});
  const InitialFields f = make_initial_fields(ip, closure);
  const FieldTotals given = field_totals(f, true);
  const FieldTotals held = cell_totals(discretize(f, 200, 0.5, true));
  EXPECT_LE(largest_relative_difference(held, given), kRoundOff);
  EXPECT_NEAR(given.mass, 1.0, kRoundOff);
}

TEST(InitialTotals, NonFiniteFieldNamesItsKey) {
  const InitialParameters ip =
      initial_parameters("expression", {{"density", std::string("1")},
                                        {"velocity", std::string("x > 0.2 ? 0/0 : 0")},
                                        {"temperature", std::string("1")},
                                        {"transverse_velocity", std::string("0")},
                                        {"constants", NamedReals{}},
                                        {"transverse_amplitude", 0.0},
                                        {"transverse_mode", 1LL}});
  const InitialFields f = make_initial_fields(ip, Physics{4e-4, 0.01});
  EXPECT_EQ(f.v(0.1), 0.0);
  try {
    (void)f.v(0.3);
    FAIL() << "a NaN velocity was returned";
  } catch (const InitialFieldError& e) {
    EXPECT_EQ(e.parameter, "velocity");
    EXPECT_NE(std::string(e.what()).find("x = 0.3"), std::string::npos) << e.what();
  }
}

TEST(InitialTotals, RunFromANonFiniteStateNamesTheCause) {
  LagrangianState s = discretize(uniform_fields(), 16, 0.5, false);
  s.node_v[5] = std::nan("");
  const RunResult r = run_hydro(DiluteClosure(Physics{4e-4, 0.01}), s, testing::run_control(1.0));
  EXPECT_EQ(r.status, RunStatus::failed);
  EXPECT_NE(r.stop_reason.find("non-finite initial field"), std::string::npos) << r.stop_reason;
  EXPECT_NE(r.stop_reason.find("velocity"), std::string::npos) << r.stop_reason;
}

}  // namespace
}  // namespace granvv::hydro
