#include "hydro/formula.hpp"

#include <muParser.h>

#include "fields/constants.hpp"

namespace granvv::hydro {

struct Formula::Compiled {
  std::string text;
  double x = 0.0;  // the parser reads x from here
  mu::Parser parser;
};

Formula::Formula(const std::string& text, const NamedReals& constants)
    : compiled_(std::make_shared<Compiled>()) {
  Compiled& c = *compiled_;
  c.text = text;
  for (const auto& [name, value] : constants) {
    if (name == "x" || name == "pi") {
      FormulaError e("constant '" + name + "' is reserved (x is the position, pi is built in)");
      e.constant = true;
      throw e;
    }
    try {
      c.parser.DefineConst(name, value);
    } catch (const mu::Parser::exception_type&) {
      FormulaError e("constant name '" + name +
                     "' is not allowed (a letter or _, then letters, digits or _)");
      e.constant = true;
      throw e;
    }
  }
  try {
    c.parser.DefineVar("x", &c.x);
    c.parser.DefineConst("pi", kPi);
    c.parser.SetExpr(text);
    (void)c.parser.Eval();  // muparser parses on the first evaluation
  } catch (const mu::Parser::exception_type& error) {
    std::string message = error.GetMsg();
    if (message.find("position") == std::string::npos && error.GetPos() >= 0) {
      message += " (position " + std::to_string(error.GetPos()) + ")";
    }
    throw FormulaError("syntax error in \"" + text + "\": " + message);
  }
}

double Formula::operator()(double x) const {
  compiled_->x = x;
  return compiled_->parser.Eval();
}

const std::string& Formula::text() const {
  return compiled_->text;
}

}  // namespace granvv::hydro
