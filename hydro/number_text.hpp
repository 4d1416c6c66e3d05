#pragma once
// Numbers in the hydro's messages: six significant digits, as a reader compares them.
#include <cstdio>
#include <string>

namespace granvv::hydro {

inline std::string number_text(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

}  // namespace granvv::hydro
