#pragma once
// Flow by inertia: the pressureless limit of Eqs. (1) of Efrati, Livne & Meerson,
// PRL 94, 088001 (2005), reached when the stress P "freezes up" late in the clustering
// instability:
//   v_t + v v_x = 0  (Eq. 4),   n_t + (n v)_x = 0  (Eq. 1a),
// on the periodic interval [-1/2, 1/2). Every fluid element keeps its velocity, so with the
// Lagrangian label xi (the position at t = 0) the exact solution is (Eq. 5, Whitham)
//   x = xi + v0(xi) t,   v(x, t) = v0(xi),   n(x, t) = n0(xi) / (1 + t v0'(xi)),
// and the velocity gradient is v_x = v0'(xi) / (1 + t v0'(xi)) (Eq. 6). The map xi -> x is
// monotone until the first zero of 1 + t v0'(xi), at the singularity time
// tau = 1 / max_xi(-v0'(xi)), when density and velocity gradient diverge at the Lagrangian point
// xi* where v0' is most negative.

#include <functional>

namespace granvv::hydro {

// Near the singular point the density grows as n0(xi*) (1 - t/tau)^{-1} (paper, text before
// Fig. 4): 1 + t v0'(xi*) = 1 - t/tau exactly.
double density_at_singular_point(double n0_at_singular_point, double t, double tau);

// Exponent of the intermediate-asymptotic density profile n ~ |x - x*|^{-2/3} close to the
// singularity (paper, text before Fig. 4, citing Zeldovich): for v0 = -xi/tau + C xi^3 + O(xi^5)
// the similarity variable is w = x / t'^{3/2}, t' = tau - t; for w >> 1 (but x << 1) the profile
// is x ~ C tau xi^3, n ~ 1/(3 C tau xi^2) ~ x^{-2/3}.
inline constexpr double kIntermediateDensityExponent = -2.0 / 3.0;

class FlowByInertia {
 public:
  using Profile = std::function<double(double)>;

  // v0, its derivative dv0 and n0 must be 1-periodic. The singularity time is found by sampling
  // dv0 at `samples` equispaced points of [-1/2, 1/2) and refining the lowest sampled local
  // minima by golden-section search: tau then has a relative error of a few 1e-16, provided
  // dv0 has no dip narrower than a few sample spacings (which the sampling would miss).
  // Throws std::invalid_argument for empty profiles or samples < 8.
  FlowByInertia(Profile v0, Profile dv0, Profile n0, int samples = 4096);

  // v0 = a sin(2 pi mode xi), n0 = 1: the paper's single-mode scene (Eq. 7), with the exact
  // tau = 1/(2 pi |a| mode) and xi* = 0 (a < 0) or -1/(2 mode) (a > 0). mode >= 1.
  static FlowByInertia single_mode(double a, int mode = 1);

  // tau = 1/max(-v0'); +inf if v0' >= 0 everywhere (for periodic v0: v0 constant).
  double singularity_time() const { return tau_; }
  // xi* in [-1/2, 1/2), where v0' is minimal (one of them if several are equal);
  // NaN if tau = +inf.
  double singular_label() const { return singular_label_; }
  // Eulerian position x* = xi* + v0(xi*) tau of the singularity (not reduced mod 1).
  double singular_position() const;
  // n0(xi*) / (1 - t/tau): the density at the singular fluid element.
  double singular_density(double t) const;

  // The label xi with x = xi + v0(xi) t exactly (xi is not reduced mod 1; xi(x + 1) = xi(x) + 1),
  // by Newton's method safeguarded by bisection on a bracket that contains the unique root.
  // Requires 0 <= t < tau (std::domain_error otherwise): beyond tau the map is multivalued.
  double lagrangian_label(double x, double t) const;
  double velocity(double x, double t) const;           // Eq. (5a)
  double density(double x, double t) const;            // Eq. (5b)
  double velocity_gradient(double x, double t) const;  // Eq. (6)

  const Profile& initial_velocity() const { return v0_; }
  const Profile& initial_velocity_derivative() const { return dv0_; }
  const Profile& initial_density() const { return n0_; }

 private:
  struct Exact {};
  FlowByInertia(Exact, Profile v0, Profile dv0, Profile n0, double tau, double singular_label,
                double v_min, double v_max);

  Profile v0_;
  Profile dv0_;
  Profile n0_;
  double tau_ = 0.0;
  double singular_label_ = 0.0;
  double v_min_ = 0.0;  // sampled range of v0, to bracket the Lagrangian label
  double v_max_ = 0.0;
};

}  // namespace granvv::hydro
