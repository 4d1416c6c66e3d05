#include "compare/heat_flux_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "compare/jackknife.hpp"
#include "compare/mode_amplitudes.hpp"
#include "fields/constants.hpp"

namespace granvv::compare {

namespace {

constexpr std::size_t kFewestMembers = 8;
// Above this correlation of the temperature and density modes over the fitted snapshots the
// two columns of the fit are one to the round-off of the amplitudes' scatter.
constexpr double kProportionalModes = 0.999;

void fail(const std::string& what) {
  throw std::invalid_argument("heat-flux fit: " + what);
}

const std::vector<double>& column(const fields::FieldSnapshot& s, const char* name,
                                  std::size_t bins) {
  const std::vector<double>& values = s.*fields::field_column(name).values;
  if (values.size() != bins) {
    fail(std::string("the members' fields have no ") + name + " on every bin (" +
         std::to_string(values.size()) + " of " + std::to_string(bins) + ")");
  }
  return values;
}

bool finite(double x) {
  return std::isfinite(x);
}

double mean_of(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return sum / double(v.size());
}

}  // namespace

HeatFluxAmplitudes heat_flux_amplitudes(const std::vector<fields::FieldSeries>& members,
                                        double mass) {
  if (members.size() < kFewestMembers) {
    fail(std::to_string(members.size()) + " members, the jackknife needs at least " +
         std::to_string(kFewestMembers));
  }
  if (!(std::isfinite(mass) && mass > 0.0)) fail("mass " + std::to_string(mass));
  std::size_t snapshots = members.front().snapshots.size();
  for (const auto& m : members) {
    snapshots = std::min(snapshots, m.snapshots.size());
    if (m.bin_edges != members.front().bin_edges) fail("the members lie on different bins");
  }
  if (snapshots == 0) fail("the members have no snapshots");
  const std::size_t bins = members.front().snapshots.front().x.size();

  HeatFluxAmplitudes a;
  for (auto* rows :
       {&a.heat_flux, &a.temperature, &a.density, &a.flow, &a.mean_density, &a.mean_temperature}) {
    rows->assign(members.size(), std::vector<double>(snapshots));
  }
  for (std::size_t s = 0; s < snapshots; ++s) {
    a.t.push_back(members.front().snapshots[s].t);
    // U: the ensemble's mean flow per bin (mass-weighted: the disks have one mass).
    std::vector<double> count(bins, 0.0), flow_x(bins, 0.0), flow_y(bins, 0.0);
    for (const auto& m : members) {
      const fields::FieldSnapshot& f = m.snapshots[s];
      const auto& n = column(f, "n", bins);
      const auto& vx = column(f, "v_x", bins);
      const auto& vy = column(f, "v_y", bins);
      for (std::size_t b = 0; b < bins; ++b) {
        if (n[b] > 0.0) count[b] += n[b], flow_x[b] += n[b] * vx[b], flow_y[b] += n[b] * vy[b];
      }
    }
    for (std::size_t b = 0; b < bins; ++b) {
      if (!(count[b] > 0.0)) {
        fail("bin " + std::to_string(b) + " holds no disk in any member at snapshot " +
             std::to_string(s));
      }
      flow_x[b] /= count[b], flow_y[b] /= count[b];
    }
    for (std::size_t i = 0; i < members.size(); ++i) {
      const fields::FieldSnapshot& f = members[i].snapshots[s];
      const auto& n = column(f, "n", bins);
      const auto& vx = column(f, "v_x", bins);
      const auto& vy = column(f, "v_y", bins);
      const auto& kinetic = column(f, "kinetic_energy", bins);
      std::vector<double> flux = column(f, "energy_flux_x", bins);
      // The contact transfer where the engine measured it, with the contact part of P_xx in
      // the enthalpy below.
      const std::vector<double>& contact = f.contact_energy_flux_x;
      const std::vector<double>& P_xx = f.P_xx;
      const bool with_contact = contact.size() == bins && P_xx.size() == bins &&
                                std::all_of(contact.begin(), contact.end(), finite) &&
                                std::all_of(P_xx.begin(), P_xx.end(), finite);
      if (with_contact) {
        for (std::size_t b = 0; b < bins; ++b) flux[b] += contact[b];
      } else if (s > 0) {
        a.contact_transfer = false;
      }
      std::vector<double> T(bins), velocity(bins);
      double thermal = 0.0;
      for (std::size_t b = 0; b < bins; ++b) {
        if (!(n[b] > 0.0)) {
          fail("bin " + std::to_string(b) + " of member " + std::to_string(i) +
               " is empty at snapshot " + std::to_string(s) + ": T is undefined (fewer bins)");
        }
        const double rho = mass * n[b];
        const double e = kinetic[b] - rho * (flow_x[b] * vx[b] + flow_y[b] * vy[b]) +
                         0.5 * rho * (flow_x[b] * flow_x[b] + flow_y[b] * flow_y[b]);
        T[b] = e / n[b];
        velocity[b] = vx[b];
        thermal += e;
      }
      const double mean_e = thermal / double(bins);
      const double mean_n = mean_of(n);
      const double mean_T = mean_e / mean_n;  // the thermal energy per disk (2D: e = n T)
      a.temperature[i][s] = mode_amplitude(T, ModePhase::cosine) / mean_T;
      a.density[i][s] = mode_amplitude(n, ModePhase::cosine) / mean_n;
      a.flow[i][s] = mode_amplitude(velocity, ModePhase::sine);
      // e + P_xx at the homogeneous state: 2 e for the kinetic part alone (2D).
      const double enthalpy = with_contact ? mean_e + mean_of(P_xx) : 2.0 * mean_e;
      a.heat_flux[i][s] = mode_amplitude(flux, ModePhase::sine) - enthalpy * a.flow[i][s];
      a.mean_density[i][s] = mean_n;
      a.mean_temperature[i][s] = mean_T;
    }
  }
  return a;
}

namespace {

// The response y and the regressors at the fitted snapshots, from the means of a set of members.
struct Design {
  Eigen::VectorXd y;
  Eigen::MatrixXd X;
  double mean_density = 0.0;
};

Design design(const std::vector<std::size_t>& snapshots,
              const std::vector<std::vector<double>>& means, double k, double mass, double diameter,
              bool burnett) {
  // means: rows heat_flux, temperature, density, flow, mean_density, mean_temperature.
  Design d;
  const auto S = static_cast<Eigen::Index>(snapshots.size());
  d.y.resize(S);
  d.X.resize(S, burnett ? 3 : 2);
  for (Eigen::Index r = 0; r < S; ++r) {
    const std::size_t s = snapshots[static_cast<std::size_t>(r)];
    const double T = means[5][s];
    const double kappa0 = 2.0 * std::sqrt(T / (kPi * mass)) / diameter;
    d.y(r) = means[0][s] / (k * kappa0 * T);
    d.X(r, 0) = means[1][s];
    d.X(r, 1) = means[2][s];
    if (burnett) d.X(r, 2) = means[3][s] / std::sqrt(T / mass);
    d.mean_density += means[4][s] / double(S);
  }
  return d;
}

Eigen::VectorXd weighted_solution(const Design& d, const Eigen::VectorXd& weight) {
  const Eigen::MatrixXd A = weight.asDiagonal() * d.X;
  const Eigen::VectorXd b = weight.asDiagonal() * d.y;
  return A.colPivHouseholderQr().solve(b);
}

}  // namespace

HeatFluxFit fit_heat_flux(const HeatFluxAmplitudes& a, double wavenumber, double mass,
                          double diameter, std::size_t start, bool burnett) {
  if (!(std::isfinite(wavenumber) && wavenumber > 0.0)) fail("wavenumber must be positive");
  if (!(mass > 0.0 && diameter > 0.0)) fail("mass and diameter must be positive");
  const std::size_t members = a.heat_flux.size();
  if (members < kFewestMembers) {
    fail(std::to_string(members) + " members, the jackknife needs at least " +
         std::to_string(kFewestMembers));
  }
  const std::size_t coefficients = burnett ? 3 : 2;
  const std::size_t total = a.t.size();
  if (start + coefficients + 3 > total) {
    fail("snapshots " + std::to_string(start) + ".." + std::to_string(total) + " are too few for " +
         std::to_string(coefficients) + " coefficients");
  }
  std::vector<std::size_t> snapshots;
  for (std::size_t s = start; s < total; ++s) snapshots.push_back(s);

  const std::vector<const std::vector<std::vector<double>>*> rows = {
      &a.heat_flux, &a.temperature, &a.density, &a.flow, &a.mean_density, &a.mean_temperature};
  std::vector<std::vector<double>> means;
  std::vector<std::vector<std::vector<double>>> leave_out;  // [row][i][s]
  for (const auto* r : rows) {
    means.push_back(member_mean(*r));
    leave_out.push_back(leave_one_out_means(*r));
  }
  const auto sample = [&](std::size_t i) {
    std::vector<std::vector<double>> m;
    for (const auto& row : leave_out) m.push_back(row[i]);
    return m;
  };
  const Design all = design(snapshots, means, wavenumber, mass, diameter, burnett);
  if (!(all.y.allFinite() && all.X.allFinite())) {
    fail("the members' heat flux, density, temperature or flow is not finite");
  }
  const Eigen::VectorXd T_part = all.X.col(0), n_part = all.X.col(1);
  const double correlation_Tn =
      ((T_part.array() - T_part.mean()) * (n_part.array() - n_part.mean())).sum() /
      std::sqrt((T_part.array() - T_part.mean()).square().sum() *
                (n_part.array() - n_part.mean()).square().sum());
  if (!(std::abs(correlation_Tn) <= kProportionalModes)) {
    fail("the temperature and density modes are proportional (correlation " +
         std::to_string(correlation_Tn) +
         ": a scene at pressure balance), so kappa and mu cannot be told apart");
  }

  // The error of each y_s from the members' scatter.
  std::vector<Design> samples;
  std::vector<std::vector<double>> y_samples;
  for (std::size_t i = 0; i < members; ++i) {
    samples.push_back(design(snapshots, sample(i), wavenumber, mass, diameter, burnett));
    y_samples.emplace_back(samples.back().y.data(),
                           samples.back().y.data() + samples.back().y.size());
  }
  const std::vector<double> y_error = jackknife_errors(y_samples);
  Eigen::VectorXd weight(static_cast<Eigen::Index>(snapshots.size()));
  for (std::size_t r = 0; r < snapshots.size(); ++r) {
    if (!(y_error[r] > 0.0)) fail("the heat flux has no scatter over the members");
    weight(static_cast<Eigen::Index>(r)) = 1.0 / y_error[r];
  }

  const Eigen::VectorXd p = weighted_solution(all, weight);
  std::vector<std::vector<double>> refits(coefficients, std::vector<double>(members));
  for (std::size_t i = 0; i < members; ++i) {
    const Eigen::VectorXd q = weighted_solution(samples[i], weight);
    for (std::size_t c = 0; c < coefficients; ++c) refits[c][i] = q(static_cast<Eigen::Index>(c));
  }
  // theta from b: beta = -b kappa0 sqrt(m <T>) / k and theta = beta m <n> / eta0^2.
  const double to_theta = -8.0 * std::sqrt(kPi) * all.mean_density * diameter / wavenumber;

  HeatFluxFit fit;
  fit.conductivity = p(0), fit.conductivity_error = jackknife_error(refits[0]);
  fit.mu = p(1), fit.mu_error = jackknife_error(refits[1]);
  if (burnett) {
    fit.burnett = to_theta * p(2);
    fit.burnett_error = std::abs(to_theta) * jackknife_error(refits[2]);
  }
  fit.correlation = jackknife_correlation(refits[0], refits[1]);

  const Eigen::VectorXd fitted = all.X * p;
  const Eigen::VectorXd navier_stokes = all.X.leftCols(2) * p.head(2);
  fit.snapshots = snapshots;
  for (std::size_t r = 0; r < snapshots.size(); ++r) {
    const auto e = static_cast<Eigen::Index>(r);
    fit.response.push_back(all.y(e));
    fit.response_error.push_back(y_error[r]);
    fit.fitted.push_back(fitted(e));
    fit.navier_stokes.push_back(navier_stokes(e));
    fit.density_part.push_back(all.X(e, 1) * p(1));
    const double z = (all.y(e) - fitted(e)) / y_error[r];
    fit.chi2 += z * z;
  }
  fit.degrees_of_freedom = static_cast<int>(snapshots.size() - coefficients);
  return fit;
}

}  // namespace granvv::compare
