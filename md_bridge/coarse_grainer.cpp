#include "md_bridge/coarse_grainer.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "fields/constants.hpp"

namespace granvv::md {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The Gaussian is cut at three standard deviations (it keeps 99.73 % of the weight; the
// discrete normalisation below restores the rest).
constexpr double kGaussianCut = 3.0;

std::string describe(double value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

// Below this N_eff - 1 (relative to the round-off of the sums) a bin has a single particle
// and no fluctuation to measure.
bool has_fluctuations(double weight, double denominator) {
  return denominator > 64.0 * std::numeric_limits<double>::epsilon() * weight;
}

// One bin's pressure tensor diagonal (header: "Pressure tensor"), NaN where undefined.
struct BinPressure {
  double xx = kNaN, yy = kNaN, xx_stderr = kNaN, yy_stderr = kNaN;
};

BinPressure bin_pressure(const Moments& m, int i, double area) {
  BinPressure b;
  const double W = m.weight[i];
  const double U = m.mass[i];
  if (!m.has_virial() || !(W > 0.0 && U > 0.0)) return b;
  const double D = W - m.mass_weight2[i] / U;
  if (!has_fluctuations(W, D)) return b;
  const double n = W / area;
  const double n_eff = W * W / m.weight2[i];
  const double T_x = std::max(m.mvx2[i] - m.px[i] * m.px[i] / U, 0.0) / D;
  const double T_y = std::max(m.mvy2[i] - m.py[i] * m.py[i] / U, 0.0) / D;
  b.xx = n * T_x + m.virial_xx[i] / area;
  b.yy = n * T_y + m.virial_yy[i] / area;
  const double chi2 = n_eff > 1.0 ? 2.0 / (n_eff - 1.0) : kNaN;
  // Each contact's two equal halves go together: the variance of its sum is twice the sum of
  // the halves' squares.
  b.xx_stderr = std::sqrt(n * T_x * n * T_x * chi2 + 2.0 * m.virial_xx2[i] / (area * area));
  b.yy_stderr = std::sqrt(n * T_y * n * T_y * chi2 + 2.0 * m.virial_yy2[i] / (area * area));
  return b;
}

}  // namespace

Moments::Moments(int bins)
    : weight(bins, 0.0),
      weight2(bins, 0.0),
      mass(bins, 0.0),
      mass_weight2(bins, 0.0),
      px(bins, 0.0),
      py(bins, 0.0),
      mv2(bins, 0.0),
      mvx2(bins, 0.0),
      mvy2(bins, 0.0),
      virial_xx(bins, 0.0),
      virial_yy(bins, 0.0),
      virial_xx2(bins, 0.0),
      virial_yy2(bins, 0.0),
      mv2vx(bins, 0.0),
      energy2(bins, 0.0),
      flux2(bins, 0.0),
      contact_flux(bins, 0.0),
      contact_flux2(bins, 0.0) {}

std::vector<std::vector<double>*> Moments::arrays() {
  return {&weight,     &weight2, &mass,    &mass_weight2, &px,           &py,
          &mv2,        &mvx2,    &mvy2,    &virial_xx,    &virial_yy,    &virial_xx2,
          &virial_yy2, &mv2vx,   &energy2, &flux2,        &contact_flux, &contact_flux2};
}

std::vector<const std::vector<double>*> Moments::arrays() const {
  return {&weight,     &weight2, &mass,    &mass_weight2, &px,           &py,
          &mv2,        &mvx2,    &mvy2,    &virial_xx,    &virial_yy,    &virial_xx2,
          &virial_yy2, &mv2vx,   &energy2, &flux2,        &contact_flux, &contact_flux2};
}

Moments& Moments::operator+=(const Moments& other) {
  if (other.bins() != bins()) {
    throw std::invalid_argument("Moments: cannot add moments of " + std::to_string(other.bins()) +
                                " bins to moments of " + std::to_string(bins()) + " bins");
  }
  const auto mine = arrays();
  const auto theirs = other.arrays();
  for (std::size_t a = 0; a < mine.size(); ++a) {
    for (std::size_t i = 0; i < mine[a]->size(); ++i) (*mine[a])[i] += (*theirs[a])[i];
  }
  particles += other.particles;
  virial_particles += other.virial_particles;
  contact_flux_particles += other.contact_flux_particles;
  return *this;
}

CoarseGrainer::CoarseGrainer(CoarseGrainGrid grid) : grid_(std::move(grid)) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("coarse-graining grid: " + what);
  };
  if (grid_.bins < 1) fail("bins = " + std::to_string(grid_.bins) + ", must be at least 1");
  if (!(std::isfinite(grid_.Lx) && grid_.Lx > 0.0)) {
    fail("Lx = " + describe(grid_.Lx) + ", must be positive and finite");
  }
  if (!(std::isfinite(grid_.Ly) && grid_.Ly > 0.0)) {
    fail("Ly = " + describe(grid_.Ly) + ", must be positive and finite");
  }
  if (!std::isfinite(grid_.x_lo)) fail("x_lo = " + describe(grid_.x_lo) + ", must be finite");
  dx_ = grid_.Lx / grid_.bins;

