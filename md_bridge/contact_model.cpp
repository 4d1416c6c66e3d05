#include "md_bridge/contact_model.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "fields/constants.hpp"

namespace granvv::md {

namespace {

// Shortest readable form of a value for error messages ("1.2", "nan", "-inf").
std::string show(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

[[noreturn]] void reject(const std::string& key, double value, const std::string& allowed) {
  throw std::invalid_argument(key + " = " + show(value) + ": " + allowed);
}

bool positive_finite(double x) {
  return std::isfinite(x) && x > 0.0;
}

// omega0 h and gamma h stay far from the stability edge for n >= 10; below this many steps
// per contact the integrator is not trusted.
constexpr int kMinStepsPerContact = 10;
constexpr int kMaxStepsPerContact = 1000000;
// Overlaps beyond 10 % of sigma leave the hard-disk limit the particle engine stands for.
constexpr double kMaxOverlapFraction = 0.1;

}  // namespace

double effective_mass(double mass) {
  return 0.5 * mass;
}

double damping_for_restitution(double restitution, double kn, double m_eff) {
  const double ln_r = std::log(restitution);
  return -2.0 * ln_r * std::sqrt(kn / m_eff) / std::sqrt(kPi * kPi + ln_r * ln_r);
}

double contact_duration(double kn, double gamma_n, double m_eff) {
  const double omega_sq = kn / m_eff - 0.25 * gamma_n * gamma_n;
  if (!(omega_sq > 0.0)) return std::numeric_limits<double>::infinity();
  return kPi / std::sqrt(omega_sq);
}

double restitution_for_damping(double gamma_n, double kn, double m_eff) {
  const double tc = contact_duration(kn, gamma_n, m_eff);
  if (std::isinf(tc)) return 0.0;  // critically or over-damped: the disks never separate
  return std::exp(-0.5 * gamma_n * tc);
}

double stiffness_for_overlap(double m_eff, double max_relative_speed, double max_overlap) {
  const double ratio = max_relative_speed / max_overlap;
  return m_eff * ratio * ratio;
}

double undamped_max_overlap(double kn, double m_eff, double relative_speed) {
  return relative_speed * std::sqrt(m_eff / kn);
}

double leapfrog_restitution(double gamma_n, double kn, double m_eff, double dt) {
  const double gh = gamma_n * dt;
  const double wh_sq = kn / m_eff * dt * dt;
  if (!(gh < 1.0)) return 0.0;
  const double rho = std::sqrt(1.0 - gh);
  const double cos_theta = (2.0 - wh_sq - gh) / (2.0 * rho);
  if (!(std::abs(cos_theta) < 1.0)) return 0.0;  // no discrete oscillation
  const double theta = std::acos(cos_theta);
  if (gh == 0.0) return 1.0;
  return std::exp(kPi * std::log1p(-gh) / (2.0 * theta));
}

double leapfrog_damping_for_restitution(double restitution, double kn, double m_eff,
                                        int steps_per_contact) {
  if (restitution >= 1.0) return 0.0;
  const double n = steps_per_contact;
  // r_h(gamma) with dt = tc(gamma)/n falls monotonically from 1 at gamma = 0 to 0 as gamma
  // approaches critical damping 2 omega0 (tc and dt diverge), so bisection brackets it.
  const auto r_of = [&](double gamma) {
    const double tc = contact_duration(kn, gamma, m_eff);
    if (std::isinf(tc)) return 0.0;
    return leapfrog_restitution(gamma, kn, m_eff, tc / n);
  };
  double lo = 0.0;
  double hi = 2.0 * std::sqrt(kn / m_eff);
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (r_of(mid) > restitution) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

void validate(const ContactSpec& spec) {
  if (!(std::isfinite(spec.restitution) && spec.restitution > 0.0 && spec.restitution <= 1.0))
    reject("md.restitution", spec.restitution, "must be in (0, 1]");
  if (!positive_finite(spec.mass)) reject("md.mass", spec.mass, "must be finite and > 0");
  if (!positive_finite(spec.diameter))
    reject("md.diameter", spec.diameter, "must be finite and > 0");
  if (!positive_finite(spec.max_overlap) || spec.max_overlap > kMaxOverlapFraction * spec.diameter)
    reject("md.max_overlap", spec.max_overlap,
           "must be in (0, " + show(kMaxOverlapFraction * spec.diameter) +
               "] (at most 0.1 sigma: the hard-disk limit)");
  if (!positive_finite(spec.max_relative_speed))
    reject("md.max_relative_speed", spec.max_relative_speed, "must be finite and > 0");
  if (spec.steps_per_contact < kMinStepsPerContact || spec.steps_per_contact > kMaxStepsPerContact)
    reject("md.steps_per_contact", spec.steps_per_contact,
           "must be an integer in [10, 1000000] (time steps per contact duration)");
}

void validate(const ContactModel& model) {
  const auto bad = [](const std::string& what, double value, const std::string& allowed) {
    reject("contact model " + what, value, allowed);
  };
  if (!positive_finite(model.kn)) bad("kn", model.kn, "must be finite and > 0");
  if (!(std::isfinite(model.gamma_n) && model.gamma_n >= 0.0))
    bad("gamma_n", model.gamma_n, "must be finite and >= 0");
  if (!positive_finite(model.mass)) bad("mass", model.mass, "must be finite and > 0");
  if (!positive_finite(model.diameter)) bad("diameter", model.diameter, "must be finite and > 0");
  if (!(std::isfinite(model.restitution) && model.restitution > 0.0 && model.restitution <= 1.0))
    bad("restitution", model.restitution, "must be in (0, 1]");
  if (!positive_finite(model.dt)) bad("dt", model.dt, "must be finite and > 0");
  const double m_eff = effective_mass(model.mass);
  const double omega0_sq = model.kn / m_eff;
  // Underdamped with room to spare (r > ~1e-6): near critical damping tc diverges.
  if (!(0.25 * model.gamma_n * model.gamma_n < (1.0 - 1e-6) * omega0_sq))
    bad("gamma_n", model.gamma_n,
        "must be below critical damping 2 sqrt(kn/m_eff) = " + show(2.0 * std::sqrt(omega0_sq)));
  const double tc = contact_duration(model.kn, model.gamma_n, m_eff);
  if (!(std::abs(model.contact_time / tc - 1.0) <= 1e-9))
    bad("contact_time", model.contact_time,
        "must be pi / sqrt(kn/m_eff - gamma_n^2/4) = " + show(tc));
  if (!(tc / model.dt >= kMinStepsPerContact * (1.0 - 1e-9)))
    bad("dt", model.dt,
        "must resolve the contact with at least 10 steps (dt <= tc/10 = " +
            show(tc / kMinStepsPerContact) + ")");
}

ContactModel make_contact_model(const ContactSpec& spec) {
  validate(spec);
  const double m_eff = effective_mass(spec.mass);
  const double n = spec.steps_per_contact;
  const double margin = 1.0 + kPi * kPi / (6.0 * n * n);
  ContactModel model;
  model.restitution = spec.restitution;
  model.mass = spec.mass;
  model.diameter = spec.diameter;
  model.kn =
      stiffness_for_overlap(m_eff, spec.max_relative_speed, spec.max_overlap) * margin * margin;
  model.gamma_n_continuum = damping_for_restitution(spec.restitution, model.kn, m_eff);
  model.gamma_n = spec.discrete_correction
                      ? leapfrog_damping_for_restitution(spec.restitution, model.kn, m_eff,
                                                         spec.steps_per_contact)
                      : model.gamma_n_continuum;
  model.contact_time = contact_duration(model.kn, model.gamma_n, m_eff);
  model.dt = model.contact_time / n;
  validate(model);
  return model;
}

std::string lammps_number(double value) {
  if (!std::isfinite(value))
    throw std::invalid_argument("refusing to send the non-finite number " + show(value) +
                                " to LAMMPS");
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

std::string pair_style_command(const ContactModel& model) {
  validate(model);
  // Kn Kt gamma_n gamma_t xmu dampflag: friction explicitly off (no NULL, no limit_damping).
  return "pair_style gran/hooke " + lammps_number(model.kn) + " 0 " + lammps_number(model.gamma_n) +
         " 0 0 0";
}

std::string pair_coeff_command() {
  return "pair_coeff * *";
}

std::string timestep_command(const ContactModel& model) {
  validate(model);
  return "timestep " + lammps_number(model.dt);
}

}  // namespace granvv::md
