#include "models/compare_scene.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <utility>

#include "compare/binned_energies.hpp"
#include "compare/density_mode_evolution.hpp"
#include "compare/ensemble_error_model.hpp"
#include "compare/ensemble_fields.hpp"
#include "compare/ensemble_statistics.hpp"
#include "compare/inertia_measures.hpp"
#include "compare/model_comparison.hpp"
#include "compare/profile_measures.hpp"
#include "compare/side_by_side.hpp"
#include "compare/verdict.hpp"
#include "hydro/flow_by_inertia.hpp"
#include "hydro/haff.hpp"
#include "models/model.hpp"
#include "models/transport_measurement.hpp"

namespace granvv::app {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Peak density, |dv/dx| at the peak and the energies per particle, both engines on the bins.
void record_peak_and_energies(CompareOutcome& out, const fields::FieldSnapshot& hb,
                              const fields::FieldSnapshot& md, int members) {
  const std::size_t hp = compare::peak_bin(hb.n), mp = compare::peak_bin(md.n);
  out.hydro_n_peak.push_back(hb.n[hp]);
  out.md_n_peak.push_back(md.n[mp]);
  out.md_n_peak_error.push_back(md.n_stderr[mp]);
  out.hydro_dvdx_peak.push_back(std::abs(compare::periodic_centred_slope(hb.v_x, hp)));
  out.md_dvdx_peak.push_back(std::abs(compare::periodic_centred_slope(md.v_x, mp)));
  const compare::EnergiesPerParticle hydro = compare::box_energies(hb);
  const compare::EnergiesPerParticle particles =
      compare::noise_corrected_energies(md, md.count, members);
  out.hydro_energy_thermal.push_back(hydro.thermal);
  out.hydro_energy_kinetic.push_back(hydro.flow);
  out.md_energy_thermal.push_back(particles.thermal);
  out.md_energy_kinetic.push_back(particles.flow);
}

// The four measures of one binned state (n relative to its mean, v scaled), in the order of
// kInertiaMeasures.
std::vector<double> inertia_measures(const std::vector<double>& n, const std::vector<double>& v,
                                     double half_width) {
  return {compare::sine_mode_amplitude(v, 1), compare::cosine_mode_amplitude(n, 1),
          compare::central_window_mass(n, half_width), compare::central_density(n)};
}
constexpr CompareOutcome::InertiaMeasure CompareOutcome::*kInertiaMeasures[] = {
    &CompareOutcome::v_mode, &CompareOutcome::n_mode, &CompareOutcome::window_mass,
    &CompareOutcome::n_centre};

// The flow by inertia's measures for the particles (per member, then mean and error), the
// hydro and flow by inertia on the bins, at every compared time.
void compare_inertia_measures(CompareOutcome& out, const MdOutcome& md_out,
                              const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
                              double n0) {
  out.central_window = compare::kCentralWindowHalfWidth;
  const double w = out.central_window;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    std::vector<std::vector<double>> members;
    for (const auto& run : md_out.runs) {
      if (pairs[i].first >= run.fields.snapshots.size()) continue;
      const auto& s = run.fields.snapshots[pairs[i].first];
      std::vector<double> relative;
      for (double n : s.n) relative.push_back(n / n0);
      members.push_back(inertia_measures(relative, s.v_x, w));
    }
    const auto st = compare::ensemble_statistics(members);
    const auto& h = out.hydro_on_bins.snapshots[i];
    const auto hydro = inertia_measures(h.n, h.v_x, w);
    const auto inertia = inertia_measures(out.inertia_n[i], out.inertia_v[i], w);
    for (std::size_t m = 0; m < std::size(kInertiaMeasures); ++m) {
      CompareOutcome::InertiaMeasure& series = out.*kInertiaMeasures[m];
      series.md.push_back(m < st.mean.size() ? st.mean[m] : kNaN);
      series.md_error.push_back(m < st.standard_error.size() ? st.standard_error[m] : kNaN);
      series.hydro.push_back(hydro[m]);
      series.inertia.push_back(inertia[m]);
    }
  }
}

// The verdict line of a judgement (compare/side_by_side.hpp).
void write_verdict(CompareOutcome& out, const CompareScene& scene,
                   const compare::SideBySide& judged) {
  out.window = judged.window;
  out.offset_sigmas = judged.offset_sigmas;
  out.disagreement = compare::disagreement_name(judged.kind);
  out.verdict =
      compare::verdict_sentence(out.window, out.t.empty() ? kNaN : out.t.back(), scene.sigmas,
                                out.signal_to_noise, out.offset_sigmas, judged.kind);
}

}  // namespace

