#pragma once
// Known model errors injected into a closure (docs/physics.md §9, "Injected model errors"): the
// viscosities, the conductivity, the inelastic heat-flux coefficient mu and the cooling sink
// each multiplied by a factor 1 + eps. The atlas's comparison power (docs/atlas.md) asks how
// small an eps the side-by-side comparison with the particles can catch; the case keys are
// hydro.viscosity_factor, hydro.conductivity_factor, hydro.mu_factor and hydro.cooling_factor.
namespace granvv::hydro {

struct TransportFactors {
  double viscosity = 1.0;     // longitudinal and shear viscosity
  double conductivity = 1.0;  // heat conductivity
  double cooling = 1.0;       // cooling sink Lambda (and so 1/t0 of Haff's law)
  double mu = 1.0;            // heat flux -mu dn/dx down the density gradient

  bool is_identity() const {
    return viscosity == 1.0 && conductivity == 1.0 && cooling == 1.0 && mu == 1.0;
  }
};

}  // namespace granvv::hydro
