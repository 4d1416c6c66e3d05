#pragma once
// Linear stability of the homogeneous cooling state (HCS) of Efrati, Livne & Meerson,
// PRL 94, 088001 (2005), Eqs. (1)-(2), on the periodic unit interval.
//
// Perturb the HCS n = 1, v = 0, T = T_H(t) = (1 + t/t0)^{-2} as
//   n = 1 + nu,  v = u,  T = T_H (1 + theta),  each ~ exp(i kx x),  kx = 2 pi k,
// and measure velocity in units of the thermal speed, w = u / T_H^{1/2}, and time by the
// collision clock ds = T_H^{1/2} dt (see collision_clock in haff.hpp). With the closure's
// HCS coefficients (HcsLinearisation in hydro/closure.hpp: eps = 1/t0, p_n = dp/dn,
// p_T = dp/dT, p, eta, kappa, mu, Lambda_n = dLambda/dn, Lambda_T' = dLambda/dT - Lambda, all
// at n = T = 1) the linearised Eqs. (1)-(2) have constant coefficients:
//   nu_s    = -i kx w                                                (continuity, Eq. 1a)
//   w_s     = -i kx p_n nu + (eps - eta kx^2) w - i kx p_T theta     (momentum, Eq. 1b)
//   theta_s = -(Lambda_n + mu kx^2) nu - i kx p w - (kappa kx^2 + Lambda_T') theta  (Eq. 2)
// where -mu kx^2 nu is the divergence of the heat flux -mu dn/dx (hydro/closure.hpp): heat
// flows down the density gradient, out of a dense spot (mu > 0 for r < 1).
// For the dilute closure (p_n = p_T = p = 1, eta = K/4, kappa = K, eps = 4q/K, Lambda_n = 2 eps,
// Lambda_T' = eps):
//   w_s     = -i kx nu + (eps - K kx^2/4) w - i kx theta
//   theta_s = -2 eps nu - i kx w - (K kx^2 + eps) theta
// The "+eps w" is not a force: it is the rescaling by the shrinking thermal speed, so a
// frozen velocity u = const has w ~ exp(eps s). In the energy equation -2 eps nu - eps theta is
// the linearised loss -(8q/K)(n^2 T^{3/2} - T_H^{3/2}) relative to Haff cooling, -i kx w the
// compressional heating -n T v_x and -K kx^2 theta the heat conduction.
//
// Any closure: det A = -kx^2 [p_n (kappa kx^2 + Lambda_T') - p_T (Lambda_n + mu kx^2)], so a real
// rate crosses zero at kx^2 = (p_T Lambda_n - p_n Lambda_T') / (p_n kappa - p_T mu)
// (HcsLinearisation's cutoff modes): the clustering mode, at pressure balance, is damped by the
// conduction kappa - mu p_T/p_n, not kappa.
// Dilute closure: det A = -kx^2 (K kx^2 - eps): a real rate crosses zero at K kx = 2 sqrt(q), i.e.
// mode k is unstable iff pi k K < sqrt(q) (paper, text after Eq. 2). That this is also the exact
// stability boundary (no complex pair crosses the imaginary axis) follows from Routh-Hurwitz:
// for K kx^2 > eps the Hurwitz condition a2 a1 > a0 holds for every kx iff q <= 1/3. For
// q > 1/3 (restitution r < 1/3, far outside the model's q << 1) a band of wave numbers just
// above the cutoff is oscillatory-unstable; the mode counts below use the paper's criterion.
//
// Dilute long waves (kx << eps, K kx^2 << eps): rates eps - kx^2 (K/4 + 1/(2 eps)) (velocity mode:
// matter moves by inertia, u ~ const), -kx^2/eps (density mode with theta = -2 nu, frozen at
// leading order) and -eps + kx^2 (3/(2 eps) - K) (temperature mode). Short waves
// (eps << kx << 1/K): sound +-i sqrt(2) kx - eps/4 - 3 K kx^2/8 (2D adiabatic index 2) and the
// clustering mode (eps - K kx^2)/2 with eigenvector nu = -theta.
//
// The transverse (shear) velocity v_y(x) of the 2D gas obeys n dv_y/dt = d/dx(eta_xy dv_y/dx),
// so w_y,s = (eps - eta_xy kx^2) w_y. For the dilute gas eta_xy = eta = (K/4) T^{1/2} (traceless
// viscous stress, no bulk viscosity): unstable iff pi k K < 2 sqrt(q).
//
// Each function takes the closure; the overloads taking Physics use the paper's dilute closure
// (DiluteClosure). The mode counts are the dilute gas's exact criterion in K and q.

#include <Eigen/Dense>
#include <array>
#include <complex>