  if (grid_.kernel == "bin") {
    kernel_ = Kernel::bin;
    return;
  }
  if (grid_.kernel == "gaussian") {
    kernel_ = Kernel::gaussian;
  } else if (grid_.kernel == "lucy") {
    kernel_ = Kernel::lucy;
  } else {
    fail("kernel = \"" + grid_.kernel + "\", allowed: \"bin\", \"gaussian\", \"lucy\"");
  }
  if (!(std::isfinite(grid_.width) && grid_.width > 0.0)) {
    fail("width = " + describe(grid_.width) + " for kernel \"" + grid_.kernel +
         "\", must be positive and finite");
  }
  support_ = kernel_ == Kernel::gaussian ? kGaussianCut * grid_.width : grid_.width;
  // A particle midway between two centres is dx/2 from the nearest one; a shorter support
  // would leave it with no weight at all.
  if (!(support_ > 0.5 * dx_)) {
    fail("width = " + describe(grid_.width) + " for kernel \"" + grid_.kernel +
         "\": the support radius " + describe(support_) + " must exceed half a bin (" +
         describe(0.5 * dx_) + ")");
  }
}

std::vector<double> CoarseGrainer::bin_centres() const {
  std::vector<double> centres(grid_.bins);
  for (int i = 0; i < grid_.bins; ++i) centres[i] = grid_.x_lo + (i + 0.5) * dx_;
  return centres;
}

