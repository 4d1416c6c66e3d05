#pragma once
// Parameters of the scaled dilute granular hydrodynamics of Efrati, Livne & Meerson,
// PRL 94, 088001 (2005), Eqs. (1)-(2): x in units of Lx, n of n0, T of T0,
// v of sqrt(T0/m), t of Lx/sqrt(T0/m).

namespace granvv::hydro {

// The case gives both (physics.K, physics.q); no defaults here.
struct Physics {
  double K = 0.0;  // Knudsen number K = (2/sqrt(pi)) (sigma Lx n0)^-1
  double q = 0.0;  // inelasticity q = (1 - r)/2
};

}  // namespace granvv::hydro
