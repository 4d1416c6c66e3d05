#pragma once
// Coarse-graining of 2D particles into 1D fields along x, averaged over y: geometry (a
// periodic grid of equal cells) x kernel (top-hat bins, Gaussian, Lucy) x fields (n, v_x, v_y,
// T), after MercuryCG (Weinhart, Thornton, Luding & Bokhove, Granular Matter 14, 289 (2012);
// Tunuguntla, Thornton & Weinhart, Comp. Part. Mech. 3, 343 (2016)).
//
// Two stages, so that it runs in place under MPI (docs/physics.md §7): every rank sums raw kernel
// moments of its own particles into a Moments (accumulate), the ranks add them
// (md_bridge/moment_reduction.hpp: allreduce), and fields() turns the summed moments into
// n, v, T with their standard errors. Only sums cross ranks, never particles.
//
// Units are those of the particles (MD: sigma = m = T0 = 1); masses may differ per particle.
// Conventions (2D, docs/physics.md §4 and §6):
//   n(x)  number density, particles per unit area;
//   v(x)  mass-weighted mean velocity, both components;
//   T(x)  granular temperature = thermal energy per particle, (1/2) m <|c - v(x)|^2>, with the
//         full local mean (v_x and v_y) removed, so that transverse (shear) flow is not counted
//         as heat; each velocity component then has variance T/m (equipartition).
#include <string>
#include <vector>

#include "fields/field_series.hpp"

namespace granvv::md {

// Geometry and kernel. Fields live at the bin centres x_lo + (i + 1/2) Lx/bins.
//   kernel "bin":      top-hat over the cell (plain binning); width is ignored.
//   kernel "gaussian": exp(-r^2 / 2 width^2), truncated at |r| = 3 width.
//   kernel "lucy":     Lucy's quartic (1 + 3 s)(1 - s)^3, s = |r|/width, support |r| < width
//                      (Lucy, Astron. J. 82, 1013 (1977), in its 1D normalisation 5/(4 width)).
// Smooth kernels wrap periodically (every image within the support counts) and need a support
// radius (3 width for the Gaussian, width for Lucy) above half a bin, so that every particle
// reaches at least one bin centre.
struct CoarseGrainGrid {
  double x_lo = 0.0, Lx = 1.0;  // periodic in x: [x_lo, x_lo + Lx)
  double y_lo = 0.0, Ly = 1.0;  // only Ly enters (the area of a bin is Ly Lx/bins)
  int bins = 1;
  std::string kernel = "bin";
  double width = 0.0;  // Gaussian standard deviation or Lucy radius, in units of x

  double bin_width() const { return Lx / bins; }
};

// Raw per-bin kernel sums over particles p. Each particle's weights w_p over the bins add up
// to exactly 1 (discrete normalisation), so per-bin sums also add up to whole-box sums:
//   weight       = sum w             (the particle count of the bin; N_b for plain bins)
//   weight2      = sum w^2           (N_eff = weight^2 / weight2)
//   mass         = sum w m
//   mass_weight2 = sum w^2 m         (sampling variance of the mean velocity)
//   px, py       = sum w m c_x, sum w m c_y
//   mv2          = sum w m |c|^2     (twice the kinetic energy)
//   mvx2, mvy2   = sum w m c_x^2, sum w m c_y^2 (the kinetic pressure tensor's diagonal)
//   virial_xx, virial_yy   = sum w W_xx, sum w W_yy (the particles' contact virial shares,
//                            md_bridge/particle_engine.hpp LocalVirial)
//   virial_xx2, virial_yy2 = sum w^2 W_xx^2, sum w^2 W_yy^2 (their sampling variance)
//   mv2vx        = sum w m |c|^2 c_x (twice the kinetic energy flux along x, box frame)
//   energy2, flux2 = sum w^2 (m |c|^2 / 2)^2, sum w^2 (m |c|^2 c_x / 2)^2 (their sampling variance)
//   contact_flux, contact_flux2 = sum w J_x, sum w^2 J_x^2: the particles' contact energy flux
//                 shares (ParticleEngine LocalVirial::energy_flux_x) and their sampling variance
// `particles` counts the particles accumulated (exact below 2^53), `virial_particles` those
// accumulated with a contact virial, `contact_flux_particles` those with a contact energy flux.
// Moments of disjoint particle sets add: that is the MPI reduction and the merging of chunks.
struct Moments {
  std::vector<double> weight, weight2, mass, mass_weight2, px, py, mv2;
  std::vector<double> mvx2, mvy2, virial_xx, virial_yy, virial_xx2, virial_yy2, mv2vx;
  std::vector<double> energy2, flux2, contact_flux, contact_flux2;
  double particles = 0.0, virial_particles = 0.0, contact_flux_particles = 0.0;
  // Whether every particle came with its contact virial (the pressure is then defined).
  bool has_virial() const { return particles > 0.0 && virial_particles == particles; }
  // Whether every particle came with its contact energy flux.
  bool has_contact_flux() const { return particles > 0.0 && contact_flux_particles == particles; }

