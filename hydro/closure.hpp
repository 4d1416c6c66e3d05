#pragma once
// The closure of the 1D granular hydrodynamics (docs/physics.md §9): the constitutive
// relations that close paper Eqs. (1)-(2) (Efrati, Livne & Meerson, PRL 94, 088001 (2005))
// for the fields n, v, T in the paper's scaling,
//   n dv/dt  = d/dx [-p + eta dv/dx],                                  (1b)
//   n dT/dt  = [-p + eta dv/dx] dv/dx - dq/dx - n Lambda,               (2)
// with the thermal energy T per particle of the 2D gas and the heat flux
//   q = -kappa dT/dx - mu dn/dx.
// The second term is the inelastic gas's heat flux down the density gradient (Brey, Dufty, Kim
// & Santos, PRE 58, 4638 (1998); Garzo & Dufty, PRE 59, 5895 (1999)): mu vanishes for elastic
// collisions and is O(1 - r) (docs/physics.md §9); the paper's Eq. (2) has mu = 0. A closure
// supplies p(n, T), its adiabatic response, the sound speed, the viscosities, the conductivity,
// mu and the cooling sink Lambda per unit mass; the operator, the time-step control, the
// cooling step, Haff's law and the linear theory of the homogeneous cooling state take all of
// these from it.
//
// Every per-cell quantity is evaluated for a whole mesh in one call (arrays in, arrays out), so
// choosing a closure at run time costs one virtual call per array, none per cell.
//
// Adding a closure (docs/architecture.md): its .hpp/.cpp implementing Closure, and one entry in
// the registry (hydro/closure_registry.cpp) with its maker and its own case keys, if any.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hydro/cooling_rate.hpp"
#include "hydro/parameter_set.hpp"
#include "hydro/physics.hpp"
#include "hydro/transport_factors.hpp"

namespace granvv::hydro {

// Constitutive coefficients per cell at the cells' densities n and temperatures T.
struct CellCoefficients {
  std::vector<double> pressure;  // p(n, T)
  // Adiabatic modulus B = n (dp/dn) at fixed entropy (per particle: dT = p dn / n^2). For a
  // cell of fixed mass, dp/d(dx) = -B/dx along its compression: this is the implicit
  // pressure response of the operator (hydro/lagrangian_operator.hpp).
  std::vector<double> adiabatic_modulus;
  std::vector<double> viscosity;        // longitudinal eta(n, T): stress eta dv_x/dx
  std::vector<double> shear_viscosity;  // eta_xy(n, T): stress eta_xy dv_y/dx
  std::vector<double> conductivity;     // kappa(n, T): heat flux -kappa dT/dx
  std::vector<double> mu;               // mu(n, T): heat flux -mu dn/dx

  void resize(size_t cells) {
    for (auto* column :
         {&pressure, &adiabatic_modulus, &viscosity, &shear_viscosity, &conductivity, &mu})
      column->resize(cells);
  }
};

// Coefficients of the linearised Eqs. (1)-(2) about the homogeneous cooling state n = 1, v = 0,
// T = T_H(t), in collision-clock units (hydro/linear_stability.hpp, docs/physics.md §2). They
// assume the hard-disk temperature scaling of every closure here: p ~ T, eta, kappa ~ T^{1/2},
// mu ~ T^{3/2}, Lambda ~ T^{3/2} at fixed n, so that the linearised equations have constant
// coefficients in the collision clock. Values at n = 1, T = 1:
struct HcsLinearisation {
  double haff_time = 0.0;             // t0 of Haff's law T_H = (1 + t/t0)^-2 (= 2/Lambda)
  double epsilon = 0.0;               // eps = 1/t0 = Lambda/2: cooling rate of T_H^{1/2}
  double pressure_density = 0.0;      // dp/dn at fixed T
  double pressure_temperature = 0.0;  // dp/dT at fixed n
  double compression_heating = 0.0;   // p: heating -p dv/dx
  double viscosity = 0.0;             // longitudinal eta
  double shear_viscosity = 0.0;       // eta_xy
  double conductivity = 0.0;          // kappa
  double mu = 0.0;                    // mu: heat flux -mu dn/dx
  double cooling_density = 0.0;       // dLambda/dn at fixed T
  double cooling_temperature = 0.0;   // dLambda/dT - Lambda at fixed n (relative to Haff)
  // Real-valued mode numbers k = kx / (2 pi) below which the clustering mode (det A > 0:
  // p_n (kappa kx^2 + Lambda_T') < p_T (Lambda_n + mu kx^2)) and the shear mode
  // (eta_xy kx^2 < eps) grow (hydro/linear_stability.hpp). Each closure computes them from its
  // own formulas; with mu the conduction a pressure-balanced mode sees is kappa - mu p_T/p_n.
  double clustering_cutoff_mode = 0.0;
  double shear_cutoff_mode = 0.0;
};

// What the validity monitors of a run read from its closure (hydro/validity_monitors.hpp,
// docs/physics.md §9): the collision rate and mean free path of the gas the closure describes,
// and the local area fraction up to which it describes it.
struct ValidityScales {
  double K = 0.0;
  double area_fraction = 0.0;  // phi0 (0: not known, the area-fraction monitor does not apply)
  bool contact_value = false;  // collisions enhanced by chi(phi0 n) (a dense-gas closure)
  double area_fraction_limit = 0.0;  // the area-fraction monitor's threshold
};

class Closure {
 public:
  virtual ~Closure() = default;
  virtual std::string name() const = 0;

