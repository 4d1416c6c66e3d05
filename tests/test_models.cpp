// The ladder's models behind one interface (models/model.hpp) and any two of them compared
// (compare/model_comparison.hpp), against exact answers: the hydro's homogeneous cooling state
// is Haff's law to round-off (its cooling step is exact), flow by inertia conserves mass and
// keeps its singularity time 1/(2 pi |a|), and a model compared with itself differs nowhere.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "compare/model_comparison.hpp"
#include "fields/constants.hpp"
#include "models/model.hpp"
#include "scene/case_config.hpp"

namespace granvv::app {
namespace {

HydroScene scene_of(const std::string& file, const std::vector<std::string>& sets) {
  return hydro_scene_from(
      CaseConfig::from_file(std::string(GRANVV_SOURCE_DIR) + "/cases/" + file, sets));
}

TEST(Models, HydroCoolingStateIsHaffsLawToRoundOff) {
  // cases/haff.toml: n = T = 1, v = 0 at K = 4e-4, q = 0.01, snapshots at 0.01, 0.1, 1.
  // The uniform state stays uniform, and the scheme's cooling step integrates dT/dt exactly, so
  // every bin's T is (1 + t/t0)^-2 to round-off: 1e-12 relative (64 cells, steps of ~1e-3).
  HydroModel hydro(scene_of("haff.toml", {}), 8);
  EXPECT_EQ(hydro.name(), "hydro/dilute");
  const fields::ModelResult h = hydro.run();
  const fields::ModelResult haff =
      make_haff_model(scene_of("haff.toml", {}).physics, {0.01, 0.1, 1.0}, 8)->run();
  EXPECT_EQ(haff.model, "haff_ode");
  const compare::ModelComparison c = compare::compare_models(haff, h, 3.0);
  ASSERT_EQ(c.t.size(), 3u) << "every Haff time is a hydro snapshot";
  ASSERT_EQ(c.fields.size(), 4u);  // n, v_x, v_y (zero on both sides), T
  for (const auto& track : c.fields) {
    for (const auto& d : track.at) EXPECT_LT(d.linf, 1e-12) << track.field;
  }
  const fields::Observable* t0 = h.observable("haff_t0");
  ASSERT_NE(t0, nullptr);
  EXPECT_DOUBLE_EQ(t0->value, 4e-4 / (4 * 0.01));
  bool compared_t0 = false;
  for (const auto& o : c.observables) {
    if (o.name != "haff_t0") continue;
    compared_t0 = true;
    EXPECT_EQ(o.relative, 0.0);
  }
  EXPECT_TRUE(compared_t0);
  EXPECT_EQ(h.cost.work_unit, "cell_steps");
  EXPECT_GT(h.cost.work, 64.0) << "at least one step of 64 cells";
  EXPECT_TRUE(hydro.outcome().run.status == hydro::RunStatus::completed);
}

TEST(Models, FlowByInertiaConservesMassAndStopsBeforeItsSingularity) {
  // The single mode v0 = a sin(2 pi x), a = -0.05: trajectories cross first at
  // tau = 1/(2 pi |a|) = 3.1831 (paper Eq. 6). Bins hold the whole unit mass at every time
  // (masses by the midpoint rule, binned exactly: 1e-12), and no snapshot is made at or after
  // 0.999 tau, where one bin's density diverges.
  const HydroScene s = scene_of("single_mode.toml", {"convergence.cells=[]"});
  const double tau = 1.0 / (2 * kPi * 0.05);
  const fields::ModelResult r =
      make_inertia_model(s.initial, s.physics, {0.0, 1.0, 3.0, 0.9995 * tau, 4.0}, 50)->run();
  ASSERT_TRUE(r.fields);
  ASSERT_EQ(r.fields->snapshots.size(), 3u);
  for (const auto& snap : r.fields->snapshots) {
    double mass = 0.0;
    for (double n : snap.n) mass += n / 50;
    EXPECT_NEAR(mass, 1.0, 1e-12) << "t = " << snap.t;
    EXPECT_TRUE(snap.T.empty()) << "flow by inertia has no temperature";
  }
  // At t = 0 every bin moves with its mean initial velocity: the bin average of a sin 2 pi x.
  const auto& first = r.fields->snapshots.front();
  for (int b = 0; b < 50; ++b) {
    const double lo = -0.5 + b / 50.0, hi = lo + 1 / 50.0;
    const double mean = -0.05 * (std::cos(2 * kPi * lo) - std::cos(2 * kPi * hi)) / (2 * kPi) * 50;
    EXPECT_NEAR(first.v_x[b], mean, 1e-6) << "bin " << b;
  }
  const fields::Observable* t = r.observable("singularity_time");
  ASSERT_NE(t, nullptr);
  EXPECT_NEAR(t->value, tau, 1e-12);
  // A uniform state has no flow-by-inertia reference.
  const HydroScene uniform = scene_of("haff.toml", {});
  EXPECT_THROW(make_inertia_model(uniform.initial, uniform.physics, {0.0}, 8), ConfigError);
}

TEST(Models, AModelAgainstItselfDiffersNowhereAndOtherBinsAreNotCompared) {
  const HydroScene s = scene_of("single_mode.toml", {"convergence.cells=[]"});
  const fields::ModelResult a = make_inertia_model(s.initial, s.physics, {0.0, 1.0}, 20)->run();
  const compare::ModelComparison same = compare::compare_models(a, a, 3.0);
  ASSERT_EQ(same.t.size(), 2u);
  ASSERT_EQ(same.fields.size(), 3u) << "n, v_x, v_y: flow by inertia has no T";
  for (const auto& track : same.fields) {
    for (const auto& d : track.at) EXPECT_EQ(d.linf, 0.0) << track.field;
  }
  ASSERT_EQ(same.observables.size(), 1u);
  EXPECT_EQ(same.observables[0].relative, 0.0);
  EXPECT_TRUE(std::isnan(same.observables[0].sigmas)) << "no standard errors: no sigmas";

  const fields::ModelResult b = make_inertia_model(s.initial, s.physics, {0.0, 1.0}, 25)->run();
  EXPECT_TRUE(compare::compare_models(a, b, 3.0).fields.empty()) << "20 bins against 25";
  EXPECT_THROW(compare::compare_field_series(*a.fields, *b.fields, {{0, 0}}, {"n"}, 3.0),
               std::invalid_argument);
}

}  // namespace
}  // namespace granvv::app