void CoarseGrainer::accumulate(Moments& m, const double* x, const double* v, const double* mass,
                               int n, int stride, const double* virial_xx, const double* virial_yy,
                               const double* contact_flux_x) const {
  if (n < 0) throw std::invalid_argument("coarse-graining: particle count " + std::to_string(n));
  if (stride < 2) throw std::invalid_argument("coarse-graining: stride " + std::to_string(stride));
  if (m.bins() != grid_.bins) {
    throw std::invalid_argument("coarse-graining: moments of " + std::to_string(m.bins()) +
                                " bins for a grid of " + std::to_string(grid_.bins));
  }
  if (n > 0 && (x == nullptr || v == nullptr)) {
    throw std::invalid_argument("coarse-graining: null position or velocity array");
  }
  if ((virial_xx == nullptr) != (virial_yy == nullptr)) {
    throw std::invalid_argument("coarse-graining: a contact virial needs both xx and yy");
  }
  const bool with_virial = virial_xx != nullptr;
  const double Lx = grid_.Lx;
  const int bins = grid_.bins;

  // Smooth kernels: the bin centres j (any integer; j mod bins is the bin, so periodic images
  // are the same loop) within the support of a particle, and their raw kernel values.
  std::vector<double> raw;
  std::vector<int> target;
  if (kernel_ != Kernel::bin) {
    const auto most = static_cast<std::size_t>(2.0 * support_ / dx_) + 2;
    raw.reserve(most);
    target.reserve(most);
  }
  const double w = grid_.width;
  const double gaussian_norm = 1.0 / (std::sqrt(2.0 * kPi) * w);
  const double lucy_norm = 5.0 / (4.0 * w);

  for (int p = 0; p < n; ++p) {
    const double xp = x[static_cast<std::ptrdiff_t>(stride) * p];
    const double cx = v[static_cast<std::ptrdiff_t>(stride) * p];
    const double cy = v[static_cast<std::ptrdiff_t>(stride) * p + 1];
    const double mp = mass ? mass[p] : 1.0;
    if (!std::isfinite(xp) || !std::isfinite(cx) || !std::isfinite(cy) ||
        !(std::isfinite(mp) && mp > 0.0)) {
      throw std::invalid_argument("coarse-graining: particle " + std::to_string(p) +
                                  " has x = " + describe(xp) + ", v = (" + describe(cx) + ", " +
                                  describe(cy) + "), m = " + describe(mp));
    }
    // Periodic wrap into [0, Lx]. A result of exactly Lx (a particle a hair below x_lo,
    // rounded) lies at the top edge of the last bin.
    double xr = xp - grid_.x_lo;
    if (xr < 0.0 || xr >= Lx) xr -= Lx * std::floor(xr / Lx);

    const double mc2 = mp * (cx * cx + cy * cy);
    const double wxx = virial_xx ? virial_xx[p] : 0.0;
    const double wyy = virial_yy ? virial_yy[p] : 0.0;
    const double jx = contact_flux_x ? contact_flux_x[p] : 0.0;
    if (!std::isfinite(wxx) || !std::isfinite(wyy) || !std::isfinite(jx)) {
      throw std::invalid_argument("coarse-graining: particle " + std::to_string(p) +
                                  " has contact virial (" + describe(wxx) + ", " + describe(wyy) +
                                  ") and contact energy flux " + describe(jx));
    }
    const auto add = [&](int i, double wi) {
      m.weight[i] += wi;
      m.weight2[i] += wi * wi;
      m.mass[i] += wi * mp;
      m.mass_weight2[i] += wi * wi * mp;
      m.px[i] += wi * mp * cx;
      m.py[i] += wi * mp * cy;
      m.mv2[i] += wi * mc2;
      m.mvx2[i] += wi * mp * cx * cx;
      m.mvy2[i] += wi * mp * cy * cy;
      m.virial_xx[i] += wi * wxx;
      m.virial_yy[i] += wi * wyy;
      m.virial_xx2[i] += wi * wi * wxx * wxx;
      m.virial_yy2[i] += wi * wi * wyy * wyy;
      m.mv2vx[i] += wi * mc2 * cx;
      m.energy2[i] += wi * wi * 0.25 * mc2 * mc2;
      m.flux2[i] += wi * wi * 0.25 * mc2 * mc2 * cx * cx;
      m.contact_flux[i] += wi * jx;
      m.contact_flux2[i] += wi * wi * jx * jx;
    };

    if (kernel_ == Kernel::bin) {
      int i = static_cast<int>(xr / dx_);
      if (i >= bins) i = bins - 1;
      if (i < 0) i = 0;
      add(i, 1.0);
      continue;
    }

    raw.clear();
    target.clear();
    const auto j_lo = static_cast<long long>(std::ceil((xr - support_) / dx_ - 0.5));
    const auto j_hi = static_cast<long long>(std::floor((xr + support_) / dx_ - 0.5));
    double total = 0.0;
    for (long long j = j_lo; j <= j_hi; ++j) {
      const double r = std::abs((j + 0.5) * dx_ - xr);
      double g = 0.0;
      if (kernel_ == Kernel::gaussian) {
        if (r <= support_) g = gaussian_norm * std::exp(-0.5 * (r / w) * (r / w));
      } else {
        const double s = r / w;
        if (s < 1.0) g = lucy_norm * (1.0 + 3.0 * s) * (1.0 - s) * (1.0 - s) * (1.0 - s);
      }
      if (g <= 0.0) continue;
      long long i = j % bins;
      if (i < 0) i += bins;
      raw.push_back(g);
      target.push_back(static_cast<int>(i));
      total += g;
    }
    // Discrete normalisation: sum over bins of W(x_i - x_p) dx = 1 exactly, whatever the
    // truncation and the particle's offset from the centres, so particle number, momentum and
    // energy are conserved by the smoothing (integral of n dx Ly = N).
    for (std::size_t k = 0; k < raw.size(); ++k) add(target[k], raw[k] / total);
  }
  m.particles += n;
  if (with_virial) m.virial_particles += n;
  if (contact_flux_x) m.contact_flux_particles += n;
}

