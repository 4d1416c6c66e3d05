// The verdict rule of a comparison (compare/verdict.hpp) on constructed inputs on both sides of
// each threshold, the boundary values included: "model" from signal-to-noise >= 3 (inclusive),
// or from a box-mean offset beyond offset_sigmas (strict); "noise" otherwise; "none" when the
// fields agreed throughout. Also the box-mean offset by hand and the verdict line, word for
// word. All inputs are exact in floating point, so the answers are compared exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "compare/field_metrics.hpp"
#include "compare/side_by_side.hpp"
#include "compare/signal_to_noise.hpp"
#include "compare/verdict.hpp"

namespace {

using granvv::compare::AgreementWindow;
using granvv::compare::box_mean_offset;
using granvv::compare::classify_disagreement;
using granvv::compare::Disagreement;
using granvv::compare::disagreement_name;
using granvv::compare::kClearSignalToNoise;
using granvv::compare::verdict_sentence;
using granvv::compare::VerdictRule;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

const VerdictRule kRule{kClearSignalToNoise, 3.0};  // the defaults of a case: compare.sigmas = 3

TEST(Verdict, ClearSignalThresholdIsThreeAndTheDefault) {
  EXPECT_EQ(kClearSignalToNoise, 3.0);
  EXPECT_EQ(VerdictRule{}.signal_to_noise_min, 3.0);
}

TEST(Verdict, AgreementThroughoutIsNoneWhateverTheSignalOrOffset) {
  EXPECT_EQ(classify_disagreement(true, 100.0, 100.0, kRule), Disagreement::none);
  EXPECT_EQ(classify_disagreement(true, 0.0, 0.0, kRule), Disagreement::none);
}

TEST(Verdict, SignalToNoiseThresholdIsInclusive) {
  const double below = std::nextafter(3.0, 0.0);
  EXPECT_EQ(classify_disagreement(false, 3.0, 0.0, kRule), Disagreement::model_clear_signal);
  EXPECT_EQ(classify_disagreement(false, 7.5, 0.0, kRule), Disagreement::model_clear_signal);
  EXPECT_EQ(classify_disagreement(false, below, 0.0, kRule), Disagreement::noise);
  EXPECT_EQ(classify_disagreement(false, 0.0, 0.0, kRule), Disagreement::noise);
}

TEST(Verdict, BoxOffsetThresholdIsStrictAndTwoSided) {
  const double above = std::nextafter(3.0, kInf);
  EXPECT_EQ(classify_disagreement(false, 1.0, 3.0, kRule), Disagreement::noise);
  EXPECT_EQ(classify_disagreement(false, 1.0, -3.0, kRule), Disagreement::noise);
  EXPECT_EQ(classify_disagreement(false, 1.0, above, kRule), Disagreement::model_box_offset);
  EXPECT_EQ(classify_disagreement(false, 1.0, -above, kRule), Disagreement::model_box_offset);
  EXPECT_EQ(classify_disagreement(false, 1.0, -4.0, kRule), Disagreement::model_box_offset);
}

TEST(Verdict, ClearSignalWinsOverTheOffset) {
  EXPECT_EQ(classify_disagreement(false, 3.0, 10.0, kRule), Disagreement::model_clear_signal);
}

TEST(Verdict, OffsetThresholdIsTheCasesSigmas) {
  // compare.sigmas = 2: an offset of 2.5 standard errors is the model's, of 2 not.
  const VerdictRule two{kClearSignalToNoise, 2.0};
  EXPECT_EQ(classify_disagreement(false, 1.0, 2.5, two), Disagreement::model_box_offset);
  EXPECT_EQ(classify_disagreement(false, 1.0, 2.0, two), Disagreement::noise);
  EXPECT_EQ(classify_disagreement(false, 1.0, 2.5, kRule), Disagreement::noise);
}

TEST(Verdict, NaNCountsAsBelowEveryThreshold) {
  EXPECT_EQ(classify_disagreement(false, kNaN, kNaN, kRule), Disagreement::noise);
}

TEST(Verdict, NamesOfTheKinds) {
  EXPECT_STREQ(disagreement_name(Disagreement::none), "none");
  EXPECT_STREQ(disagreement_name(Disagreement::model_clear_signal), "model");
  EXPECT_STREQ(disagreement_name(Disagreement::model_box_offset), "model");
  EXPECT_STREQ(disagreement_name(Disagreement::noise), "noise");
}

TEST(Verdict, BoxMeanOffsetInStandardErrorsOfTheMean) {
  // d = hydro - md = 1 in four bins with unit errors: sum d = 4, sqrt(sum e^2) = 2 -> 2.
  EXPECT_EQ(box_mean_offset({1, 2, 3, 4}, {0, 1, 2, 3}, {1, 1, 1, 1}), 2.0);
  // Differences of both signs cancel: d = {3, -1}, e = {3, 4}: 2 / 5.
  EXPECT_EQ(box_mean_offset({3, 0}, {0, 1}, {3, 4}), 2.0 / 5.0);
  // Left out: a NaN difference (empty bin), a zero and a NaN error. Kept: d = -3, e = 1.5 ->
  // -3 / 1.5 = -2.
  EXPECT_EQ(box_mean_offset({kNaN, 5, 5, 0}, {0, 0, 0, 3}, {1, 0, kNaN, 1.5}), -2.0);
  // Nothing usable: 0.
  EXPECT_EQ(box_mean_offset({1, 2}, {0, 0}, {0, kNaN}), 0.0);
}

TEST(Verdict, SentenceForEachWindowAndKind) {
  AgreementWindow all;
  all.throughout = true;
  all.until = 2.5;
  EXPECT_EQ(verdict_sentence(all, 2.5, 3.0, 0.5, 0.0, Disagreement::none),
            "fields agree within 3 sigma at every compared time up to t = 2.5 [signal/noise 0.5]");

  AgreementWindow parted;
  parted.until = 1.0;
  parted.left_at = 2.0;
  parted.first_out = "T";
  EXPECT_EQ(verdict_sentence(parted, 4.0, 3.0, 1.25, 0.0, Disagreement::noise),
            "fields agree within 3 sigma until t = 1; first to part: T (at t = 2) [signal/noise "
            "1.25: the imposed flow is not well above the particles' noise and the box means "
            "agree, so the difference is noise-driven, not a failure of the hydro]");
  EXPECT_EQ(verdict_sentence(parted, 4.0, 3.0, 1.25, -4.5, Disagreement::model_box_offset),
            "fields agree within 3 sigma until t = 1; first to part: T (at t = 2) [signal/noise "
            "1.25; the box mean of T is off by -4.5 standard errors, which zero-mean noise "
            "cannot make: the difference is the hydro's]");

  AgreementWindow never;
  never.left_at = 0.5;
  never.first_out = "v_x";
  EXPECT_EQ(verdict_sentence(never, 4.0, 2.0, 12.0, 0.0, Disagreement::model_clear_signal),
            "fields differ beyond 2 sigma from the first compared time; worst: v_x [signal/noise "
            "12: the signal is clear of the noise, so the difference is the hydro's]");

  // Four significant digits.
  EXPECT_EQ(verdict_sentence(AgreementWindow{}, kNaN, 3.0, 1.0 / 3.0, 0.0, Disagreement::noise)
                .substr(0, 43),
            "no common output time [signal/noise 0.3333:");
}

// The side-by-side judgement end to end on series built by hand: 8 bins, the particles' T = 1
// with a standard error of 0.01 in every bin at t = 0, 1, 2; a hydro equal to them at t = 0 and
// 1 and 5 % hotter everywhere at t = 2 (5 standard errors, in every bin) parts at t = 2, and
// its box mean is off by 5 sqrt(8) = 14 errors of that mean: a model disagreement, without
// any imposed signal. The same hydro with an offset of 0.5 % (0.5 errors) agrees throughout.
TEST(SideBySide, AUniformOffsetBeyondTheErrorsIsTheModels) {
  using granvv::fields::FieldSeries;
  using granvv::fields::FieldSnapshot;
  auto series = [](double hot_at_2, bool errors) {
    FieldSeries f = FieldSeries::on_bins(-0.5, 1.0, 8);
    for (double t : {0.0, 1.0, 2.0}) {
      FieldSnapshot s;
      s.t = t;
      s.label = "output";
      for (int b = 0; b < 8; ++b) s.x.push_back(-0.5 + (b + 0.5) / 8);
      s.n.assign(8, 1.0);
      s.v_x.assign(8, 0.0);
      s.T.assign(8, t == 2.0 ? 1.0 + hot_at_2 : 1.0);
      if (errors) {
        s.n_stderr.assign(8, 0.01);
        s.v_x_stderr.assign(8, 0.01);
        s.T_stderr.assign(8, 0.01);
      }
      f.snapshots.push_back(s);
    }
    return f;
  };
  const FieldSeries particles = series(0.0, true);
  const VerdictRule rule{kClearSignalToNoise, 3.0};
  const auto parted = granvv::compare::judge_side_by_side(particles, series(0.05, false),
                                                          {"n", "v_x", "T"}, 3.0, 0.9, 0.0, rule);
  EXPECT_EQ(parted.t, (std::vector<double>{0.0, 1.0, 2.0}));
  EXPECT_FALSE(parted.window.throughout);
  EXPECT_EQ(parted.window.until, 1.0);
  EXPECT_EQ(parted.window.first_out, "T");
  EXPECT_NEAR(parted.offset_sigmas, 5.0 * std::sqrt(8.0), 1e-9);
  EXPECT_EQ(parted.kind, Disagreement::model_box_offset);
  const auto close = granvv::compare::judge_side_by_side(particles, series(0.005, false),
                                                         {"n", "v_x", "T"}, 3.0, 0.9, 0.0, rule);
  EXPECT_TRUE(close.window.throughout);
  EXPECT_EQ(close.kind, Disagreement::none);
}

}  // namespace

