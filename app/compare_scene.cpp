#include "app/compare_scene.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>
#include <utility>

#include "compare/binned_energies.hpp"
#include "compare/density_modes.hpp"
#include "compare/ensemble_error_model.hpp"
#include "compare/ensemble_statistics.hpp"
#include "compare/profile_measures.hpp"
#include "compare/verdict.hpp"
#include "hydro/flow_by_inertia.hpp"
#include "hydro/haff.hpp"
#include "hydro/linear_stability.hpp"

namespace granvv::app {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Flow by inertia is put on the bins up to this fraction of its singularity time: at the
// singularity itself its density is infinite in one bin (paper Eqs. 5-7).
constexpr double kInertiaBeforeSingularity = 0.999;

// One member's snapshot error model against the ensemble of a field: the error of the mean and
// its source label (compare/ensemble_error_model.hpp).
std::vector<double> mean_error(const std::vector<double>& model_one_member,
                               const compare::EnsembleStatistics& stats, std::string& source) {
  compare::EnsembleMeanError e = compare::ensemble_mean_error(model_one_member, stats);
  source = compare::error_source_label(e);
  return std::move(e.error);
}

// Per field: the hydro on the bins against the MD mean and its error (scaled units), and their
// difference at this output time.
void compare_fields_at(std::vector<ComparedField>& fields, const compare::BinnedFields& hb,
                       const EnsembleSnapshot* m, double n0, double sigmas) {
  const int bins = static_cast<int>(hb.n.size());
  // MD means in scaled units, and their errors.
  std::vector<double> md_n, md_T, model_n, model_vx, model_vy, model_T;
  for (int b = 0; b < bins; ++b) {
    md_n.push_back(m->n.mean[b] / n0);
    md_T.push_back(m->T.mean[b]);
    const double count = m->count.mean[b];
    // Poisson for one member's bin count (an ideal gas; S(0) < 1 at finite density, and the
    // ensemble calibration below corrects the level), in MD units like the ensemble's.
    model_n.push_back(count > 0 ? m->n.mean[b] / std::sqrt(count) : kNaN);
    model_vx.push_back(m->v_x_snapshot_error[b]);
    model_vy.push_back(m->v_y_snapshot_error[b]);
    model_T.push_back(m->T_snapshot_error[b]);
  }
  const double T_bar = compare::mass_weighted_mean(md_n, md_T);
  for (auto& f : fields) {
    std::vector<double> hv, mv, err;
    double scale = 1.0;  // n: the mean density n0
    if (f.name == "n") {
      hv = hb.n, mv = md_n, err = mean_error(model_n, m->n, f.error_source);
      for (double& e : err) e /= n0;
    } else if (f.name == "v_x") {
      hv = hb.v_x, mv = m->v_x.mean, err = mean_error(model_vx, m->v_x, f.error_source);
      scale = std::sqrt(T_bar);  // the thermal speed at this time
    } else if (f.name == "v_y") {
      hv = hb.v_y, mv = m->v_y.mean, err = mean_error(model_vy, m->v_y, f.error_source);
      scale = std::sqrt(T_bar);
    } else {
      hv = hb.T, mv = md_T, err = mean_error(model_T, m->T, f.error_source);
      scale = T_bar;  // the mean temperature at this time
    }
    f.track.at.push_back(compare::field_difference(hv, mv, err, scale, sigmas));
    f.hydro.push_back(hv), f.md.push_back(mv), f.md_error.push_back(err);
  }
}

// Peak density, |dv/dx| at the peak and the energies per particle, both engines on the bins.
void record_peak_and_energies(CompareOutcome& out, const compare::BinnedFields& hb,
                              const EnsembleSnapshot* m, double n0, int members) {
  const int bins = static_cast<int>(hb.n.size());
  compare::BinnedFields md_mean;
  for (int b = 0; b < bins; ++b) {
    md_mean.n.push_back(m->n.mean[b] / n0), md_mean.T.push_back(m->T.mean[b]);
  }
  md_mean.v_x = m->v_x.mean, md_mean.v_y = m->v_y.mean;
  const std::size_t hp = compare::peak_bin(hb.n), mp = compare::peak_bin(md_mean.n);
  out.hydro_n_peak.push_back(hb.n[hp]);
  out.md_n_peak.push_back(md_mean.n[mp]);
  out.md_n_peak_error.push_back(out.fields.front().md_error.back()[mp]);
  out.hydro_dvdx_peak.push_back(std::abs(compare::periodic_centred_slope(hb.v_x, hp)));
  out.md_dvdx_peak.push_back(std::abs(compare::periodic_centred_slope(md_mean.v_x, mp)));
  const compare::EnergiesPerParticle hydro = compare::box_energies(hb);
  const compare::EnergiesPerParticle md =
      compare::noise_corrected_energies(md_mean, m->count.mean, members);
  out.hydro_energy_thermal.push_back(hydro.thermal);
  out.hydro_energy_kinetic.push_back(hydro.flow);
  out.md_energy_thermal.push_back(md.thermal);
  out.md_energy_kinetic.push_back(md.flow);
}

// Density modes: |n_k| of the hydro; for the particles the rms over members (the phases of
// noise-born modes differ between seeds, so the mean field would average them away), and the
// linear theory evolving each member's own t = 0 perturbation (nu, w, theta)_k with exp(A s)
// (hydro/linear_stability.hpp), rms over members.
void compare_density_modes(
    CompareOutcome& out, int modes, const hydro::Physics& physics, const MdOutcome& md_out,
    const std::vector<std::pair<const EnsembleSnapshot*, const hydro::LagrangianState*>>& pairs,
    double n0, int bins) {
  const int members = static_cast<int>(md_out.runs.size());
  for (int k = 1; k <= modes; ++k) {
    out.theory_rate.push_back(hydro::hcs_modes(physics, k)[0].rate.real());
  }
  std::vector<std::vector<Eigen::Vector3cd>> initial(members);
  for (int r = 0; r < members; ++r) {
    const auto& f = md_out.runs[r].snapshots.front().fields;
    for (int k = 1; k <= modes; ++k) {
      initial[r].push_back(compare::hcs_perturbation(f.n, f.v_x, f.T, k));
    }
  }
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto hb = compare::bin_lagrangian_state(*pairs[i].second, bins);
    std::vector<double> hydro_row, md_row, md_err, theory_row;
    const std::size_t s_index = pairs[i].first - md_out.snapshots.data();
    for (int k = 1; k <= modes; ++k) {
      hydro_row.push_back(std::abs(compare::bin_fourier_coefficient(hb.n, k)));
      std::vector<std::vector<double>> power;  // one |n_k|^2 per member
      double theory2 = 0.0;
      for (int r = 0; r < members; ++r) {
        const auto& snaps = md_out.runs[r].snapshots;
        if (s_index >= snaps.size()) continue;
        std::vector<double> relative;
        for (double n : snaps[s_index].fields.n) relative.push_back(n / n0);
        power.push_back({std::norm(compare::bin_fourier_coefficient(relative, k))});
        const Eigen::Vector3cd evolved =
            hydro::hcs_linear_evolution(physics, k, initial[r][k - 1], out.collision_clock[i]);
        theory2 += std::norm(evolved[0]);
      }
      // rms over members; its error from the scatter of |n_k|^2 (d sqrt(p) = dp / 2 sqrt(p)).
      const auto st = compare::ensemble_statistics(power);
      const double rms = std::sqrt(st.mean[0]);
      md_row.push_back(rms);
      md_err.push_back(rms > 0 ? 0.5 * st.standard_error[0] / rms : kNaN);
      theory_row.push_back(std::sqrt(theory2 / members));
    }
    out.hydro_modes.push_back(hydro_row);
    out.md_modes.push_back(md_row);
    out.md_modes_error.push_back(md_err);
    out.theory_modes.push_back(theory_row);
  }
}