  Moments() = default;
  explicit Moments(int bins);
  int bins() const { return static_cast<int>(weight.size()); }
  // Adds moments of another particle set on the same grid; throws std::invalid_argument if
  // the bin counts differ.
  Moments& operator+=(const Moments& other);
  // The per-bin arrays in a fixed order (packing for the reduction).
  std::vector<std::vector<double>*> arrays();
  std::vector<const std::vector<double>*> arrays() const;
};

// One snapshot of the fields is a fields::FieldSnapshot at the bin centres (t and label left
// to the caller), with count = sum of weights (the particles of the bin, kernel-weighted).
// Quantities that a bin cannot define are quiet NaN: v where the bin holds no weight, T and
// every standard error where fewer than two particles contribute (N_eff = (sum w)^2 / sum w^2
// <= 1). Standard errors are those of one snapshot, from the local T and N_eff, assuming
// independent particles with Maxwellian (Gaussian) velocity fluctuations about v(x):
//   v_x_stderr = v_y_stderr = sqrt(T sum w^2 m) / sum w m    (= sqrt(T / (m N_b)) for bins),
//   T_stderr   = T / sqrt(N_eff - 1)                          (exact for bins: 2(N_b - 1)
//                                                              degrees of freedom, chi^2).
// n has none (n_stderr is empty): its snapshot variance is set by the static structure factor
// of the gas, not by the sample itself (Poisson only for an ideal gas); an ensemble over seeds
// measures it.
// Pressure tensor (docs/physics.md §11), kinetic with the bin's mean flow removed plus contact:
//   P_aa = n T_a + sum w W_aa / A_bin,   T_a = (sum u c_a^2 - p_a^2 / U) / D,
// with the same unbiased denominator D as T, so (P_xx + P_yy)/2 = n T exactly when no contact
// acts. Its single-snapshot error adds in quadrature the chi^2 error of the kinetic part,
// n T_a sqrt(2 / (N_eff - 1)), and the sampling error of the virial sum, sqrt(2 sum w^2 W_aa^2)
// / A_bin (independent contacts, each shared in two equal halves). P_xx, P_yy are NaN where T is,
// and everywhere when the moments carry no contact virial (Moments::has_virial).
// Kinetic energy and its flux along x in the box frame: kinetic_energy = (1/2) sum w m |c|^2 /
// A_bin and energy_flux_x = (1/2) sum w m |c|^2 c_x / A_bin, plain sums without the bin's mean
// flow removed. Each has the single-snapshot error of a sum over independent particles,
// sqrt(sum w^2 X^2 - sum w^2 (sum w X / sum w)^2) / A_bin, X the particle's share. The heat
// flux relative to a flow is formed from them at the level of a mode (compare/
// heat_flux_fit.hpp): removing each bin's own sample mean would bias a third moment by about
// -3/N for N particles per bin. The contact (collisional) transfer of energy is not in them:
// contact_energy_flux_x = sum w J_x / A_bin is, with the error sqrt(2 sum w^2 J_x^2) / A_bin of
// independent contacts each shared in two equal halves (as the virial's), NaN when the moments carry none (Moments::has_contact_flux).

// Whole-box energies and momentum from the summed moments.
//   kinetic_total = sum_p m |c|^2 / 2, momentum = sum_p m c: exact for every kernel, because
//   every particle's weights add up to one.
//   kinetic_macro_x/y = sum_bins (1/2) M_b v_b^2 per component, with M_b the bin's mass
//   (the integral of (1/2) m n v^2 dx Ly); the y part is the transverse (shear) flow,
//   docs/physics.md §6. thermal_biased = sum_bins (1/2) sum_p w m |c - v_b|^2 = sum_bins T_b^biased
//   count_b. Identity (exact algebra for every kernel, round-off in practice):
//     thermal_biased + kinetic_macro_x + kinetic_macro_y = kinetic_total.
//   thermal = sum_bins T_b count_b with the unbiased T. It exceeds thermal_biased by exactly
//   macro_noise_x + macro_noise_y, where macro_noise = sum_bins (1/2) T_b sum w^2 m / sum w m
//   is the expected energy that the sampling noise of each bin's mean velocity puts into the
//   macroscopic kinetic energy (T_b/2 per bin and component for plain bins). Hence also
//     thermal + (kinetic_macro_x - macro_noise_x) + (kinetic_macro_y - macro_noise_y)
//       = kinetic_total
//   to round-off, bins with N_eff <= 1 excluded from thermal and macro_noise (their
//   fluctuation energy is zero). The noise floor matters when the signal is small (§8).
struct BoxEnergies {
  double particles = 0.0, mass = 0.0;
  double momentum_x = 0.0, momentum_y = 0.0;
  double kinetic_total = 0.0;
  double kinetic_macro_x = 0.0, kinetic_macro_y = 0.0;
  double thermal_biased = 0.0;
  double thermal = 0.0;
  double macro_noise_x = 0.0, macro_noise_y = 0.0;
};

// Whole-box pressure from the summed moments: the bins' P_aa (kinetic part from bins with
// N_eff > 1 only, as BoxEnergies::thermal) averaged over the equal-area bins, and the
// single-snapshot standard error of (P_xx + P_yy)/2 from the bins' errors (independent bins).
// thermal = sum_bins T_b count_b, so the box's P/(n T) = (P_xx + P_yy)/2 A / thermal. NaN
// without a contact virial.
struct BoxPressure {
  double xx = 0.0, yy = 0.0;
  double mean_stderr = 0.0;  // of (xx + yy)/2
  double thermal = 0.0;      // BoxEnergies::thermal
  double area = 0.0;         // Lx Ly
  double mean() const { return 0.5 * (xx + yy); }
  // P / (n T): 1 for an ideal gas.
  double compressibility() const { return mean() * area / thermal; }
};

class CoarseGrainer {
 public:
  // Throws std::invalid_argument (one line naming the value) on bins < 1, non-positive or
  // non-finite Lx or Ly, an unknown kernel, or a smooth kernel whose width is not positive or
  // whose support does not reach half a bin.
  explicit CoarseGrainer(CoarseGrainGrid grid);