Moments CoarseGrainer::accumulate(const double* x, const double* v, const double* mass, int n,
                                  int stride) const {
  Moments m(grid_.bins);
  accumulate(m, x, v, mass, n, stride);
  return m;
}

fields::FieldSnapshot CoarseGrainer::fields(const Moments& m) const {
  if (m.bins() != grid_.bins) {
    throw std::invalid_argument("coarse-graining: moments of " + std::to_string(m.bins()) +
                                " bins for a grid of " + std::to_string(grid_.bins));
  }
  const int bins = grid_.bins;
  fields::FieldSnapshot f;
  f.x = bin_centres();
  for (auto* a : {&f.n, &f.v_x, &f.v_y, &f.T, &f.count, &f.v_x_stderr, &f.v_y_stderr, &f.T_stderr,
                  &f.P_xx, &f.P_yy, &f.P_xx_stderr, &f.P_yy_stderr}) {
    a->assign(bins, kNaN);
  }
  const double area = dx_ * grid_.Ly;
  for (auto* a :
       {&f.kinetic_energy, &f.energy_flux_x, &f.kinetic_energy_stderr, &f.energy_flux_x_stderr}) {
    a->resize(bins);
  }
  // The error of a sum over independent particles, sum w X, from the particles' own scatter.
  const auto sum_error = [&](double sum, double sum_sq, int i) {
    const double W = m.weight[i];
    const double variance = W > 0.0 ? sum_sq - m.weight2[i] * (sum / W) * (sum / W) : 0.0;
    return std::sqrt(std::max(variance, 0.0)) / area;
  };
  for (int i = 0; i < bins; ++i) {
    f.kinetic_energy[i] = 0.5 * m.mv2[i] / area;
    f.energy_flux_x[i] = 0.5 * m.mv2vx[i] / area;
    f.kinetic_energy_stderr[i] = sum_error(0.5 * m.mv2[i], m.energy2[i], i);
    f.energy_flux_x_stderr[i] = sum_error(0.5 * m.mv2vx[i], m.flux2[i], i);
  }
  f.contact_energy_flux_x.assign(bins, kNaN);
  f.contact_energy_flux_x_stderr.assign(bins, kNaN);
  if (m.has_contact_flux()) {
    for (int i = 0; i < bins; ++i) {
      f.contact_energy_flux_x[i] = m.contact_flux[i] / area;
      // Each collision's two equal halves go together, as the virial's (bin_pressure).
      f.contact_energy_flux_x_stderr[i] = std::sqrt(2.0 * m.contact_flux2[i]) / area;
    }
  }
  for (int i = 0; i < bins; ++i) {
    const BinPressure p = bin_pressure(m, i, area);
    f.P_xx[i] = p.xx, f.P_yy[i] = p.yy, f.P_xx_stderr[i] = p.xx_stderr;
    f.P_yy_stderr[i] = p.yy_stderr;
    const double W = m.weight[i];
    const double U = m.mass[i];
    f.count[i] = W;
    f.n[i] = W / area;
    if (!(W > 0.0 && U > 0.0)) continue;
    const double n_eff = W * W / m.weight2[i];
    f.v_x[i] = m.px[i] / U;
    f.v_y[i] = m.py[i] / U;
    // Unbiased temperature (see the header): D = W - sum w^2 m / U is W (1 - 1/N_eff) for
    // equal masses and N_b - 1 for plain bins.
    const double D = W - m.mass_weight2[i] / U;
    if (!has_fluctuations(W, D)) continue;
    const double S = m.mv2[i] - (m.px[i] * m.px[i] + m.py[i] * m.py[i]) / U;
    const double T = std::max(S, 0.0) / (2.0 * D);
    f.T[i] = T;
    // Var(v_b) per component = sum (w m)^2 (T/m) / U^2.
    f.v_x_stderr[i] = f.v_y_stderr[i] = std::sqrt(T * m.mass_weight2[i]) / U;
    // For Gaussian velocities sum w m |c - v|^2 has relative variance 1/N_eff about its mean
    // (2 components, each a chi^2); removing the mean costs one effective particle, exactly so
    // for bins (chi^2 with 2 (N_b - 1) degrees of freedom: Var T = T^2 / (N_b - 1)).
    if (n_eff > 1.0) f.T_stderr[i] = T / std::sqrt(n_eff - 1.0);
  }
  return f;
}

