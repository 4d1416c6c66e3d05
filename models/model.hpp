#pragma once
// The models of a scene's ladder behind one interface (docs/architecture.md, "Models"). Each is
// built from its part of the resolved case and, run, returns a fields::ModelResult in the
// hydro's scaled units: its fields where it has them (on the bins asked for), named observables
// and its cost. compare/model_comparison.hpp weighs any two results.
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "compare/ensemble_fields.hpp"
#include "fields/model_result.hpp"
#include "scene/hydro_scene.hpp"
#include "scene/md_scene.hpp"

namespace granvv::app {

// Wall seconds from start to now: a model's cost (fields::ModelCost).
double seconds_since(std::chrono::steady_clock::time_point start);

class Model {
 public:
  virtual ~Model() = default;
  virtual std::string name() const = 0;
  virtual fields::ModelResult run() = 0;
};

// Haff's law (hydro/haff.hpp): the homogeneous cooling state n = 1, v = 0, T = (1 + t/t0)^-2 on
// `bins` bins at `times`. Observable haff_t0.
std::unique_ptr<Model> make_haff_model(const hydro::Physics& physics, std::vector<double> times,
                                       int bins);

// Flow by inertia (paper Eq. 5) of the case's initial fields on `bins` bins, at the given times
// before 0.999 of its singularity time (there its density is infinite in one bin). Observables
// singularity_time and crossing_time_n<level> of its peak density for each of crossing_levels
// (hydro/inertia_crossing.hpp). Throws ConfigError if the initial velocity has no
// flow-by-inertia reference.
std::unique_ptr<Model> make_inertia_model(const hydro::InitialParameters& initial,
                                          const hydro::Physics& physics, std::vector<double> times,
                                          int bins, std::vector<double> crossing_levels = {});

// The hydro with its closure. Fields on `bins` bins (bin_lagrangian_state) or, for bins = 0, on
// its own cells. Observables: haff_t0 (of its closure), t_final, singularity_time (the 1/n_max
// fit, when it stopped at the singularity) and crossing_time_n<level> for every density level
// it crossed.
class HydroModel : public Model {
 public:
  HydroModel(HydroScene scene, int bins, hydro::ProgressCallback progress = {});
  std::string name() const override;
  fields::ModelResult run() override;
  const HydroOutcome& outcome() const { return outcome_; }

 private:
  HydroScene scene_;
  int bins_;
  hydro::ProgressCallback progress_;
  HydroOutcome outcome_;
};
fields::ModelResult hydro_result(const HydroScene& scene, const HydroOutcome& outcome, int bins);
// "crossing_time_n10": the observable of the time the peak density first reaches level.
std::string crossing_time_name(double level);

// The particles with their engine, an ensemble of seeds. Fields: the ensemble mean on the
// particles' bins with the error of that mean (compare::ensemble_mean_fields). Observables with
// their standard errors: haff_t0 (the fit to the ensemble), pressure (the box's, in n0 T0) and
// compressibility P/(nT), both averaged over the samples and the members.
class ParticleModel : public Model {
 public:
  using Progress = std::function<void(int member, const md::MdProgress&)>;
  // checkpointing (may be null: none) saves and resumes the members (scene/md_scene.hpp); it
  // must outlive the run.
  ParticleModel(MdScene scene, md::ParticleEngine& engine, Progress progress = {},
                const MdCheckpointing* checkpointing = nullptr);
  std::string name() const override;
  fields::ModelResult run() override;
  const MdOutcome& outcome() const { return outcome_; }

 private:
  MdScene scene_;
  md::ParticleEngine& engine_;
  Progress progress_;
  const MdCheckpointing* checkpointing_;
  MdOutcome outcome_;
};
// The particles' scaled units (compare/ensemble_fields.hpp).
compare::ScaledUnits scaled_units(const md::ParticleScene& scene);
fields::ModelResult particle_result(const MdScene& scene, const MdOutcome& outcome,
                                    fields::FieldSeries mean_fields);

}  // namespace granvv::app