std::optional<CompareScene> compare_scene_from(const CaseConfig& c) {
  if (!c.boolean("compare.enabled")) return std::nullopt;
  CompareScene s;
  s.hydro_from_md = c.string("compare.hydro_initial") == "md";
  s.sigmas = c.real("compare.sigmas");
  s.verdict_rule.offset_sigmas = s.sigmas;
  s.agreement_fraction = c.real("compare.agreement_fraction");
  s.density_modes = c.int_value("compare.density_modes");
  const long long bins = c.int_value("md.bins");
  if (2LL * s.density_modes >= bins) {
    throw ConfigError(c.origin("compare.density_modes") +
                      ": compare.density_modes = " + std::to_string(s.density_modes) +
                      ": must be < md.bins / 2 = " + std::to_string(bins / 2) +
                      " (the Nyquist mode of the bins)");
  }
  s.closures = c.strings("compare.closures");
  const std::string listed = format_value(c.value("compare.closures"));
  if (s.closures.front() != c.string("hydro.closure")) {
    throw ConfigError(c.origin("compare.closures") + ": compare.closures = " + listed +
                      ": the first closure fills the hydro and compare blocks, so it must be "
                      "hydro.closure = \"" +
                      c.string("hydro.closure") + "\" (list it first)");
  }
  // Each closure models the particle scene: its phi0 is md.area_fraction (scene/hydro_scene.cpp).
  hydro::ClosureParameters params;
  params.physics = {c.real("physics.K"), c.real("physics.q")};
  read_closure_keys(c, params);
  params.extra["area_fraction"] = c.real("md.area_fraction");
  for (const auto& name : s.closures) {
    const auto problem = hydro::closure_parameter_problem(name, params);
    const std::string key = problem ? closure_problem_key(name, *problem) : "";
    if (problem && key != "physics.area_fraction") {  // the closure's own key
      throw ConfigError(c.origin(key) + ": " + key + " = " + format_value(c.value(key)) +
                        ": closure \"" + name + "\" of compare.closures: " + problem->reason);
    }
    if (problem) {
      throw ConfigError(c.origin("compare.closures") + ": compare.closures = " + listed +
                        ": closure \"" + name + "\" cannot model the particles at " +
                        "md.area_fraction = " + format_value(c.value("md.area_fraction")) + " (" +
                        problem->reason + ")");
    }
  }
  if (c.string("compare.transport") != "none") {
    CompareScene::Transport t;
    t.coefficient = c.string("compare.transport");
    t.field = c.string("compare.transport_field");
    t.phase = compare::mode_phase(c.string("compare.transport_phase"));
    t.start = c.int_value("compare.transport_start");
    t.factors = c.reals("compare.transport_factors");
    if (t.factors.empty()) t.factors = kDefaultTransportFactors;
    for (const auto& signal : c.strings("compare.transport_signals")) {
      const std::size_t colon = signal.find(':');
      t.signals.emplace_back(signal.substr(0, colon),
                             compare::mode_phase(signal.substr(colon + 1)));
    }
    if (t.signals.empty()) t.signals.emplace_back(t.field, t.phase);
    if (t.factors.size() < 2) {
      throw ConfigError(c.origin("compare.transport_factors") + ": compare.transport_factors = " +
                        format_value(c.value("compare.transport_factors")) +
                        ": needs at least two factors to fit between (or [] for the default)");
    }
    s.transport = std::move(t);
  }
  if (c.string("md.kernel") != "bin") {
    throw ConfigError(c.origin("md.kernel") + ": md.kernel = \"" + c.string("md.kernel") +
                      "\": a comparison bins the hydro like the particles, so it needs "
                      "md.kernel = \"bin\"");
  }
  return s;
}

void align_hydro_with_md(HydroScene& hydro, const md::ParticleScene& scene, double md_t_end,
                         const fields::FieldSeries& md_fields) {
  hydro.physics = scene.physics();
  hydro.area_fraction = scene.area_fraction;
  auto& ctl = hydro.control;
  ctl.t_end = scene.scaled_time(md_t_end);
  ctl.output_times.clear();
  for (const auto& s : md_fields.snapshots) {
    const double t = scene.scaled_time(s.t);
    if (t > 0.0 && (ctl.output_times.empty() || t > ctl.output_times.back())) {
      ctl.output_times.push_back(t);
    }
  }
  if (!ctl.output_times.empty()) ctl.t_end = std::max(ctl.t_end, ctl.output_times.back());
}

void prepare_comparison_hydro(HydroScene& hydro, const CompareScene& compare, const MdScene& md,
                              const fields::FieldSeries& md_fields) {
  const md::ParticleScene& sc = md.spec.scene;
  if (compare.hydro_from_md)
    hydro.given_fields = fields_from_snapshot(md_fields.snapshots.front(), sc);
  align_hydro_with_md(hydro, sc, md.spec.t_end, md_fields);
}

hydro::InitialFields fields_from_snapshot(const fields::FieldSnapshot& s,
                                          const md::ParticleScene& scene) {
  const double n0 = scene.number_density();
  std::vector<double> n, vx, vy, T;
  for (std::size_t b = 0; b < s.x.size(); ++b) {
    const double values[] = {s.n[b], s.v_x[b], s.v_y[b], s.T[b]};
    for (double v : values) {
      if (!std::isfinite(v)) {
        throw std::runtime_error("the MD's coarse-grained fields at t = " + std::to_string(s.t) +
                                 " have an empty bin (" + std::to_string(b) +
                                 "); use fewer md.bins to start the hydro "
                                 "from them");
      }
    }
    n.push_back(s.n[b] / n0), vx.push_back(s.v_x[b]), vy.push_back(s.v_y[b]);
    T.push_back(s.T[b]);
  }
  hydro::InitialFields f;
  f.n = compare::bin_interpolant(n);
  f.v = compare::bin_interpolant(vx);
  f.vy = compare::bin_interpolant(vy);
  f.T = compare::bin_interpolant(T);
  return f;
}