BoxEnergies CoarseGrainer::energies(const Moments& m) const {
  if (m.bins() != grid_.bins) {
    throw std::invalid_argument("coarse-graining: moments of " + std::to_string(m.bins()) +
                                " bins for a grid of " + std::to_string(grid_.bins));
  }
  BoxEnergies e;
  e.particles = m.particles;
  for (int i = 0; i < grid_.bins; ++i) {
    const double W = m.weight[i];
    const double U = m.mass[i];
    e.mass += U;
    e.momentum_x += m.px[i];
    e.momentum_y += m.py[i];
    e.kinetic_total += 0.5 * m.mv2[i];
    if (!(W > 0.0 && U > 0.0)) continue;
    const double macro_x = 0.5 * m.px[i] * m.px[i] / U;
    const double macro_y = 0.5 * m.py[i] * m.py[i] / U;
    e.kinetic_macro_x += macro_x;
    e.kinetic_macro_y += macro_y;
    const double half_S = 0.5 * m.mv2[i] - macro_x - macro_y;
    e.thermal_biased += half_S;
    const double D = W - m.mass_weight2[i] / U;
    if (!has_fluctuations(W, D)) continue;
    const double T = half_S / D;
    e.thermal += T * W;
    e.macro_noise_x += 0.5 * T * m.mass_weight2[i] / U;
  }
  e.macro_noise_y = e.macro_noise_x;
  return e;
}

BoxPressure CoarseGrainer::pressure(const Moments& m) const {
  if (m.bins() != grid_.bins) {
    throw std::invalid_argument("coarse-graining: moments of " + std::to_string(m.bins()) +
                                " bins for a grid of " + std::to_string(grid_.bins));
  }
  BoxPressure box;
  box.thermal = energies(m).thermal;
  box.area = grid_.Lx * grid_.Ly;
  if (!m.has_virial()) {
    box.xx = box.yy = box.mean_stderr = kNaN;
    return box;
  }
  const double area = dx_ * grid_.Ly;
  double variance = 0.0;
  for (int i = 0; i < grid_.bins; ++i) {
    const BinPressure p = bin_pressure(m, i, area);
    // A bin without fluctuations (N_eff <= 1) adds its contacts only, as thermal adds nothing.
    const bool kinetic = std::isfinite(p.xx);
    box.xx += kinetic ? p.xx : m.virial_xx[i] / area;
    box.yy += kinetic ? p.yy : m.virial_yy[i] / area;
    if (kinetic) variance += 0.25 * (p.xx_stderr * p.xx_stderr + p.yy_stderr * p.yy_stderr);
  }
  box.xx /= grid_.bins;
  box.yy /= grid_.bins;
  box.mean_stderr = std::sqrt(variance) / grid_.bins;
  return box;
}

}  // namespace granvv::md
