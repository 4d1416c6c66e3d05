#pragma once
// A user's formula in x, evaluated by muparser (Debian libmuparser-dev): the fields of
// initial.type = "expression" (hydro/initial_expression.cpp). Besides x the formula may use pi
// and named constants; muparser's functions (sin, exp, sqrt, abs, min, max, ...), ^ and ?: are
// available.
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "hydro/parameter_set.hpp"

namespace granvv::hydro {

class Formula {
 public:
  // Throws FormulaError for a syntax error, an unknown name, or a constant whose name
  // muparser cannot take (or that is x or pi).
  Formula(const std::string& text, const NamedReals& constants);
  double operator()(double x) const;
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
