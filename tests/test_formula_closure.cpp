// The closure from the user's formulas (hydro/formula_closure.hpp): with its defaults, the
// dilute closure's formulas, it is the dilute closure to the accuracy of its numerical
// derivatives and cooling integrator; the check of the formulas names the key of the first one
// that is not finite, or not positive where it must be; the cooling step is accurate for a sink
// without Haff's scaling; and a run stops past hydro.density_limit. The conformance suite of
// every closure (tests/test_closure.cpp) runs it too.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "fields/constants.hpp"
#include "hydro/closure.hpp"
#include "hydro/dilute_closure.hpp"
#include "hydro/formula_closure.hpp"

namespace granvv::hydro {
namespace {

ClosureParameters formulas(std::map<std::string, std::string> texts, NamedReals constants = {},
                           CoolingRate cooling = CoolingRate::small_q) {
  ClosureParameters p{Physics{4e-4, 0.01}, {}, cooling};
  p.texts = std::move(texts);
  if (!constants.empty()) p.tables["constants"] = std::move(constants);
  return p;
}

TEST(FormulaClosure, DefaultsAreTheDiluteClosure) {
  // Numerical B and c: fourth-order differences of the linear p = n T, exact but for round-off
  // (~1e-13); the cooling step: one Dormand-Prince step of a constant du/dt (round-off).
  for (const CoolingRate cooling : {CoolingRate::small_q, CoolingRate::exact}) {
    const Physics physics{2e-3, 0.03};
    ClosureParameters params{physics, {}, cooling};
    const FormulaClosure formula(params);
    const DiluteClosure dilute(physics, cooling);
    const std::vector<double> n{1e-5, 0.3, 1.0, 7.5, 1e5}, T{2.0, 1.0, 0.013, 1e-7, 3e3};
    CellCoefficients a, b;
    std::vector<double> ca, cb, ra, rb, Ta, Tb;
    formula.cell_coefficients(n, T, a);
    dilute.cell_coefficients(n, T, b);
    formula.sound_speed(n, T, ca);
    dilute.sound_speed(n, T, cb);
    formula.cooling_rate(n, T, ra);
    dilute.cooling_rate(n, T, rb);
    formula.cool(n, T, 0.01, Ta);
    dilute.cool(n, T, 0.01, Tb);
    for (size_t i = 0; i < n.size(); ++i) {
      SCOPED_TRACE(i);
      EXPECT_NEAR(a.pressure[i] / b.pressure[i], 1.0, 1e-15);
      EXPECT_NEAR(a.adiabatic_modulus[i] / b.adiabatic_modulus[i], 1.0, 1e-12);
      EXPECT_NEAR(a.viscosity[i] / b.viscosity[i], 1.0, 1e-15);
      EXPECT_NEAR(a.shear_viscosity[i] / b.shear_viscosity[i], 1.0, 1e-15);
      EXPECT_NEAR(a.conductivity[i] / b.conductivity[i], 1.0, 1e-15);
      EXPECT_NEAR(ca[i] / cb[i], 1.0, 1e-12);
      EXPECT_NEAR(ra[i] / rb[i], 1.0, 1e-14);
      EXPECT_NEAR(Ta[i] / Tb[i], 1.0, 1e-13);
    }
    const HcsLinearisation x = formula.hcs_linearisation(), y = dilute.hcs_linearisation();
    for (const auto& [u, v] : {std::pair{x.haff_time, y.haff_time},
                               {x.epsilon, y.epsilon},
                               {x.pressure_density, y.pressure_density},
                               {x.pressure_temperature, y.pressure_temperature},
                               {x.compression_heating, y.compression_heating},
                               {x.viscosity, y.viscosity},
                               {x.shear_viscosity, y.shear_viscosity},
                               {x.conductivity, y.conductivity},
                               {x.cooling_density, y.cooling_density},
                               {x.cooling_temperature, y.cooling_temperature},
                               {x.clustering_cutoff_mode, y.clustering_cutoff_mode},
                               {x.shear_cutoff_mode, y.shear_cutoff_mode}}) {
      EXPECT_NEAR(u / v, 1.0, 1e-11);
    }
    EXPECT_EQ(formula.name(), "formula");
  }
}

TEST(FormulaClosure, SuppliesMuToTheCellsAndTheLinearTheory) {
  // mu = 0.3 K T^{3/2} / n: the cells' column and the linearisation's value at n = T = 1, and
  // the clustering cutoff with the conduction kappa - mu p_T/p_n a pressure-balanced mode sees
  // (dilute otherwise: p_n = p_T = 1, Lambda_n = 2 eps, Lambda_T' = eps, so kx^2 = eps / (K -
  // 0.3 K)).
  const FormulaClosure closure(formulas({{"mu", "0.3*K*T^(3/2)/n"}}));
  CellCoefficients cell;
  closure.cell_coefficients({2.0, 0.5}, {4.0, 0.25}, cell);
  EXPECT_DOUBLE_EQ(cell.mu[0], 0.3 * 4e-4 * 8.0 / 2.0);
  EXPECT_DOUBLE_EQ(cell.mu[1], 0.3 * 4e-4 * 0.125 / 0.5);
  const HcsLinearisation h = closure.hcs_linearisation();
  EXPECT_DOUBLE_EQ(h.mu, 0.3 * 4e-4);
  const double kx = std::sqrt(h.epsilon / (0.7 * 4e-4));
  EXPECT_NEAR(h.clustering_cutoff_mode / (kx / kTwoPi), 1.0, 1e-11);
}

TEST(FormulaClosure, CoolingStepFollowsASinkWithoutHaffScaling) {
  // Lambda = a n T^2: T(t) = T0 / (1 + a n T0 t) exactly. The integrator's local error bound is
  // 1e-13 of u = T^{-1/2} per step; over the whole interval the error stays below 1e-11.
  const FormulaClosure closure(formulas({{"cooling_rate", "a*n*T^2"}}, {{"a", 3.0}}));
  for (const auto& [n, T0, dt] : {std::tuple{1.0, 1.0, 0.1}, {5.0, 0.3, 2.0}, {0.5, 2.0, 40.0}}) {
    const double exact = T0 / (1.0 + 3.0 * n * T0 * dt);
    EXPECT_NEAR(closure.cooled(n, T0, dt) / exact, 1.0, 1e-11) << n << " " << T0 << " " << dt;
  }
  EXPECT_EQ(closure.cooled(1.0, 0.7, 0.0), 0.7);
}

struct BadFormula {
  const char* key;
  const char* text;
  const char* says;  // a part of the reason
};

TEST(FormulaClosure, CheckNamesTheKeyOfTheFirstFormulaOutsideItsRange) {
  const BadFormula bad[] = {
      {"pressure", "n*T - 1", "is -1 at n = 1e-06, T = 1e-12 (allowed: finite and > 0"},
      {"viscosity", "sqrt(T - 1)", "nan at n = 1e-06, T = 1e-12"},
      {"shear_viscosity", "K/4*sqrt(T)/(n - 1)^2", "is inf at n = 1,"},
      {"conductivity", "-K*sqrt(T)", "allowed: finite and > 0"},
      {"conductivity", "0", "is 0 at"},
      {"cooling_rate", "(n < 100 ? 1 : -1)*n*T^(3/2)", "is -"},
      {"cooling_rate", "exp(1/T)", "is inf at"},
      {"mu", "1/(n - 1)", "is inf at n = 1,"},
      // p = T/n: B = n p_n + p p_T/n = -T/n + T/n^3 < 0 for n > 1.
      {"pressure", "T/n", "gives the adiabatic modulus"},
      {"pressure", "n*T +", "syntax error in \"n*T +\""},
      {"viscosity", "x*T", "Unexpected token \"x\""},
  };
  for (const auto& b : bad) {
    SCOPED_TRACE(std::string(b.key) + " = " + b.text);
    const ClosureParameters p = formulas({{b.key, b.text}});
    const auto problem = FormulaClosure::parameter_problem(p);
    ASSERT_TRUE(problem.has_value());
    EXPECT_EQ(problem->parameter, b.key);
    EXPECT_NE(problem->reason.find(b.says), std::string::npos) << problem->reason;
    EXPECT_THROW(make_closure("formula", p), std::invalid_argument);
  }
  // The constants: the case's own names and muparser's rules.
  for (const char* name : {"K", "q", "r", "phi0", "n", "T", "pi", "2a"}) {
    const auto problem = FormulaClosure::parameter_problem(formulas({}, {{name, 1.0}}));
    ASSERT_TRUE(problem.has_value()) << name;
    EXPECT_EQ(problem->parameter, "constants") << name;
  }
  // The grid ends at hydro.density_limit: a pole past it is allowed, and the run stops there.
  ClosureParameters dense = formulas({{"pressure", "n*T/(1 - n/10)"}});
  EXPECT_EQ(FormulaClosure::parameter_problem(dense)->parameter, "pressure");
  dense.extra["density_limit"] = 9.0;
  EXPECT_FALSE(FormulaClosure::parameter_problem(dense).has_value());
  const FormulaClosure closure(dense);
  EXPECT_EQ(closure.validity_problem({1.0, 9.0, 2.0}), "");
  EXPECT_NE(closure.validity_problem({1.0, 9.5, 2.0}).find("n = 9.5 in cell 1"), std::string::npos);
  // Good formulas pass, with a constant of the user's.
  EXPECT_FALSE(FormulaClosure::parameter_problem(
                   formulas({{"viscosity", "b*K*sqrt(T)"}, {"mu", "0*n"}}, {{"b", 0.3}}))
                   .has_value());
}

}  // namespace
}  // namespace granvv::hydro
