// The ladder's exact references as models: Haff's law and flow by inertia (models/model.hpp).
#include <chrono>
#include <cmath>

#include "compare/binned_fields.hpp"
#include "hydro/flow_by_inertia.hpp"
#include "hydro/haff.hpp"
#include "hydro/inertia_crossing.hpp"
#include "models/model.hpp"

namespace granvv::app {
namespace {

// Flow by inertia is put on the bins up to this fraction of its singularity time: at the
// singularity itself its density is infinite in one bin (paper Eqs. 5-7).
constexpr double kInertiaBeforeSingularity = 0.999;
// Lagrangian labels per bin of the flow-by-inertia state (second-order masses, binned exactly).
constexpr int kInertiaLabelsPerBin = 100;

class HaffModel : public Model {
 public:
  HaffModel(const hydro::Physics& physics, std::vector<double> times, int bins)
      : physics_(physics), times_(std::move(times)), bins_(bins) {}
  std::string name() const override { return "haff_ode"; }
  fields::ModelResult run() override {
    const auto start = std::chrono::steady_clock::now();
    const double t0 = hydro::haff_time_scale(physics_);
    fields::ModelResult r;
    r.model = name();
    fields::FieldSeries f = fields::FieldSeries::on_bins(-0.5, 1.0, bins_);
    for (double t : times_) {
      fields::FieldSnapshot s;
      s.t = t;
      s.label = "output";
      for (int b = 0; b < bins_; ++b) s.x.push_back(-0.5 + (b + 0.5) / bins_);
      s.n.assign(bins_, 1.0);
      s.v_x.assign(bins_, 0.0);
      s.v_y.assign(bins_, 0.0);
      s.T.assign(bins_, hydro::haff_temperature(t, t0));
      f.snapshots.push_back(std::move(s));
    }
    r.fields = std::move(f);
    r.observables.push_back({"haff_t0", t0});
    r.cost = {seconds_since(start), double(times_.size()), "evaluations"};
    return r;
  }

 private:
  hydro::Physics physics_;
  std::vector<double> times_;
  int bins_;
};

class InertiaModel : public Model {
 public:
  InertiaModel(hydro::InitialFields initial, hydro::FlowByInertia flow, std::vector<double> times,
               int bins, std::vector<double> crossing_levels)
      : initial_(std::move(initial)),
        flow_(std::move(flow)),
        tau_(flow_.singularity_time()),
        times_(std::move(times)),
        bins_(bins),
        crossing_levels_(std::move(crossing_levels)) {}
  std::string name() const override { return "flow_by_inertia"; }
  fields::ModelResult run() override {
    const auto start = std::chrono::steady_clock::now();
    fields::ModelResult r;
    r.model = name();
    fields::FieldSeries f = fields::FieldSeries::on_bins(-0.5, 1.0, bins_);
    const int labels = kInertiaLabelsPerBin * bins_;
    for (double t : times_) {
      if (!(t < kInertiaBeforeSingularity * tau_)) continue;
      fields::FieldSnapshot s =
          compare::bin_lagrangian_state(compare::flow_by_inertia_state(initial_, t, labels), bins_);
      s.t = t;
      s.label = "output";
      s.T.clear();  // flow by inertia has no pressure: T plays no part (docs/physics.md §3)
      f.snapshots.push_back(std::move(s));
    }
    r.cost = {seconds_since(start), double(labels) * f.snapshots.size(), "evaluations"};
    r.fields = std::move(f);
    if (std::isfinite(tau_)) r.observables.push_back({"singularity_time", tau_});
    for (double level : crossing_levels_) {
      const double t = hydro::inertia_crossing_time(flow_, level);
      if (std::isfinite(t)) r.observables.push_back({crossing_time_name(level), t});
    }
    r.cost.wall_seconds = seconds_since(start);
    return r;
  }

 private:
  hydro::InitialFields initial_;
  hydro::FlowByInertia flow_;
  double tau_;
  std::vector<double> times_;
  int bins_;
  std::vector<double> crossing_levels_;
};

}  // namespace

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::unique_ptr<Model> make_haff_model(const hydro::Physics& physics, std::vector<double> times,
                                       int bins) {
  return std::make_unique<HaffModel>(physics, std::move(times), bins);
}

std::unique_ptr<Model> make_inertia_model(const hydro::InitialParameters& initial,
                                          const hydro::Physics& physics, std::vector<double> times,
                                          int bins, std::vector<double> crossing_levels) {
  const auto reference = hydro::inertia_reference(initial);
  if (!reference) {
    throw ConfigError("initial.type = \"" + initial.type +
                      "\": its initial velocity has no flow-by-inertia reference");
  }
  return std::make_unique<InertiaModel>(hydro::make_initial_fields(initial, physics),
                                        reference->flow, std::move(times), bins,
                                        std::move(crossing_levels));
}

}  // namespace granvv::app
