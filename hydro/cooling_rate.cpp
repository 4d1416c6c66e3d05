#include "hydro/cooling_rate.hpp"

#include <stdexcept>

namespace granvv::hydro {

std::vector<std::string> cooling_rate_names() {
  return {to_string(CoolingRate::small_q), to_string(CoolingRate::exact)};
}

CoolingRate cooling_rate_from_name(const std::string& name) {
  for (const CoolingRate c : {CoolingRate::small_q, CoolingRate::exact}) {
    if (to_string(c) == name) return c;
  }
  throw std::invalid_argument("unknown cooling rate '" + name + "'; known: small_q, exact");
}

std::string to_string(CoolingRate cooling) {
  return cooling == CoolingRate::exact ? "exact" : "small_q";
}

double inelastic_loss_factor(CoolingRate cooling, double q) {
  return cooling == CoolingRate::exact ? 1.0 - q : 1.0;
}

}  // namespace granvv::hydro