  // All per-cell coefficients for densities n and temperatures T (same size; outputs resized).
  virtual void cell_coefficients(const std::vector<double>& n, const std::vector<double>& T,
                                 CellCoefficients& out) const = 0;
  // Adiabatic sound speed c(n, T), c^2 = B/n.
  virtual void sound_speed(const std::vector<double>& n, const std::vector<double>& T,
                           std::vector<double>& c) const = 0;
  // Cooling sink per unit mass Lambda(n, T): dT/dt = -Lambda at fixed density.
  virtual void cooling_rate(const std::vector<double>& n, const std::vector<double>& T,
                            std::vector<double>& rate) const = 0;
  // Temperatures after cooling exactly for dt at fixed densities n (operator splitting).
  virtual void cool(const std::vector<double>& n, const std::vector<double>& T, double dt,
                    std::vector<double>& cooled) const = 0;

  virtual HcsLinearisation hcs_linearisation() const = 0;
  virtual ValidityScales validity_scales() const = 0;

  // Why the closure no longer describes cells of densities n (empty while it does): the driver
  // stops a run there (hydro/driver.hpp, RunStatus::closure_limit). The dilute gas has no limit.
  virtual std::string validity_problem(const std::vector<double>& n) const {
    (void)n;
    return {};
  }
};

// What a closure is built from: the paper's K and q, closure-specific named parameters (the
// Enskog closure's "area_fraction"), and the inelastic loss of the cooling term, which every
// closure applies; and injected model errors (identity: none), which every closure takes.
struct ClosureParameters {
  Physics physics;
  std::map<std::string, double> extra;
  CoolingRate cooling = CoolingRate::small_q;
  TransportFactors factors{};
};

// A closure parameter outside what the closure can use: its name in `extra` and why.
struct ClosureParameterProblem {
  std::string parameter;  // "area_fraction"
  std::string reason;     // "the enskog closure needs an area fraction in (0, 0.69)"
};

// A key a closure declares as its own (hydro/closure_registry.cpp): the case key
// hydro.<spec.name>, which reaches the closure as ClosureParameters::extra[spec.name] (a real;
// an integer or a switch as one, true = 1). The case schema derives these keys, and a case
// that runs only other closures may not set them. Keys every closure reads (physics.K, q,
// cooling, area_fraction, the hydro.*_factor errors) are the schema's own.
struct ClosureKey {
  ParameterSpec spec;
  std::string closure;  // the hydro.closure it belongs to
  std::string key() const { return "hydro." + spec.name; }
};
// Every closure's own keys, closure by closure in the order of closure_names(). Two closures
// may not declare the same key (std::logic_error).
const std::vector<ClosureKey>& closure_keys();

// The registered closures by name ("dilute": paper Eqs. (1)-(2)), wrapped in a ScaledClosure
// when params.factors is not the identity (hydro/scaled_closure.hpp). Throws
// std::invalid_argument for an unknown name, listing the known ones.
std::unique_ptr<Closure> make_closure(const std::string& name, const ClosureParameters& params);
std::vector<std::string> closure_names();
// Whether closure `name` has the inelastic heat flux -mu dn/dx (mu != 0 for r < 1); throws like
// make_closure for an unknown name.
bool closure_has_density_heat_flux(const std::string& name);
// The first parameter of `params` that closure `name` cannot use (none: nullopt). Throws like
// make_closure for an unknown name.
std::optional<ClosureParameterProblem> closure_parameter_problem(const std::string& name,
                                                                 const ClosureParameters& params);

}  // namespace granvv::hydro
