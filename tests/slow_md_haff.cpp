// Long particle run (ctest -L slow): homogeneous cooling of 4000 disks (2 seeds) against
// Haff's law with t0 from kinetic theory. The measured t0 must be within 3 % of the Enskog
// value t0 = 2 / (sqrt(pi) (1 - r^2) chi(phi) n sigma sqrt(T0/m)) and clearly away from the
// dilute one (chi = 1, 8 % off at phi = 0.05): the test resolves the density correction.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "support/cli_runner.hpp"

namespace granvv::md {
namespace {

TEST(SlowMdHaff, CoolingTimeMatchesEnskogKineticTheory) {
  const auto dir = granvv::testing::fresh_directory("slow-md-haff");
  const auto r = granvv::testing::run_cli(
      "run md_haff --quiet --no-report --set md.particles=4000 --set md.box_width=250.7 "
      "--set md.ensemble=2 --set md.t_end=60 --out " +
      dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto md = nlohmann::json::parse(granvv::testing::read_text(dir / "summary.json"))["md"];
  const double t0 = md["haff_t0_measured"], err = md["haff_t0_measured_error"];
  const double chi = md["haff_t0_theory"], dilute = md["haff_t0_theory_dilute"];
  EXPECT_LT(std::abs(t0 / chi - 1.0), 0.03) << t0 << " +- " << err << " vs " << chi;
  EXPECT_GT(std::abs(t0 / dilute - 1.0), 0.03) << t0 << " vs dilute " << dilute;
  EXPECT_NEAR(md["restitution_measured"].get<double>(), 0.9, 1e-3);
}

}  // namespace
}  // namespace granvv::md
