#pragma once
// A user's formula, evaluated by muparser (Debian libmuparser-dev): the fields of
// initial.type = "expression" in x (hydro/initial_expression.cpp) and the constitutive relations
// of hydro.closure = "formula" in n and T (hydro/formula_closure.hpp). Besides its variables the
// formula may use pi and named constants; muparser's functions (sin, exp, sqrt, abs, min, max,
// ...), ^ and ?: are available.
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "hydro/parameter_set.hpp"

namespace granvv::hydro {

class Formula {
 public:
  // A formula in x. Throws FormulaError for a syntax error, an unknown name, or a constant whose
  // name muparser cannot take (or that is x or pi).
  Formula(const std::string& text, const NamedReals& constants);
  // A formula in the named variables ({"n", "T"}), which no constant may be named.
  Formula(const std::string& text, const NamedReals& constants,
          const std::vector<std::string>& variables);
  double operator()(double x) const;            // a formula in one variable
  double operator()(double a, double b) const;  // in two, in the order of `variables`
  const std::string& text() const;

 private:
  struct Compiled;
  std::shared_ptr<Compiled> compiled_;  // shared by copies: a std::function holds one
};

struct FormulaError : std::runtime_error {
  using std::runtime_error::runtime_error;
  bool constant = false;  // the problem is a constant's name, not the formula
};

}  // namespace granvv::hydro
