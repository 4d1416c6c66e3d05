#include "hydro/formula.hpp"

#include <muParser.h>

#include <algorithm>
#include <mutex>

#include "fields/constants.hpp"

namespace granvv::hydro {
namespace {

// A formula or muparser's message about it as one short line quotes them: at most this many
// characters, then how long the whole is.
constexpr std::size_t kQuotedCharacters = 60;

std::string excerpt(const std::string& text, std::size_t characters = kQuotedCharacters) {
  std::string out = text.substr(0, characters);
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';
  }
  if (text.size() > characters) out += "... (" + std::to_string(text.size()) + " characters)";
  return out;
}

}  // namespace

struct Formula::Compiled {
  std::string text;
  std::vector<double> values;  // the parser reads the variables from here (sized once)
  mu::Parser parser;
  // Copies of a Formula share it, and evaluation writes the variables and the parser's stack:
  // one evaluation at a time (the particle sampler may run in several threads).
  std::mutex evaluating;
};

Formula::Formula(const std::string& text, const NamedReals& constants)
    : Formula(text, constants, {"x"}) {}

Formula::Formula(const std::string& text, const NamedReals& constants,
                 const std::vector<std::string>& variables)
    : compiled_(std::make_shared<Compiled>()) {
  Compiled& c = *compiled_;
  c.text = text;
  if (text.size() > std::size_t(mu::MaxLenExpression)) {
    throw FormulaError("the formula is " + std::to_string(text.size()) +
                       " characters long (allowed: at most " +
                       std::to_string(mu::MaxLenExpression) + ", muparser's limit)");
  }
  c.values.assign(variables.size(), 0.0);
  std::string reserved;
  for (const auto& variable : variables) reserved += variable + ", ";
  for (const auto& [name, value] : constants) {
    if (name == "pi" || std::find(variables.begin(), variables.end(), name) != variables.end()) {
      FormulaError e("constant '" + name + "' is reserved (" + reserved +
                     "pi: the formula's variables and pi are built in)");
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
    for (size_t i = 0; i < variables.size(); ++i) c.parser.DefineVar(variables[i], &c.values[i]);
    c.parser.DefineConst("pi", kPi);
    c.parser.SetExpr(text);
    (void)c.parser.Eval();  // muparser parses on the first evaluation
  } catch (const mu::Parser::exception_type& error) {
    std::string message = excerpt(error.GetMsg(), 2 * kQuotedCharacters);
    if (message.find("position") == std::string::npos && error.GetPos() >= 0) {
      message += " (position " + std::to_string(error.GetPos()) + ")";
    }
    throw FormulaError("syntax error in \"" + excerpt(text) + "\": " + message);
  }
}

double Formula::operator()(double x) const {
  const std::lock_guard<std::mutex> lock(compiled_->evaluating);
  compiled_->values[0] = x;
  return compiled_->parser.Eval();
}

double Formula::operator()(double a, double b) const {
  const std::lock_guard<std::mutex> lock(compiled_->evaluating);
  compiled_->values[0] = a;
  compiled_->values[1] = b;
  return compiled_->parser.Eval();
}

const std::string& Formula::text() const {
  return compiled_->text;
}

}  // namespace granvv::hydro
