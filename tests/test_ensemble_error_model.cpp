// The error of an ensemble-mean field (compare/ensemble_error_model.hpp) against values worked
// out by hand: the pooled variance ratio R = mean_b k_b SE_b^2 / model_b^2 and the error
// model_b sqrt(R / k_b). The inputs are dyadic where possible, so most answers are exact in
// floating point (EXPECT_EQ); where a square root of a non-square enters, the tolerance is a
// few ulps (1e-15 relative).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "compare/ensemble_error_model.hpp"
#include "compare/ensemble_statistics.hpp"

namespace {

using granvv::compare::ensemble_mean_error;
using granvv::compare::EnsembleMeanError;
using granvv::compare::EnsembleStatistics;
using granvv::compare::error_source_label;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

EnsembleStatistics statistics(std::vector<double> standard_error, std::vector<int> members) {
  EnsembleStatistics s;
  s.mean.assign(standard_error.size(), 0.0);  // the error model does not read the mean
  s.standard_error = std::move(standard_error);
  s.members = std::move(members);
  return s;
}

TEST(EnsembleErrorModel, FourTimesTheModelVarianceDoublesTheModelErrorOverRootK) {
  // k = 4 members in every bin; the observed one-member variance k SE^2 is 4 model^2 in each
  // bin: SE_b = 2 model_b / sqrt(4) = model_b. So R = 4 and error_b = model_b sqrt(4 / 4) =
  // 2 model_b / sqrt(k) = model_b.
  const std::vector<double> model = {1.0, 2.0, 0.5};
  const EnsembleMeanError e = ensemble_mean_error(model, statistics({1.0, 2.0, 0.5}, {4, 4, 4}));
  EXPECT_TRUE(e.calibrated);
  EXPECT_EQ(e.members, 4);
  EXPECT_EQ(e.variance_ratio, 4.0);
  ASSERT_EQ(e.error.size(), 3u);
  for (std::size_t b = 0; b < model.size(); ++b) EXPECT_EQ(e.error[b], 2.0 * model[b] / 2.0);
  EXPECT_EQ(error_source_label(e), "ensemble of 4 (model error x 2)");
}

TEST(EnsembleErrorModel, RatioIsPooledOverBinsNotTakenBinByBin) {
  // Bin 0: k = 2, SE = 1, model 1: ratio 2 * 1 / 1 = 2. Bin 1: k = 2, SE = 2, model 1: ratio
  // 2 * 4 / 1 = 8. R = (2 + 8) / 2 = 5, the same for both bins: error_b = 1 * sqrt(5 / 2).
  const EnsembleMeanError e = ensemble_mean_error({1.0, 1.0}, statistics({1.0, 2.0}, {2, 2}));
  EXPECT_EQ(e.variance_ratio, 5.0);
  EXPECT_NEAR(e.error[0], std::sqrt(2.5), 1e-15 * std::sqrt(2.5));
  EXPECT_EQ(e.error[0], e.error[1]);
  EXPECT_EQ(error_source_label(e), "ensemble of 2 (model error x 2.23607)");  // sqrt 5, 6 digits
}

TEST(EnsembleErrorModel, BinsWithoutModelOrScatterStayOutOfTheRatio) {
  // Only bin 0 enters R: k = 4, SE = 1.5, model 1 -> R = 4 * 2.25 = 9, sqrt R = 3.
  //   bin 1: one member (k < 2)          -> not pooled; error 2 * sqrt(9 / 1) = 6
  //   bin 2: NaN standard error          -> not pooled; error 1 * sqrt(9 / 4) = 1.5
  //   bin 3: model 0 (no error model)    -> not pooled; error 0
  //   bin 4: NaN model (an empty bin)    -> not pooled; error NaN
  //   bin 5: no member at all (k = 0)    -> not pooled; error 1 * sqrt(9 / max(1, 0)) = 3
  const EnsembleMeanError e =
      ensemble_mean_error({1.0, 2.0, 1.0, 0.0, kNaN, 1.0},
                          statistics({1.5, kNaN, kNaN, 0.5, 0.5, kNaN}, {4, 1, 4, 4, 4, 0}));
  EXPECT_EQ(e.variance_ratio, 9.0);
  EXPECT_EQ(e.members, 4);
  EXPECT_EQ(e.error[0], 1.5);
  EXPECT_EQ(e.error[1], 6.0);
  EXPECT_EQ(e.error[2], 1.5);
  EXPECT_EQ(e.error[3], 0.0);
  EXPECT_TRUE(std::isnan(e.error[4]));
  EXPECT_EQ(e.error[5], 3.0);
}

TEST(EnsembleErrorModel, SingleMemberKeepsTheSnapshotModel) {
  // One member: no standard error anywhere, so no calibration: R = 1 and error = model.
  const std::vector<double> model = {0.25, 0.5, 0.75};
  const EnsembleMeanError e = ensemble_mean_error(model, statistics({kNaN, kNaN, kNaN}, {1, 1, 1}));
  EXPECT_FALSE(e.calibrated);
  EXPECT_EQ(e.variance_ratio, 1.0);
  EXPECT_EQ(e.members, 1);
  EXPECT_EQ(e.error, model);
  EXPECT_EQ(error_source_label(e), "single-snapshot model");
}

}  // namespace
