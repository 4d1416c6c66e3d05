// The suite guards its own physics: the restitution sweep of homogeneous cooling
// (cases/md_cooling_sweep.toml, 7 values of r, 4 seeds each, about 2.5 min on 2 cores) against
// the stored baseline tests/baselines/cooling_sweep.json, made by the same command on the code
// whose restitution mapping was verified in LAMMPS.
//
// Tolerance: a point fails when its measured Haff time moves from the baseline by more than
// tolerance_sigmas (3) combined standard errors, sqrt(err^2 + err_baseline^2). On the machine
// that made the baseline the runs are bit-for-bit repeatable (fixed seeds, one rank), so the real
// code passes exactly. On another platform the trajectories decorrelate and the two runs become
// independent samples: with Gaussian errors 3 combined errors gives a false alarm on one of the 7
// points 2 % of the time, but errors estimated from 4 seeds have heavier tails (a few per cent
// per point), so regenerate the baseline there rather than widen the tolerance. A restitution
// mapping broken by 2 % moves t0 by 1-7 % at r = 0.5-0.8 (within or near the tolerance there)
// and by 17-95 % at r >= 0.9 (t0 ~ 1/(1 - r^2)), far beyond it.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/cli_runner.hpp"

namespace granvv::compare {
namespace {

using nlohmann::json;

TEST(CoolingRegression, RestitutionSweepMatchesStoredBaseline) {
  const json baseline = json::parse(granvv::testing::read_text(
      std::string(GRANVV_SOURCE_DIR) + "/tests/baselines/cooling_sweep.json"));
  std::ostringstream values;
  for (std::size_t i = 0; i < baseline["points"].size(); ++i) {
    values << (i ? "," : "") << baseline["points"][i]["restitution"].get<double>();
  }
  const auto dir = granvv::testing::fresh_directory("cooling-regression");
  const auto r = granvv::testing::run_cli(
      "sweep " + baseline["case"].get<std::string>() +
      " --quiet --no-report --set md.restitution=" + values.str() + " --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json sweep = json::parse(granvv::testing::read_text(dir / "sweep.json"));
  const json& measured = sweep["cooling"]["points"];
  ASSERT_EQ(measured.size(), baseline["points"].size()) << sweep.dump(2);
  const double k = baseline["tolerance_sigmas"];
  for (std::size_t i = 0; i < measured.size(); ++i) {
    const json& m = measured[i];
    const json& b = baseline["points"][i];
    SCOPED_TRACE("r = " + std::to_string(b["restitution"].get<double>()));
    EXPECT_DOUBLE_EQ(m["restitution"].get<double>(), b["restitution"].get<double>());
    const double t0 = m["t0"], err = m["t0_error"], t0_b = b["t0"], err_b = b["t0_error"];
    const double combined = std::hypot(err, err_b);
    EXPECT_LE(std::abs(t0 - t0_b), k * combined)
        << "t0 = " << t0 << " +- " << err << " against the baseline " << t0_b << " +- " << err_b
        << ": moved by " << std::abs(t0 - t0_b) / combined << " combined standard errors";
  }
  // The physics the baseline stands for (issue acceptance): zeta ~ (1 - r^2)^p with p within
  // 0.1 of kinetic theory's 1 over r >= 0.7.
  const json& power = sweep["cooling"]["power_of_one_minus_r2"];
  ASSERT_TRUE(power.is_object()) << sweep.dump(2);
  EXPECT_NEAR(power["power"].get<double>(), 1.0, 0.1);
  EXPECT_NEAR(
      power["power"].get<double>(), baseline["power"].get<double>(),
      k * std::hypot(power["power_error"].get<double>(), baseline["power_error"].get<double>()));
}

}  // namespace
}  // namespace granvv::compare