  const CoarseGrainGrid& grid() const { return grid_; }
  std::vector<double> bin_centres() const;

  // Adds the moments of n particles to `m` (which must have grid().bins bins). LAMMPS layout:
  // particle i has position x[stride i + 0..1] and velocity v[stride i + 0..1]; mass[i] is
  // its mass (LAMMPS rmass), or mass == nullptr for unit mass. Positions outside the box (atoms
  // between neighbour-list rebuilds, docs/physics.md §10) are wrapped periodically; y is not read.
  // Throws std::invalid_argument on n < 0, stride < 2, a wrong-sized m, a non-finite position.
  // virial_xx, virial_yy (both or neither): each particle's contact virial share, which adds
  // the virial moments and counts the particles in Moments::virial_particles; contact_flux_x:
  // each particle's contact energy flux share, counted in Moments::contact_flux_particles.
  void accumulate(Moments& m, const double* x, const double* v, const double* mass, int n,
                  int stride = 3, const double* virial_xx = nullptr,
                  const double* virial_yy = nullptr, const double* contact_flux_x = nullptr) const;
  Moments accumulate(const double* x, const double* v, const double* mass, int n,
                     int stride = 3) const;

  // Fields from summed moments. The temperature removes the local mass-weighted mean and is
  // unbiased for independent particles with equipartition (each component of c_p has
  // variance T/m_p about v): with u = w m,
  //   E[sum u |c - v_b|^2] = 2 T (sum w - sum w^2 m / sum w m),
  // so T_b = sum u |c - v_b|^2 / (2 (sum w - sum w^2 m / sum w m)). For equal masses the
  // denominator is 2 W (1 - 1/N_eff), N_eff = W^2 / sum w^2; for plain bins it is 2 (N_b - 1),
  // the Bessel correction, where the naive 1/(2 N_b) is low by the factor (N_b - 1)/N_b.
  // The fluctuation sum is formed as mv2 - |p|^2 / mass: its relative round-off is about
  // eps (1 + m |v|^2 / 2T), harmless unless the flow is 10^6 times the thermal speed.
  fields::FieldSnapshot fields(const Moments& m) const;
  BoxEnergies energies(const Moments& m) const;
  BoxPressure pressure(const Moments& m) const;

 private:
  enum class Kernel { bin, gaussian, lucy };
  CoarseGrainGrid grid_;
  Kernel kernel_ = Kernel::bin;
  double dx_ = 1.0;
  double support_ = 0.0;  // kernel support radius (0 for bins)
};

}  // namespace granvv::md