namespace {

// A comparison on 8 bins at two times where only v_y parts: the particles' v_y = 0.4 sin 2 pi x
// with error 0.01 at every bin, the hydro's half of it; n, v_x and T equal.
granvv::fields::FieldSeries shear_fields(double amplitude) {
  auto f = granvv::fields::FieldSeries::on_bins(-0.5, 1.0, 8);
  for (double t : {0.0, 1.0}) {
    granvv::fields::FieldSnapshot s;
    s.t = t;
    for (int b = 0; b < 8; ++b) {
      const double x = -0.5 + (b + 0.5) / 8;
      s.x.push_back(x);
      s.n.push_back(1.0), s.v_x.push_back(0.0), s.T.push_back(1.0), s.count.push_back(64);
      s.v_y.push_back(amplitude * std::sin(2 * M_PI * x));
      s.n_stderr.push_back(0.01), s.v_x_stderr.push_back(0.01), s.T_stderr.push_back(0.01);
      s.v_y_stderr.push_back(0.01);
    }
    f.snapshots.push_back(s);
  }
  return f;
}

TEST(Verdict, TransverseOnlyDisagreementWithAClearShearWaveIsTheModels) {
  using granvv::compare::compared_fields;
  using granvv::compare::judge_side_by_side;
  using granvv::compare::largest_flow_component;
  using granvv::compare::velocity_signal_to_noise;
  const auto none = [](double) { return 0.0; };
  const auto shear = [](double x) { return 0.4 * std::sin(2 * M_PI * x); };
  // n0 = 1, Ly = 32, Lx = 16 on 8 bins: n0 Ly l = 64, noise 1/8; the signal is the largest v_y on
  // the 4096 profile centres, 0.4 cos(pi/4096): S/N 3.2 cos(pi/4096) (a few roundings).
  const double ratio =
      velocity_signal_to_noise(largest_flow_component(none, shear), 1.0, 32.0, 16.0, 8).ratio();
  EXPECT_NEAR(ratio, 3.2 * std::cos(M_PI / 4096), 1e-14);
  // Without v_y the same scene had no signal at all.
  EXPECT_EQ(velocity_signal_to_noise(largest_flow_component(none, {}), 1.0, 32.0, 16.0, 8).ratio(),
            0.0);
  const auto judged = judge_side_by_side(shear_fields(0.4), shear_fields(0.2),
                                         compared_fields(true), 3.0, 0.95, ratio, kRule);
  EXPECT_EQ(judged.window.first_out, "v_y");
  EXPECT_NEAR(judged.offset_sigmas, 0.0, 1e-12);  // a sine has no box mean: it cannot tell
  EXPECT_STREQ(disagreement_name(judged.kind), "model");
  // Judged with the old, v_y-blind signal (0) the same difference was noise.
  const auto blind = judge_side_by_side(shear_fields(0.4), shear_fields(0.2), compared_fields(true),
                                        3.0, 0.95, 0.0, kRule);
  EXPECT_STREQ(disagreement_name(blind.kind), "noise");
}

}  // namespace
