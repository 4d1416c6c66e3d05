#pragma once
// Mathematical constants, defined once for every library and test (fields/ depends on nothing,
// so each library may include it).

namespace granvv {

// pi, and 2 pi (exact: doubling is exact in binary floating point).
inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;

}  // namespace granvv