#include "hydro/closure.hpp"
#include "hydro/physics.hpp"

namespace granvv::hydro {

// eps = 1/t0 (dilute: 4q/K): the HCS cooling rate of the thermal speed in collision-clock units.
double hcs_epsilon(const Closure& closure);
double hcs_epsilon(const Physics& physics);

// Scaled wave number kx = 2 pi k of mode k on the periodic unit interval.
double mode_wavenumber(int k);

// Matrix A of d/ds (nu, w, theta) = A (nu, w, theta) for the Fourier mode k (header comment).
// The Physics overloads throw std::invalid_argument unless K > 0 and q >= 0 are finite.
Eigen::Matrix3cd hcs_linear_operator(const Closure& closure, int k);
Eigen::Matrix3cd hcs_linear_operator(const Physics& physics, int k);
// The same for a real wave number kx (used to probe the boundary between quantised modes).
Eigen::Matrix3cd hcs_linear_operator_kx(const Closure& closure, double kx);
Eigen::Matrix3cd hcs_linear_operator_kx(const Physics& physics, double kx);

struct HcsMode {
  std::complex<double> rate;  // lambda: amplitude ~ exp(lambda s) = (1 + t/t0)^{lambda t0}
  // (nu, w, theta), divided by its largest-modulus component, which therefore is exactly 1;
  // among components equal in modulus to 1e-12 relative the first one is chosen.
  Eigen::Vector3cd eigenvector;
};

// Eigenmodes of A, sorted by real part, largest first (ties: larger imaginary part first).
std::array<HcsMode, 3> hcs_modes(const Closure& closure, int k);
std::array<HcsMode, 3> hcs_modes(const Physics& physics, int k);
std::array<HcsMode, 3> hcs_modes_kx(const Closure& closure, double kx);
std::array<HcsMode, 3> hcs_modes_kx(const Physics& physics, double kx);

// Growth rate eps - eta_xy kx^2 (dilute: eps - K kx^2/4; collision-clock units) of the
// transverse velocity mode k.
double shear_rate(const Closure& closure, int k);
double shear_rate(const Physics& physics, int k);

// Real-valued mode cutoffs sqrt(q)/(pi K) and 2 sqrt(q)/(pi K): the dilute closure's (below).
double clustering_cutoff_mode(const Physics& physics);
double shear_cutoff_mode(const Physics& physics);
// The same for any closure (HcsLinearisation::clustering_cutoff_mode, shear_cutoff_mode): the
// real mode number where det A = 0, i.e. p_n (kappa kx^2 + Lambda_T') = p_T Lambda_n, and
// where eta_xy kx^2 = eps. The dilute closure gives the two above.
double clustering_cutoff_mode(const Closure& closure);
double shear_cutoff_mode(const Closure& closure);

// Whether mode k (k and -k are the same mode; k = 0 is never unstable) satisfies pi |k| K <
// sqrt(q), respectively pi |k| K < 2 sqrt(q). The inequality is decided for the given doubles
// K, q in double-double arithmetic (pi to ~1e-32, relative error of the comparison < 1e-30),
// so a mode placed on the boundary by rounding K or q lands on the side that exact arithmetic
// gives. Exact equality is impossible for double K, q (pi^2 is irrational); a tie within 1e-29
// relative is treated as marginal (rate zero) and not counted as unstable.
bool clustering_mode_unstable(const Physics& physics, int k);
bool shear_mode_unstable(const Physics& physics, int k);

// Number of modes k >= 1 with pi k K < sqrt(q) (79 for K = 4e-4, q = 0.01, as in the paper),
// respectively pi k K < 2 sqrt(q). Throws std::overflow_error if the count exceeds INT_MAX.
int clustering_unstable_modes(const Physics& physics);
int shear_unstable_modes(const Physics& physics);
// The number of modes k >= 1 below the closure's cutoff mode (k < cutoff in double arithmetic:
// for the dilute closure it can differ from the double-double count above only when the cutoff
// is within a rounding error of an integer). Throws std::overflow_error past INT_MAX.
int clustering_unstable_modes(const Closure& closure);
int shear_unstable_modes(const Closure& closure);

// exp(A s) initial: the linear evolution of mode k over a collision-clock interval s
// (s = collision_clock(t, t0) from t = 0). Padé scaling-and-squaring matrix exponential, which
// stays accurate where A is not diagonalisable (merging of the density mode and sound pair).
Eigen::Vector3cd hcs_linear_evolution(const Closure& closure, int k,
                                      const Eigen::Vector3cd& initial, double s);
Eigen::Vector3cd hcs_linear_evolution(const Physics& physics, int k,
                                      const Eigen::Vector3cd& initial, double s);

}  // namespace granvv::hydro
