// Small eigenmodes of the homogeneous cooling state evolved by the full nonlinear Lagrangian
// scheme, against the rates of the dispersion relation (hydro/linear_stability.hpp), for
// unstable and stable modes k <= 20 and all three branches, and the transverse shear mode; the
// same for the Enskog closure at phi0 = 0.2 with the exact cooling rate (its own dispersion
// relation, docs/physics.md §9), and for the dilute closure with a heat flux -mu dn/dx
// (hydro/closure.hpp), which tests the operator's mu term against the linear theory's.
// Tolerance 1e-3 relative: the spatial error of the scheme is (kx h)^2/12 = 3e-4 at k = 20
// on 2000 cells, the temporal error (omega dt)^2/12 < 1e-4 at cfl = 0.5, and the nonlinear
// correction is of the order of the amplitude 1e-6.
#include <gtest/gtest.h>

#include <cmath>

#include "hydro/dilute_closure.hpp"
#include "hydro/driver.hpp"
#include "hydro/enskog_closure.hpp"
#include "hydro/haff.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "hydro/linear_mode_measurement.hpp"
#include "hydro/linear_stability.hpp"
#include "support/run_control.hpp"

namespace granvv::hydro {
namespace {

const Physics kPhysics{0.01, 0.01};  // modes 1-3 unstable: pi k K < sqrt(q) = 0.1
const DiluteClosure kClosure(kPhysics);
const EnskogClosure kEnskog(kPhysics, 0.2, CoolingRate::exact);

// The dilute closure with a heat flux -mu dn/dx, mu = mu0 T^{3/2} (the hard-disk scaling of mu
// at fixed n, hydro/closure.hpp; only mu(1, T_H) enters the linear theory). mu0 = 0.3 K is about
// Garzo & Dufty's dilute mu at r = 0.8 (docs/physics.md §9), large enough that every rate
// below moves by well over the tolerance (checked in MuMovesTheRates).
class DiluteWithMu final : public Closure {
 public:
  DiluteWithMu(const Physics& physics, double mu0) : dilute_(physics), mu0_(mu0) {}
  std::string name() const override { return "dilute_with_mu"; }
  void cell_coefficients(const std::vector<double>& n, const std::vector<double>& T,
                         CellCoefficients& out) const override {
    dilute_.cell_coefficients(n, T, out);
    for (size_t i = 0; i < n.size(); ++i) out.mu[i] = mu0_ * T[i] * std::sqrt(T[i]);
  }
  void sound_speed(const std::vector<double>& n, const std::vector<double>& T,
                   std::vector<double>& c) const override {
    dilute_.sound_speed(n, T, c);
  }
  void cooling_rate(const std::vector<double>& n, const std::vector<double>& T,
                    std::vector<double>& rate) const override {
    dilute_.cooling_rate(n, T, rate);
  }
  void cool(const std::vector<double>& n, const std::vector<double>& T, double dt,
            std::vector<double>& cooled) const override {
    dilute_.cool(n, T, dt, cooled);
  }
  HcsLinearisation hcs_linearisation() const override {
    HcsLinearisation h = dilute_.hcs_linearisation();
    h.mu = mu0_;
    // p_n = p_T = 1: the clustering mode grows while (kappa - mu) kx^2 < Lambda_n - Lambda_T'.
    const double kx2 = (h.cooling_density - h.cooling_temperature) / (h.conductivity - h.mu);
    h.clustering_cutoff_mode = std::sqrt(kx2) / (2.0 * M_PI);
    return h;
  }
  ValidityScales validity_scales() const override { return dilute_.validity_scales(); }

