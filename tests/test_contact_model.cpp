// The contact law (md_bridge/contact_model.hpp) against its formulas (docs/physics.md §5), against
// an independent integration of the continuum spring-dashpot, and against a step-by-step
// emulation of LAMMPS' velocity Verlet for the discrete correction. No LAMMPS here.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fields/constants.hpp"
#include "md_bridge/contact_model.hpp"
#include "support/contact_spec.hpp"

namespace {

using namespace granvv::md;

using granvv::kPi;
using granvv::testing::test_contact_spec;

std::string message_of(const ContactSpec& spec) {
  try {
    make_contact_model(spec);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// Continuum head-on contact, xi'' = -omega0^2 xi - gamma xi', xi(0) = 0, xi'(0) = u, by RK4
// with a step tc/20000, until xi returns to 0 (linear interpolation of the crossing).
struct ContinuumContact {
  double restitution, duration, max_overlap;
};
ContinuumContact integrate_contact(double kn, double gamma, double m_eff, double u) {
  const double w2 = kn / m_eff;
  const double h = contact_duration(kn, gamma, m_eff) / 20000.0;
  double xi = 0.0, v = u, t = 0.0, peak = 0.0;
  const auto acc = [&](double x, double y) { return -w2 * x - gamma * y; };
  for (;;) {
    const double k1x = v, k1v = acc(xi, v);
    const double k2x = v + 0.5 * h * k1v, k2v = acc(xi + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = acc(xi + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = acc(xi + h * k3x, v + h * k3v);
    const double xi_new = xi + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    const double v_new = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (xi_new <= 0.0 && t > 0.0) {
      const double f = xi / (xi - xi_new);
      return {-(v + f * (v_new - v)) / u, t + f * h, peak};
    }
    xi = xi_new;
    v = v_new;
    t += h;
    peak = std::max(peak, xi);
  }
}

// Two disks of mass m, diameter sigma, integrated exactly as LAMMPS' fix nve/sphere with
// pair gran/hooke does: half kick, drift, force from the new positions and the half-step
// velocities, half kick. The contact starts at phase s within a step. Returns r and the
// largest overlap.
struct DiscreteContact {
  double restitution, max_overlap;
};
DiscreteContact verlet_contact(const ContactModel& m, double u, double s) {
  const double h = m.dt, sigma = m.diameter, m_eff = 0.5 * m.mass;
  const double gap = (2.0 + s) * u * h;
  double xa = -0.5 * (sigma + gap), xb = -xa, va = 0.5 * u, vb = -0.5 * u, fb = 0.0;
  double peak = 0.0;
  bool touched = false;
  for (int step = 0; step < 100000; ++step) {
    va -= 0.5 * h * fb / m.mass;  // force on a is -fb
    vb += 0.5 * h * fb / m.mass;
    xa += h * va;
    xb += h * vb;
    const double overlap = sigma - (xb - xa);
    fb = 0.0;
    if (overlap > 0.0) {
      touched = true;
      peak = std::max(peak, overlap);
      fb = m.kn * overlap - m_eff * m.gamma_n * (vb - va);
    } else if (touched) {
      return {(vb - va) / u, peak};
    }
    va -= 0.5 * h * fb / m.mass;
    vb += 0.5 * h * fb / m.mass;
  }
  return {std::numeric_limits<double>::quiet_NaN(), peak};
}

TEST(ContactModel, EffectiveMassOfEqualDisksIsHalfTheMass) {
  EXPECT_DOUBLE_EQ(effective_mass(1.0), 0.5);
  EXPECT_DOUBLE_EQ(effective_mass(3.0), 1.5);
}

TEST(ContactModel, DampingFormulaAndItsInverse) {
  const double kn = 5000.0, m_eff = 0.5;  // omega0 = 100
  for (const double r : {0.1, 0.5, 0.7, 0.9, 0.98, 0.999}) {
    const double ln_r = std::log(r);
    const double expected = -2.0 * ln_r * 100.0 / std::sqrt(kPi * kPi + ln_r * ln_r);
    const double gamma = damping_for_restitution(r, kn, m_eff);
    EXPECT_NEAR(gamma, expected, 1e-12 * expected) << "r = " << r;
    EXPECT_NEAR(contact_duration(kn, gamma, m_eff), kPi / std::sqrt(10000.0 - 0.25 * gamma * gamma),
                1e-15);
    EXPECT_NEAR(restitution_for_damping(gamma, kn, m_eff), r, 1e-14) << "r = " << r;
  }
  EXPECT_EQ(damping_for_restitution(1.0, kn, m_eff), 0.0);
  EXPECT_DOUBLE_EQ(contact_duration(kn, 0.0, m_eff), kPi / 100.0);
  // Critical damping: the disks never separate.
  EXPECT_TRUE(std::isinf(contact_duration(kn, 200.0, m_eff)));
  EXPECT_EQ(restitution_for_damping(250.0, kn, m_eff), 0.0);
}

TEST(ContactModel, FormulaMatchesAnIntegratedContinuumCollision) {
  // RK4 at tc/20000: r and tc to ~1e-8 (limited by the crossing interpolation).
  const double kn = 2.0e4, m_eff = 0.5, u = 3.0;
  for (const double r : {0.5, 0.7, 0.9, 0.98, 1.0}) {
    const double gamma = damping_for_restitution(r, kn, m_eff);
    const ContinuumContact c = integrate_contact(kn, gamma, m_eff, u);
    EXPECT_NEAR(c.restitution, r, 1e-7) << "r = " << r;
    EXPECT_NEAR(c.duration / contact_duration(kn, gamma, m_eff), 1.0, 1e-7) << "r = " << r;
    // The undamped overlap u sqrt(m_eff/kn) bounds the damped one.
    EXPECT_LE(c.max_overlap, undamped_max_overlap(kn, m_eff, u) * (1.0 + 1e-9));
  }
  EXPECT_NEAR(integrate_contact(kn, 0.0, m_eff, u).max_overlap / undamped_max_overlap(kn, m_eff, u),
              1.0, 1e-8);
}

TEST(ContactModel, HardDiskStiffnessPutsTheFastestCollisionAtTheOverlapBound) {
  const double m_eff = 0.5, u_max = 10.0, delta_max = 0.01;
  const double kn = stiffness_for_overlap(m_eff, u_max, delta_max);
  EXPECT_DOUBLE_EQ(kn, 0.5 * 1e6);  // m_eff (u_max/delta_max)^2
  EXPECT_NEAR(undamped_max_overlap(kn, m_eff, u_max), delta_max, 1e-15);
  EXPECT_NEAR(undamped_max_overlap(kn, m_eff, 0.5 * u_max), 0.5 * delta_max, 1e-15);
}

TEST(ContactModel, LeapfrogRestitutionTendsToTheContinuumAndIsLowAtFiniteSteps) {
  const double kn = 5000.0, m_eff = 0.5;
  for (const double r : {0.5, 0.7, 0.9, 0.98}) {
    const double gamma = damping_for_restitution(r, kn, m_eff);
    const double tc = contact_duration(kn, gamma, m_eff);
    EXPECT_NEAR(leapfrog_restitution(gamma, kn, m_eff, tc / 1e5), r, 1e-5) << "r = " << r;
    const double r30 = leapfrog_restitution(gamma, kn, m_eff, tc / 30);
    const double r60 = leapfrog_restitution(gamma, kn, m_eff, tc / 60);
    if (r <= 0.7) {
      // Strong damping: first order in dt. To leading order (expanding rho and theta),
      // ln r_h = ln r [1 + gamma dt (1/2 - omega0^2 / (4 omega^2))], omega = pi / tc.
      EXPECT_NEAR((r - r30) / (r - r60), 2.0, 0.15) << "r = " << r;
      const double omega_ratio_sq = (kn / m_eff) * tc * tc / (kPi * kPi);
      const double coefficient = gamma * tc / 60 * (0.5 - 0.25 * omega_ratio_sq);
      EXPECT_NEAR((std::log(r60) / std::log(r) - 1.0) / coefficient, 1.0, 0.1) << "r = " << r;
    } else {
      // Weak damping: the O(dt^2) frequency shift competes; both tiny.
      EXPECT_NEAR(r30, r, 2e-4) << "r = " << r;
    }
  }
  EXPECT_EQ(leapfrog_restitution(0.0, kn, m_eff, 1e-3), 1.0);
  EXPECT_EQ(leapfrog_restitution(100.0, kn, m_eff, 0.02), 0.0);  // gamma h >= 1
}

TEST(ContactModel, DiscreteDampingReproducesTheTargetInTheLeapfrogFormula) {
  const double kn = 5000.0, m_eff = 0.5;
  for (const double r : {0.05, 0.5, 0.7, 0.9, 0.98, 0.9999}) {
    for (const int n : {10, 30, 100}) {
      const double gamma = leapfrog_damping_for_restitution(r, kn, m_eff, n);
      const double dt = contact_duration(kn, gamma, m_eff) / n;
      EXPECT_NEAR(leapfrog_restitution(gamma, kn, m_eff, dt), r, 1e-12)
          << "r = " << r << ", n = " << n;
      if (r <= 0.7) {
        EXPECT_LT(gamma, damping_for_restitution(r, kn, m_eff));
      }
      const double ratio = gamma / damping_for_restitution(r, kn, m_eff);
      EXPECT_GT(ratio, 0.85);
      EXPECT_LT(ratio, 1.01);
    }
  }
  EXPECT_EQ(leapfrog_damping_for_restitution(1.0, kn, m_eff, 30), 0.0);
}

TEST(ContactModel, PhaseAveragedVerletCollisionMatchesTheLeapfrogFormula) {
  // Emulated LAMMPS integration, 256 entry phases: the corrected model's mean r is within
  // 1e-3 of the target (measured 2.5e-4 for r = 0.5); the continuum gamma_n is low by
  // O(1/n) (3.4e-3 for r = 0.5 at n = 30).
  for (const double r : {0.5, 0.7, 0.9, 0.98}) {
    for (const bool correct : {true, false}) {
      ContactSpec spec = test_contact_spec();
      spec.restitution = r;
      spec.discrete_correction = correct;
      const ContactModel m = make_contact_model(spec);
      double sum = 0.0, lo = 1.0, hi = 0.0;
      const int phases = 256;
      for (int k = 0; k < phases; ++k) {
        const double rk = verlet_contact(m, 1.0, (k + 0.5) / phases).restitution;
        sum += rk;
        lo = std::min(lo, rk);
        hi = std::max(hi, rk);
      }
      const double mean = sum / phases;
      const double predicted = leapfrog_restitution(m.gamma_n, m.kn, 0.5, m.dt);
      EXPECT_NEAR(mean, predicted, 5e-4) << "r = " << r << ", corrected = " << correct;
      if (correct) {
        EXPECT_NEAR(mean, r, 1e-3) << "r = " << r;
      }
      // A single collision scatters by O(gamma dt) around the mean.
      EXPECT_LT(hi - lo, 2.0 * m.gamma_n * m.dt) << "r = " << r;
    }
  }
  ContactSpec half = test_contact_spec();
  half.restitution = 0.5;
  half.discrete_correction = false;
  const ContactModel continuum = make_contact_model(half);
  double sum = 0.0;
  for (int k = 0; k < 256; ++k) sum += verlet_contact(continuum, 1.0, (k + 0.5) / 256).restitution;
  EXPECT_LT(sum / 256, 0.5 - 2e-3);
}

TEST(ContactModel, DefaultModelFromTheSpec) {
  const ContactSpec spec = test_contact_spec();
  const ContactModel m = make_contact_model(spec);
  const double margin = 1.0 + kPi * kPi / (6.0 * 30 * 30);
  EXPECT_NEAR(m.kn, 0.5 * 1e6 * margin * margin, 1e-12 * m.kn);
  EXPECT_DOUBLE_EQ(m.gamma_n_continuum, damping_for_restitution(0.9, m.kn, 0.5));
  EXPECT_LT(m.gamma_n, m.gamma_n_continuum);
  EXPECT_GT(m.gamma_n, 0.99 * m.gamma_n_continuum);
  EXPECT_DOUBLE_EQ(m.contact_time, contact_duration(m.kn, m.gamma_n, 0.5));
  EXPECT_DOUBLE_EQ(m.dt, m.contact_time / 30);
  EXPECT_EQ(m.restitution, 0.9);
  EXPECT_EQ(m.mass, 1.0);
  EXPECT_EQ(m.diameter, 1.0);
  // tc ~ pi delta_max / u_max: the hard-disk limit.
  EXPECT_NEAR(m.contact_time, kPi * 0.01 / 10.0, 0.01 * m.contact_time);

  ContactSpec plain = spec;
  plain.discrete_correction = false;
  EXPECT_EQ(make_contact_model(plain).gamma_n, make_contact_model(plain).gamma_n_continuum);

  ContactSpec elastic = spec;
  elastic.restitution = 1.0;
  const ContactModel e = make_contact_model(elastic);
  EXPECT_EQ(e.gamma_n, 0.0);
  EXPECT_DOUBLE_EQ(e.contact_time, kPi * std::sqrt(0.5 / e.kn));

  // Mass and diameter enter through m_eff and the overlap bound.
  ContactSpec heavy = spec;
  heavy.mass = 4.0;
  heavy.diameter = 2.0;
  heavy.max_overlap = 0.02;
  const ContactModel h = make_contact_model(heavy);
  EXPECT_NEAR(h.kn, 2.0 * std::pow(10.0 / 0.02, 2) * margin * margin, 1e-9 * h.kn);
  EXPECT_NEAR(leapfrog_restitution(h.gamma_n, h.kn, 2.0, h.dt), 0.9, 1e-12);
}

TEST(ContactModel, VerletOverlapStaysBelowTheBoundAtTheFastestSpeed) {
  // The kn margin covers the discrete overshoot of the contact start (worst for r = 1).
  for (const double r : {0.5, 0.98, 1.0}) {
    for (const int n : {10, 30}) {
      ContactSpec spec = test_contact_spec();
      spec.restitution = r;
      spec.steps_per_contact = n;
      const ContactModel m = make_contact_model(spec);
      double peak = 0.0;
      for (int k = 0; k < 128; ++k)
        peak =
            std::max(peak, verlet_contact(m, spec.max_relative_speed, (k + 0.5) / 128).max_overlap);
      EXPECT_LE(peak, spec.max_overlap) << "r = " << r << ", n = " << n;
      EXPECT_GT(peak, (r == 1.0 ? 0.99 : 0.5) * spec.max_overlap) << "r = " << r;
    }
  }
}

TEST(ContactModel, SpecValidationNamesKeyValueAndRange) {
  ContactSpec s = test_contact_spec();
  s.restitution = 1.2;
  EXPECT_EQ(message_of(s), "md.restitution = 1.2: must be in (0, 1]");
  for (const double bad : {0.0, -0.5, std::numeric_limits<double>::quiet_NaN()}) {
    s.restitution = bad;
    EXPECT_NE(message_of(s).find("md.restitution"), std::string::npos) << bad;
  }
  s = test_contact_spec();
  s.mass = 0.0;
  EXPECT_EQ(message_of(s), "md.mass = 0: must be finite and > 0");
  s = test_contact_spec();
  s.diameter = -1.0;
  EXPECT_EQ(message_of(s), "md.diameter = -1: must be finite and > 0");
  s = test_contact_spec();
  s.max_overlap = 0.0;
  EXPECT_EQ(message_of(s),
            "md.max_overlap = 0: must be in (0, 0.1] (at most 0.1 sigma: the hard-disk limit)");
  s.max_overlap = 0.2;
  EXPECT_NE(message_of(s).find("md.max_overlap = 0.2"), std::string::npos);
  s = test_contact_spec();
  s.max_relative_speed = -3.0;
  EXPECT_EQ(message_of(s), "md.max_relative_speed = -3: must be finite and > 0");
  s.max_relative_speed = std::numeric_limits<double>::infinity();
  EXPECT_EQ(message_of(s), "md.max_relative_speed = inf: must be finite and > 0");
  s = test_contact_spec();
  s.steps_per_contact = 9;
  EXPECT_EQ(message_of(s),
            "md.steps_per_contact = 9: must be an integer in [10, 1000000] (time steps per "
            "contact duration)");
  s.steps_per_contact = 10;
  EXPECT_EQ(message_of(s), "");
  s = test_contact_spec();
  s.restitution = 1.0;
  EXPECT_EQ(message_of(s), "");
  // The case's knobs have no default in a ContactSpec: one left unset is refused by name.
  EXPECT_EQ(message_of(ContactSpec{}), "md.restitution = nan: must be in (0, 1]");
  s = test_contact_spec();
  s.steps_per_contact = ContactSpec{}.steps_per_contact;
  EXPECT_NE(message_of(s).find("md.steps_per_contact = 0"), std::string::npos);
}

TEST(ContactModel, ModelValidationGuardsWhatReachesLammps) {
  const ContactModel good = make_contact_model(test_contact_spec());
  EXPECT_NO_THROW(validate(good));
  auto m = good;
  m.dt = 0.0;
  EXPECT_THROW(validate(m), std::invalid_argument);
  m.dt = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(validate(m), std::invalid_argument);
  m.dt = good.contact_time / 5;  // fewer than 10 steps per contact
  EXPECT_THROW(validate(m), std::invalid_argument);
  m = good;
  m.gamma_n = 2.0 * std::sqrt(good.kn / 0.5);  // critical damping
  EXPECT_THROW(validate(m), std::invalid_argument);
  m = good;
  m.gamma_n = -1.0;
  EXPECT_THROW(validate(m), std::invalid_argument);
  m = good;
  m.kn = std::numeric_limits<double>::infinity();
  EXPECT_THROW(validate(m), std::invalid_argument);
  m = good;
  m.restitution = 0.0;
  EXPECT_THROW(validate(m), std::invalid_argument);
  EXPECT_THROW(pair_style_command(ContactModel{}), std::invalid_argument);
}

TEST(ContactModel, LammpsCommandsHaveFrictionOffAndExactNumbers) {
  const ContactModel m = make_contact_model(test_contact_spec());
  const std::string style = pair_style_command(m);
  std::istringstream in(style);
  std::vector<std::string> t;
  for (std::string w; in >> w;) t.push_back(w);
  ASSERT_EQ(t.size(), 8u) << style;
  EXPECT_EQ(t[0], "pair_style");
  EXPECT_EQ(t[1], "gran/hooke");
  EXPECT_EQ(std::stod(t[2]), m.kn);       // Kn (force/distance), round-trips exactly
  EXPECT_EQ(t[3], "0");                   // Kt: not NULL (NULL = 2/7 Kn)
  EXPECT_EQ(std::stod(t[4]), m.gamma_n);  // gamma_n (1/time)
  EXPECT_EQ(t[5], "0");                   // gamma_t: not NULL (NULL = gamma_n/2)
  EXPECT_EQ(t[6], "0");                   // xmu
  EXPECT_EQ(t[7], "0");                   // dampflag; no limit_damping keyword
  EXPECT_EQ(pair_coeff_command(), "pair_coeff * *");
  const std::string ts = timestep_command(m);
  EXPECT_EQ(ts.rfind("timestep ", 0), 0u);
  EXPECT_EQ(std::stod(ts.substr(9)), m.dt);
  EXPECT_EQ(lammps_number(0.5), "0.5");
  EXPECT_EQ(lammps_number(-2.0), "-2");
  EXPECT_THROW(lammps_number(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_THROW(lammps_number(-std::numeric_limits<double>::infinity()), std::invalid_argument);
}

}  // namespace