std::vector<std::string> monitors_fired_by(const hydro::ValidityRecord& validity,
                                           const compare::AgreementWindow& window) {
  std::vector<std::string> fired;
  if (window.throughout || !window.left_at) return fired;
  for (const auto& d : hydro::monitor_definitions()) {
    const auto& crossing = validity.first_crossing[static_cast<int>(d.monitor)];
    if (crossing && crossing->time <= *window.left_at) fired.push_back(d.name);
  }
  return fired;
}

CompareOutcome compare_engines(const CompareScene& scene, const HydroScene& hydro,
                               const HydroOutcome& hydro_out, const MdScene& md,
                               const MdOutcome& md_out) {
  const auto& sc = md.spec.scene;
  const double n0 = sc.number_density();
  const int bins = md.spec.bins;
  const int members = static_cast<int>(md_out.runs.size());
  const auto closure = make_hydro_closure(hydro);  // its Haff time and linear theory
  CompareOutcome out;
  for (int b = 0; b < bins; ++b) out.x.push_back(-0.5 + (b + 0.5) / bins);

  // Both models on the particles' bins, scaled units (models/model.hpp): the particles' ensemble
  // mean with the error of that mean, and the hydro binned like the particles.
  std::vector<fields::FieldSeries> member_fields;
  for (const auto& run : md_out.runs) member_fields.push_back(run.fields);
  const compare::EnsembleMeanFields mean =
      compare::ensemble_mean_fields(member_fields, scaled_units(sc));
  const fields::ModelResult particles = particle_result(md, md_out, mean.fields);
  const fields::ModelResult continuum = hydro_result(hydro, hydro_out, bins);
  // The output times both reached: each particle snapshot against the hydro's at that time.
  out.signal_to_noise = initial_signal_to_noise(md).ratio();
  const compare::SideBySide judged = compare::judge_side_by_side(
      *particles.fields, *continuum.fields, compare::compared_fields(hydro.transverse),
      scene.sigmas, scene.agreement_fraction, out.signal_to_noise, scene.verdict_rule);
  const auto& pairs = judged.pairs;
  for (const auto& track : judged.tracks) {
    FieldComparison f;
    f.name = track.field;
    f.track = track;
    if (!pairs.empty()) {  // how the error was made, at the last compared time
      const auto& all = compare::fields_with_errors();
      const auto k = std::find(all.begin(), all.end(), f.name) - all.begin();
      f.error_source = mean.error_source[pairs.back().first][k];
    }
    out.fields.push_back(std::move(f));
  }

  out.hydro_on_bins = out.md_on_bins = fields::FieldSeries::on_bins(-0.5, 1.0, bins);
  for (const auto& [i, j] : pairs) {
    const fields::FieldSnapshot& m = particles.fields->snapshots[i];
    const fields::FieldSnapshot& h = continuum.fields->snapshots[j];
    out.t.push_back(m.t);
    record_peak_and_energies(out, h, m, members);
    out.collision_clock.push_back(hydro::collision_clock(m.t, hydro::haff_time_scale(*closure)));
    out.hydro_on_bins.snapshots.push_back(h);
    out.md_on_bins.snapshots.push_back(m);
  }

  // Flow by inertia (paper Eq. 5) on the same bins where the case's initial velocity has it,
  // NaN rows at the times it does not reach (at and after its singularity).
  std::optional<fields::ModelResult> inertia;
  if (hydro::inertia_reference(hydro.initial)) {
    inertia = make_inertia_model(hydro.initial, hydro.physics, out.t, bins)->run();
  }
  for (double t : out.t) {
    const fields::FieldSnapshot* s = nullptr;
    if (inertia) {
      for (const auto& snap : inertia->fields->snapshots) {
        if (snap.t == t) s = &snap;
      }
    }
    out.inertia_n.push_back(s ? s->n : std::vector<double>(bins, kNaN));
    out.inertia_v.push_back(s ? s->v_x : std::vector<double>(bins, kNaN));
    out.inertia_n_peak.push_back(s ? *std::max_element(s->n.begin(), s->n.end()) : kNaN);
  }

  compare_inertia_measures(out, md_out, pairs, n0);
  if (scene.density_modes > 0 && !pairs.empty()) {
    compare::DensityModes modes =
        compare::density_modes(scene.density_modes, *closure, member_fields, *continuum.fields,
                               pairs, out.collision_clock, n0);
    out.theory_rate = std::move(modes.theory_rate);
    out.hydro_modes = std::move(modes.hydro);
    out.md_modes = std::move(modes.md);
    out.md_modes_error = std::move(modes.md_error);
    out.theory_modes = std::move(modes.theory);
  }

  write_verdict(out, scene, judged);
  return out;
}

}  // namespace granvv::app