 private:
  DiluteClosure dilute_;
  double mu0_;
};
const DiluteWithMu kWithMu(kPhysics, 0.3 * kPhysics.K);

const Closure& closure_named(const std::string& name) {
  if (name == "enskog") return kEnskog;
  if (name == "dilute_with_mu") return kWithMu;
  return kClosure;
}

// Run until the mode has grown or decayed by about e^3 (at most s = 0.4), sampling so that
// the phase advances by less than 0.3 rad between samples.
std::vector<LagrangianState> evolve(const Closure& closure, const InitialFields& fields,
                                    std::complex<double> rate, int cells, bool transverse = false) {
  const double t0 = haff_time_scale(closure);
  const double s_end = std::min(0.4, 3.0 / std::abs(rate.real()));
  const int samples = std::max(20, int(std::ceil(s_end * std::abs(rate.imag()) / 0.3)));
  auto time_of = [t0](double s) { return t0 * std::expm1(s / t0); };
  RunControl control = testing::run_control(time_of(s_end), 0.5);
  for (int i = 1; i <= samples; ++i) control.output_times.push_back(time_of(s_end * i / samples));
  const RunResult r = run_hydro(closure, discretize(fields, cells, 0.5, transverse), control);
  EXPECT_EQ(r.status, RunStatus::completed) << r.stop_reason;
  std::vector<LagrangianState> states;
  for (const auto& snap : r.snapshots) states.push_back(snap.state);
  return states;
}

class LinearGrowth : public ::testing::TestWithParam<std::tuple<std::string, int, int>> {};

TEST_P(LinearGrowth, RateMatchesDispersionRelation) {
  const auto [name, k, branch] = GetParam();
  const Closure& closure = closure_named(name);
  const ParameterSet linear_mode = {
      {"mode", (long long)k}, {"linear_branch", (long long)branch}, {"linear_amplitude", 1e-6}};
  const auto modes = hcs_modes(closure, k);
  const int cells = k <= 5 ? 1000 : 2000;
  const auto states =
      evolve(closure, find_initial_condition("linear_mode").generate(linear_mode, closure),
             modes[branch].rate, cells);
  const MeasuredRate r = measure_linear_rate(states, closure, k, branch);
  EXPECT_LT(r.relative_error, 1e-3) << "k = " << k << " branch " << branch << ": measured "
                                    << r.measured << ", theory " << r.theory;
  if (branch == 0) {
    // The sign of the leading rate is the instability criterion (dilute: pi k K < sqrt(q)).
    EXPECT_EQ(r.measured.real() > 0, k <= clustering_unstable_modes(closure));
    if (name == "dilute") {
      EXPECT_EQ(k <= clustering_unstable_modes(closure),
                M_PI * k * kPhysics.K < std::sqrt(kPhysics.q));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(UnstableAndStable, LinearGrowth,
                         ::testing::Combine(::testing::Values("dilute"),
                                            ::testing::Values(1, 2, 3, 4, 6, 10, 20),
                                            ::testing::Values(0, 1, 2)));
INSTANTIATE_TEST_SUITE_P(DiluteWithMu, LinearGrowth,
                         ::testing::Combine(::testing::Values("dilute_with_mu"),
                                            ::testing::Values(1, 2, 3, 4, 10),
                                            ::testing::Values(0, 1, 2)));
INSTANTIATE_TEST_SUITE_P(Enskog, LinearGrowth,
                         ::testing::Combine(::testing::Values("enskog"),
                                            ::testing::Values(1, 2, 4, 10),
                                            ::testing::Values(0, 1, 2)));

TEST(LinearGrowth, MuMovesTheRates) {
  // The heat flux -mu dn/dx changes the dispersion relation by at least three times the runs'
  // tolerance (so the runs above test the operator's mu term; the least moved is k = 1's sound
  // pair, by 0.4 %), and with it the clustering cutoff: with
  // K = 0.01, q = 0.01 and mu = 0.3 K it moves from sqrt(q)/(pi K) = 3.18 to 3.18/sqrt(0.7) =
  // 3.80, still between modes 3 and 4.
  for (int k : {1, 2, 3, 4, 10}) {
    const auto with = hcs_modes(kWithMu, k), without = hcs_modes(kClosure, k);
    for (int branch = 0; branch < 3; ++branch) {
      EXPECT_GT(std::abs(with[branch].rate - without[branch].rate),
                3 * kLinearRateTolerance * std::abs(with[branch].rate))
          << "k = " << k << " branch " << branch;
    }
  }
  EXPECT_NEAR(clustering_cutoff_mode(kWithMu), clustering_cutoff_mode(kClosure) / std::sqrt(0.7),
              1e-12);
  // The cutoff is where det A changes sign (hydro/linear_stability.hpp).
  const double kx = 2 * M_PI * clustering_cutoff_mode(kWithMu);
  EXPECT_GT(hcs_linear_operator_kx(kWithMu, kx * (1 - 1e-6)).determinant().real(), 0.0);
  EXPECT_LT(hcs_linear_operator_kx(kWithMu, kx * (1 + 1e-6)).determinant().real(), 0.0);
}

TEST(LinearGrowth, ShearModeOfTransverseVelocity) {
  for (int k : {1, 3, 6, 12}) {  // shear-unstable iff pi k K < 2 sqrt(q): k <= 6
    InitialFields fields = uniform_fields();
    const double kx = 2 * M_PI * k;
    fields.vy = [kx](double x) { return 1e-6 * std::cos(kx * x); };
    const double rate = shear_rate(kPhysics, k);
    const auto states = evolve(kClosure, fields, rate, 1000, true);
    // Fourier amplitude of w_y = v_y / T_H^{1/2} against e^{rate s}.
    const double t0 = haff_time_scale(kPhysics);
    auto amplitude = [&](const LagrangianState& s) {
      double a = 0;
      for (int j = 0; j < s.cells(); ++j)
        a += 2.0 * s.node_vy[j] * std::cos(kx * s.node_x[j]) / s.cells();
      return a / std::sqrt(haff_temperature(s.t, t0));
    };
    const double s_end = collision_clock(states.back().t, t0);
    const double measured = std::log(amplitude(states.back()) / amplitude(states.front())) / s_end;
    EXPECT_NEAR(measured, rate, 1e-3 * std::abs(rate)) << "k = " << k;
    EXPECT_EQ(measured > 0, M_PI * k * kPhysics.K < 2 * std::sqrt(kPhysics.q));
  }
}

}  // namespace
}  // namespace granvv::hydro