// The kind of disagreement (compare/verdict.hpp) and the verdict line. The box-mean offset is
// that of the first field to part, at the time it parted.
void write_verdict(CompareOutcome& out, const CompareScene& scene) {
  if (!out.window.throughout && out.window.left_at) {
    const auto k = std::find(out.t.begin(), out.t.end(), *out.window.left_at) - out.t.begin();
    for (const auto& f : out.fields) {
      if (f.name == out.window.first_out) {
        out.offset_sigmas = compare::box_mean_offset(f.hydro[k], f.md[k], f.md_error[k]);
      }
    }
  }
  const compare::Disagreement kind = compare::classify_disagreement(
      out.window.throughout, out.signal_to_noise, out.offset_sigmas, scene.verdict_rule);
  out.disagreement = compare::disagreement_name(kind);
  out.verdict =
      compare::verdict_sentence(out.window, out.t.empty() ? kNaN : out.t.back(), scene.sigmas,
                                out.signal_to_noise, out.offset_sigmas, kind);
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
  if (c.string("md.kernel") != "bin") {
    throw ConfigError(c.origin("md.kernel") + ": md.kernel = \"" + c.string("md.kernel") +
                      "\": a comparison bins the hydro like the particles, so it needs "
                      "md.kernel = \"bin\"");
  }
  return s;
}

void align_hydro_with_md(HydroScene& hydro, const md::ParticleScene& scene, double md_t_end,
                         const std::vector<EnsembleSnapshot>& md_snapshots) {
  hydro.physics = scene.physics();
  auto& ctl = hydro.control;
  ctl.t_end = scene.scaled_time(md_t_end);
  ctl.output_times.clear();
  for (const auto& s : md_snapshots) {
    const double t = scene.scaled_time(s.t);
    if (t > 0.0 && (ctl.output_times.empty() || t > ctl.output_times.back())) {
      ctl.output_times.push_back(t);
    }
  }
  if (!ctl.output_times.empty()) ctl.t_end = std::max(ctl.t_end, ctl.output_times.back());
}

