// The atlas as a library (atlas/atlas_judgement.hpp, atlas/atlas_ladder.hpp): references,
// errors and the recommendation on synthetic runs with known answers, without running a model.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "atlas/atlas_judgement.hpp"

namespace granvv::testing {
namespace {

using app::AtlasRun;
using app::LadderRung;

// A finished run of a family with one scalar observable.
AtlasRun run_of(const std::string& model, std::map<std::string, double> knobs, double value,
                double seconds, const std::string& status = "ok",
                double standard_error = std::nan("")) {
  AtlasRun r;
  r.setting.model = model;
  r.setting.knobs = std::move(knobs);
  r.status = status;
  r.cost.wall_seconds = seconds;
  r.scalars["crossing_time_n10"] = value;
  r.scalar_errors["crossing_time_n10"] = standard_error;
  return r;
}

const std::vector<LadderRung> kLadder = {
    {"haff_ode", ""}, {"flow_by_inertia", ""}, {"hydro/dilute", ""}, {"hydro/enskog", "not here"}};

std::vector<AtlasRun> hydro_runs() {
  return {run_of("hydro/dilute", {{"cells", 100}, {"step_factor", 1}}, 1.04, 0.1),
          run_of("hydro/dilute", {{"cells", 200}, {"step_factor", 1}}, 1.01, 0.4),
          run_of("hydro/dilute", {{"cells", 200}, {"step_factor", 0.5}}, 1.00, 0.8),
          run_of("hydro/dilute", {{"cells", 400}, {"step_factor", 0.5}}, 0.0, 3.0, "non_finite"),
          run_of("flow_by_inertia", {}, 1.20, 0.001)};
}

TEST(AtlasLibrary, TheReferenceIsTheRichestFamilysFinestFinishedRun) {
  const auto runs = hydro_runs();
  std::vector<std::string> observables = {"crossing_time_n10", "haff_t0"};
  const app::AtlasReference ref = app::find_reference(kLadder, runs, observables);
  ASSERT_EQ(ref.run, &runs[2]);  // 400 cells failed; 200 at step factor 0.5 is the finest
  EXPECT_EQ(ref.family->name(), "hydro/dilute");
  // haff_t0 is not given by the reference: dropped and said so.
  EXPECT_EQ(observables, std::vector<std::string>{"crossing_time_n10"});
  EXPECT_EQ(ref.not_judged, std::vector<std::string>{"haff_t0"});
  // Its own error: the neighbour one step coarser in step factor (1.01 against 1.00); 100 cells
  // at step factor 1 differs in both knobs and is not a neighbour.
  ASSERT_EQ(ref.convergence.count("crossing_time_n10"), 1u);
  EXPECT_NEAR(ref.convergence.at("crossing_time_n10"), 0.01, 1e-12);
  EXPECT_TRUE(ref.statistical.empty());
}

TEST(AtlasLibrary, AnEnsembleReferenceIsItsOwnStandardError) {
  std::vector<AtlasRun> runs = hydro_runs();
  runs.push_back(run_of("particles/event_driven", {{"ensemble", 4}, {"particle_factor", 1}}, 2.0,
                        5.0, "ok", 0.02));
  runs.push_back(run_of("particles/event_driven", {{"ensemble", 8}, {"particle_factor", 1}}, 2.0,
                        9.0, "ok", 0.01));
  // Another scene's size is never the reference, however many members it has.
  runs.push_back(run_of("particles/event_driven", {{"ensemble", 64}, {"particle_factor", 0.5}}, 2.0,
                        9.0, "ok", 0.001));
  std::vector<LadderRung> ladder = kLadder;
  ladder.push_back({"particles/event_driven", ""});
  std::vector<std::string> observables = {"crossing_time_n10"};
  const app::AtlasReference ref = app::find_reference(ladder, runs, observables);
  ASSERT_EQ(ref.run, &runs[6]);
  EXPECT_NEAR(ref.statistical.at("crossing_time_n10"), 0.005, 1e-15);  // 0.01 / 2.0
  EXPECT_EQ(ref.convergence, ref.statistical);
  EXPECT_EQ(ref.own.at("hydro/dilute"), &runs[2]);
}

TEST(AtlasLibrary, RecommendationIsTheCheapestAdequateAndItsNextRung) {
  const auto runs = hydro_runs();
  std::vector<std::string> observables = {"crossing_time_n10"};
  const app::AtlasReference ref = app::find_reference(kLadder, runs, observables);
  const app::AtlasErrors errors = app::atlas_errors(runs, ref, observables);
  // Errors against 1.00: 4 %, 1 %, the reference's own 1 %, and 20 % for flow by inertia.
  std::optional<std::size_t> best;
  auto rec = app::recommendation_json(runs, errors, observables, 0.02, 3.0, best);
  ASSERT_TRUE(best);
  EXPECT_EQ(*best, 1u);  // 200 cells at step factor 1: adequate at 2 %, cheaper than the reference
  EXPECT_EQ(rec["model"], "hydro/dilute");
  EXPECT_EQ(rec["next_rung"], nullptr);  // no richer family ran
  // At 30 % flow by inertia is adequate and the cheapest; the hydro is its next rung up.
  rec = app::recommendation_json(runs, errors, observables, 0.3, 3.0, best);
  EXPECT_EQ(*best, 4u);
  EXPECT_EQ(rec["next_rung"]["model"], "hydro/dilute");
  EXPECT_EQ(rec["next_rung"]["adequate"], true);
  // Nothing meets 0.1 %: no model, and the reason.
  rec = app::recommendation_json(runs, errors, observables, 1e-3, 3.0, best);
  EXPECT_FALSE(best);
  EXPECT_EQ(rec["model"], nullptr);
}

TEST(AtlasLibrary, RunRowsMarkTheParetoFrontAndOverResolution) {
  const auto runs = hydro_runs();
  std::vector<std::string> observables = {"crossing_time_n10"};
  const app::AtlasReference ref = app::find_reference(kLadder, runs, observables);
  const app::AtlasErrors errors = app::atlas_errors(runs, ref, observables);
  const auto rows = app::run_rows(runs, errors, ref, observables);
  ASSERT_EQ(rows.size(), runs.size());
  // (0.1 s, 4 %), (0.4 s, 1 %), (0.8 s, 1 %: the reference's convergence), (0.001 s, 20 %):
  // the 0.8 s run is beaten by the 0.4 s one at the same error.
  EXPECT_EQ(rows[0]["pareto"].size(), 1u);
  EXPECT_EQ(rows[1]["pareto"].size(), 1u);
  EXPECT_EQ(rows[4]["pareto"].size(), 1u);
  EXPECT_EQ(rows[3]["status"], "non_finite");
  EXPECT_EQ(rows[1]["cells"], 200);
  EXPECT_EQ(rows[1]["step_factor"], 1.0);
}

}  // namespace
}  // namespace granvv::testing
