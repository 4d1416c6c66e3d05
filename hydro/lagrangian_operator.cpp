#include "hydro/lagrangian_operator.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "hydro/wide_loops.hpp"

namespace granvv::hydro {

LagrangianOperator::LagrangianOperator(const Closure& closure, int cells)
    : closure_(closure),
      n_(cells),
      momentum_diag_(cells),
      momentum_upper_(cells),
      energy_diag_(cells),
      energy_upper_(cells),
      shear_diag_(cells),
      shear_upper_(cells),
      v_mid_(cells),
      vy_mid_(cells),
      dv_mid_(cells),
      work_(cells),
      inertia_(cells) {
  if (cells < 3)
    throw std::invalid_argument("periodic tridiagonal system needs at least 3 unknowns");
}

GRANVV_WIDE_LOOPS
void LagrangianOperator::freeze(const std::vector<double>& cell_mass,
                                const std::vector<double>& widths, const std::vector<double>& T,
                                double dt, const std::vector<double>& reference_dv,
                                FrozenCoefficients& out) {
  out.density.resize(n_);
  out.viscous_coupling.resize(n_);
  out.shear_coupling.resize(n_);
  out.heat_coupling.resize(n_);
  out.acoustic_coupling.resize(n_);
  if (reference_dv.empty()) {
    out.reference_dv.assign(n_, 0.0);
  } else {
    out.reference_dv = reference_dv;
  }
  inverse_width_.resize(n_);
#pragma GCC ivdep  // distinct arrays
  for (int i = 0; i < n_; ++i) {
    inverse_width_[i] = 1.0 / widths[i];
    out.density[i] = cell_mass[i] * inverse_width_[i];
  }
  closure_.cell_coefficients(out.density, T, out.cell);
  const CellCoefficients& cell = out.cell;
  const double half_dt = 0.5 * dt;
#pragma GCC ivdep  // distinct arrays
  for (int i = 0; i < n_; ++i) {
    const double inverse_w = inverse_width_[i];
    out.viscous_coupling[i] = cell.viscosity[i] * inverse_w;
    out.shear_coupling[i] = cell.shear_viscosity[i] * inverse_w;
    out.acoustic_coupling[i] = half_dt * cell.adiabatic_modulus[i] * inverse_w;
  }
  // Heat flux at node j between cell centres j-1 and j: the mean of the two cells' kappa (mu)
  // over the centre-to-centre distance h_j = (dx_{j-1} + dx_j)/2 (the halves cancel exactly).
  const auto node_coupling = [&](const std::vector<double>& coefficient,
                                 std::vector<double>& coupling) {
    const auto at = [&](int j, int l) {
      return (coefficient[l] + coefficient[j]) / (widths[l] + widths[j]);
    };
    coupling[0] = at(0, n_ - 1);
#pragma GCC ivdep  // distinct arrays
    for (int j = 1; j < n_; ++j) coupling[j] = at(j, j - 1);
  };
  node_coupling(cell.conductivity, out.heat_coupling);
  // Whether mu != 0 in any cell: the bits of |mu| or-ed together (an integer reduction, which
  // vectorises; NaN counts as non-zero, as it compares unequal to 0).
  std::uint64_t mu_bits = 0;
  for (int i = 0; i < n_; ++i) {
    std::uint64_t bits;
    std::memcpy(&bits, &cell.mu[i], sizeof bits);
    mu_bits |= bits << 1;
  }
  const bool density_heat_flux = mu_bits != 0;
  out.density_heat_coupling.resize(density_heat_flux ? n_ : 0);
  if (density_heat_flux) node_coupling(cell.mu, out.density_heat_coupling);
}

GRANVV_WIDE_LOOPS
bool LagrangianOperator::advance(const LagrangianState& from, const std::vector<double>& T_from,
                                 const FrozenCoefficients& c, double dt, PassFields& to) {
  const int n = n_;
  const auto& m = from.cell_mass;
  const auto& a = c.viscous_coupling;
  const auto& a_xy = c.shear_coupling;
  const auto& p = c.cell.pressure;
  const auto& b = c.heat_coupling;
  const auto& alpha = c.acoustic_coupling;
  const auto& dv_ref = c.reference_dv;
  to.t = from.t + dt;
  const double inverse_dt = 1.0 / dt;

  // Momentum, paper Eq. 1b: mu_j dv_j/dt = P_j - P_{j-1} with, at the time-centred velocity
  // vbar = (v^n + v^{n+1})/2 and dv_i = vbar_{i+1} - vbar_i,
  //   P_i = -(p_i - alpha_i (dv_i - dv_ref_i)) + a_i dv_i.
  const auto momentum_row = [&](int j, int l) {
    const double mu = 0.5 * (m[l] + m[j]);
    inertia_[j] = 2.0 * mu * inverse_dt;
    momentum_diag_[j] = inertia_[j] + a[j] + alpha[j] + a[l] + alpha[l];
    momentum_upper_[j] = -(a[j] + alpha[j]);
    const double explicit_stress_j = -p[j] - alpha[j] * dv_ref[j];
    const double explicit_stress_l = -p[l] - alpha[l] * dv_ref[l];
    v_mid_[j] = inertia_[j] * from.node_v[j] + explicit_stress_j - explicit_stress_l;
  };
  momentum_row(0, n - 1);
#pragma GCC ivdep  // distinct arrays
  for (int j = 1; j < n; ++j) momentum_row(j, j - 1);
  const bool transverse = from.has_transverse();
  if (transverse) {
    // Transverse momentum: shear stress a_xy_i (vy_{i+1} - vy_i) (docs/physics.md §6).
    const auto shear_row = [&](int j, int l) {
      shear_diag_[j] = inertia_[j] + a_xy[j] + a_xy[l];
      shear_upper_[j] = -a_xy[j];
      vy_mid_[j] = inertia_[j] * from.node_vy[j];
    };
    shear_row(0, n - 1);
#pragma GCC ivdep  // distinct arrays
    for (int j = 1; j < n; ++j) shear_row(j, j - 1);
  }
  // The energy equation's matrix (Crank-Nicolson conduction, below) does not depend on the
  // velocities, so it is factorised together with the momentum ones (hydro/batched_tridiagonal).
  const auto energy_matrix_row = [&](int i, int r) {
    energy_diag_[i] = m[i] * inverse_dt + 0.5 * (b[r] + b[i]);
    energy_upper_[i] = -0.5 * b[r];
  };
#pragma GCC ivdep  // distinct arrays
  for (int i = 0; i + 1 < n; ++i) energy_matrix_row(i, i + 1);
  energy_matrix_row(n - 1, 0);
  const PeriodicTridiagonalView momentum{momentum_diag_.data(), momentum_upper_.data()};
  const PeriodicTridiagonalView energy{energy_diag_.data(), energy_upper_.data()};
  if (transverse) {
    const PeriodicTridiagonalView shear{shear_diag_.data(), shear_upper_.data()};
    if (!factorize_periodic<3>(n, {momentum, shear, energy}, {&momentum_, &shear_, &energy_})) {
      return false;
    }
    solve_periodic<2>(n, {&momentum_, &shear_}, {v_mid_.data(), vy_mid_.data()});
  } else {
    // The momentum's right side is known: its forward sweep runs inside the factorisation.
    if (!factorize_periodic<2>(n, {momentum, energy}, {&momentum_, &energy_}, v_mid_.data())) {
      return false;
    }
    back_substitute_periodic<1>(n, {&momentum_}, {v_mid_.data()});
  }
  to.node_x.resize(n);
  to.node_v.resize(n);
  to.node_vy.resize(transverse ? n : 0);
  for (int j = 0; j < n; ++j) {
    to.node_x[j] = from.node_x[j] + dt * v_mid_[j];
    to.node_v[j] = 2.0 * v_mid_[j] - from.node_v[j];
  }
  if (transverse) {
    for (int j = 0; j < n; ++j) to.node_vy[j] = 2.0 * vy_mid_[j] - from.node_vy[j];
  }

  // Energy, paper Eq. 2: m_i dT_i/dt = P_i (vbar_{i+1} - vbar_i) + [viscous heating by v_y]
  // + conduction, with the same P_i as the momentum step (exact energy exchange),
  // Crank-Nicolson conduction G_j = b_j (T_j - T_{j-1}) and the explicit heat flux down the
  // density gradient D_j = d_j (n_j - n_{j-1}) (header comment).
  const auto work = [&](int i, int r) {
    const double dv = v_mid_[r] - v_mid_[i];
    dv_mid_[i] = dv;
    work_[i] = (-p[i] + alpha[i] * (dv - dv_ref[i]) + a[i] * dv) * dv;
  };
#pragma GCC ivdep  // distinct arrays
  for (int i = 0; i + 1 < n; ++i) work(i, i + 1);
  work(n - 1, 0);
  if (transverse) {
    const auto shear_heating = [&](int i, int r) {
      const double dvy = vy_mid_[r] - vy_mid_[i];
      work_[i] += a_xy[i] * dvy * dvy;
    };
#pragma GCC ivdep  // distinct arrays
    for (int i = 0; i + 1 < n; ++i) shear_heating(i, i + 1);
    shear_heating(n - 1, 0);
  }
  const auto& T = T_from;
  to.cell_T.resize(n);
  auto& rhs = to.cell_T;
  const auto energy_rhs = [&](int i, int l, int r) {
    const double conduction = b[r] * (T[r] - T[i]) - b[i] * (T[i] - T[l]);
    rhs[i] = m[i] * inverse_dt * T[i] + work_[i] + 0.5 * conduction;
  };
  energy_rhs(0, n - 1, 1);
#pragma GCC ivdep  // distinct arrays
  for (int i = 1; i + 1 < n; ++i) energy_rhs(i, i - 1, i + 1);
  energy_rhs(n - 1, n - 2, 0);
  if (!c.density_heat_coupling.empty()) {
    // The heat flux -mu dn/dx, explicit: D_j = d_j (n_j - n_{j-1}) enters as G_j does.
    const auto& d = c.density_heat_coupling;
    const auto& density = c.density;
    const auto density_flux = [&](int i, int l, int r) {
      rhs[i] += d[r] * (density[r] - density[i]) - d[i] * (density[i] - density[l]);
    };
    density_flux(0, n - 1, 1);
    for (int i = 1; i + 1 < n; ++i) density_flux(i, i - 1, i + 1);
    density_flux(n - 1, n - 2, 0);
  }
  solve_periodic<1>(n, {&energy_}, {to.cell_T.data()});
  // 0 < T <= the largest double: positive and finite (NaN fails both comparisons). No node may
  // overtake its neighbour. The failures are counted (an integer sum of comparisons vectorises,
  // a running boolean does not).
  constexpr double kLargest = std::numeric_limits<double>::max();
  const double* T_to = to.cell_T.data();
  const double* x_to = to.node_x.data();
  int failures = 0;
  for (int i = 0; i < n; ++i) failures += !((T_to[i] > 0.0) & (T_to[i] <= kLargest));
  for (int i = 0; i + 1 < n; ++i) failures += !(x_to[i + 1] > x_to[i]);
  return failures == 0 && cell_width(to.node_x, n - 1) > 0.0;
}

}  // namespace granvv::hydro