hydro::InitialFields fields_from_snapshot(const EnsembleSnapshot& s,
                                          const md::ParticleScene& scene) {
  const double n0 = scene.number_density();
  std::vector<double> n, vx, vy, T;
  for (std::size_t b = 0; b < s.x.size(); ++b) {
    const double values[] = {s.n.mean[b], s.v_x.mean[b], s.v_y.mean[b], s.T.mean[b]};
    for (double v : values) {
      if (!std::isfinite(v)) {
        throw std::runtime_error("the MD's coarse-grained fields at t = " + std::to_string(s.t) +
                                 " have an empty bin (" + std::to_string(b) +
                                 "); use fewer md.bins to start the hydro "
                                 "from them");
      }
    }
    n.push_back(s.n.mean[b] / n0), vx.push_back(s.v_x.mean[b]), vy.push_back(s.v_y.mean[b]);
    T.push_back(s.T.mean[b]);
  }
  hydro::InitialFields f;
  f.n = compare::bin_interpolant(n);
  f.v = compare::bin_interpolant(vx);
  f.vy = compare::bin_interpolant(vy);
  f.T = compare::bin_interpolant(T);
  return f;
}

CompareOutcome compare_engines(const CompareScene& scene, const HydroScene& hydro,
                               const HydroOutcome& hydro_out, const MdScene& md,
                               const MdOutcome& md_out) {
  const auto& sc = md.spec.scene;
  const double n0 = sc.number_density();
  const int bins = md.spec.bins;
  const int members = static_cast<int>(md_out.runs.size());
  CompareOutcome out;
  for (int b = 0; b < bins; ++b) out.x.push_back(-0.5 + (b + 0.5) / bins);

  // The output times both engines reached: each MD snapshot against the hydro snapshot taken
  // at the same scaled time.
  std::vector<std::pair<const EnsembleSnapshot*, const hydro::LagrangianState*>> pairs;
  for (const auto& m : md_out.snapshots) {
    const double t = sc.scaled_time(m.t);
    for (const auto& h : hydro_out.run.snapshots) {
      if (std::abs(h.state.t - t) <= 1e-9 * std::max(1.0, t)) {
        pairs.emplace_back(&m, &h.state);
        break;
      }
    }
  }

  std::vector<std::string> names = {"n", "v_x", "T"};
  if (hydro.transverse) names.insert(names.begin() + 2, "v_y");
  for (const auto& name : names) {
    ComparedField f;
    f.name = name;
    f.track.field = name;
    out.fields.push_back(std::move(f));
  }

  const hydro::InitialFields case_fields = hydro::make_initial_fields(hydro.initial, hydro.physics);
  const auto inertia_reference = hydro::inertia_reference(hydro.initial);
  const bool smooth = inertia_reference.has_value();
  const double inertia_tau = smooth ? inertia_reference->flow.singularity_time() : kNaN;
  const double t0 = hydro::haff_time_scale(hydro.physics);

  for (const auto& [m, h] : pairs) {
    const double t = sc.scaled_time(m->t);
    out.t.push_back(t);
    const compare::BinnedFields hb = compare::bin_lagrangian_state(*h, bins);
    compare_fields_at(out.fields, hb, m, n0, scene.sigmas);
    record_peak_and_energies(out, hb, m, n0, members);
    // Flow by inertia on the same bins, before its singularity.
    if (smooth && t < kInertiaBeforeSingularity * inertia_tau) {
      const auto inertia = compare::bin_lagrangian_state(
          compare::flow_by_inertia_state(case_fields, t, 100 * bins), bins);
      out.inertia_n.push_back(inertia.n);
      out.inertia_v.push_back(inertia.v_x);
      out.inertia_n_peak.push_back(*std::max_element(inertia.n.begin(), inertia.n.end()));
    } else {
      out.inertia_n.emplace_back(bins, kNaN);
      out.inertia_v.emplace_back(bins, kNaN);
      out.inertia_n_peak.push_back(kNaN);
    }
    out.collision_clock.push_back(hydro::collision_clock(t, t0));
  }

  if (scene.density_modes > 0 && !pairs.empty()) {
    compare_density_modes(out, scene.density_modes, hydro.physics, md_out, pairs, n0, bins);
  }

  std::vector<compare::FieldTrack> tracks;
  for (const auto& f : out.fields) tracks.push_back(f.track);
  out.window = compare::agreement_window(out.t, tracks, scene.agreement_fraction);

  out.signal_to_noise = initial_signal_to_noise(md).ratio();

  write_verdict(out, scene);
  return out;
}

}  // namespace granvv::app
