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
#include "compare/ensemble_fields.hpp"
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

// The particles' ensemble mean of one snapshot in scaled units (n in n0; x, v and T are
// already scaled in MD units, docs/physics.md §4), with the error of that mean for each compared
// field: one member's snapshot error model calibrated by the ensemble
// (compare/ensemble_error_model.hpp). Records each field's error source.
fields::FieldSnapshot md_mean_scaled(const MdOutcome& md_out, std::size_t s, double n0,
                                     std::vector<FieldComparison>& compared) {
  const fields::FieldSnapshot& mean = md_out.fields.snapshots[s];
  const fields::FieldSnapshot& first = md_out.runs.front().fields.snapshots[s];
  std::vector<fields::FieldSeries> members;
  for (const auto& run : md_out.runs) members.push_back(run.fields);
  const int bins = static_cast<int>(mean.n.size());
  fields::FieldSnapshot m;
  m.t = mean.t, m.label = mean.label;
  for (int b = 0; b < bins; ++b) {
    m.n.push_back(mean.n[b] / n0);
    // Poisson for one member's bin count (an ideal gas; S(0) < 1 at finite density, and the
    // ensemble calibration corrects the level), in MD units like the ensemble's.
    m.n_stderr.push_back(mean.count[b] > 0 ? mean.n[b] / std::sqrt(mean.count[b]) : kNaN);
  }
  m.v_x = mean.v_x, m.v_y = mean.v_y, m.T = mean.T;
  m.v_x_stderr = first.v_x_stderr, m.v_y_stderr = first.v_y_stderr, m.T_stderr = first.T_stderr;
  m.count = mean.count;
  for (auto& f : compared) {
    const fields::FieldColumn& c = fields::field_column(f.name);
    compare::EnsembleMeanError e = compare::ensemble_mean_error(
        m.*c.standard_error, compare::column_statistics(members, s, c.values));
    f.error_source = compare::error_source_label(e);
    m.*c.standard_error = std::move(e.error);
  }
  for (double& e : m.n_stderr) e /= n0;
  return m;
}

// Per field: the hydro on the bins against the particles' mean and its error, at one time.
void compare_fields_at(std::vector<FieldComparison>& compared, const fields::FieldSnapshot& hb,
                       const fields::FieldSnapshot& md, double sigmas) {
  const double T_bar = compare::mass_weighted_mean(md.n, md.T);
  for (auto& f : compared) {
    const fields::FieldColumn& c = fields::field_column(f.name);
    // The scale of the differences: n0 for n, the thermal speed for v, the mean T for T.
    const double scale = f.name == "n" ? 1.0 : f.name == "T" ? T_bar : std::sqrt(T_bar);
    f.track.at.push_back(
        compare::field_difference(hb.*c.values, md.*c.values, md.*c.standard_error, scale, sigmas));
  }
}

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

// Density modes: |n_k| of the hydro; for the particles the rms over members (the phases of
// noise-born modes differ between seeds, so the mean field would average them away), and the
// linear theory evolving each member's own t = 0 perturbation (nu, w, theta)_k with exp(A s)
// (hydro/linear_stability.hpp), rms over members.
void compare_density_modes(
    CompareOutcome& out, int modes, const hydro::Physics& physics, const MdOutcome& md_out,
    const std::vector<std::pair<std::size_t, const hydro::LagrangianState*>>& pairs, double n0,
    int bins) {
  const int members = static_cast<int>(md_out.runs.size());
  for (int k = 1; k <= modes; ++k) {
    out.theory_rate.push_back(hydro::hcs_modes(physics, k)[0].rate.real());
  }
  std::vector<std::vector<Eigen::Vector3cd>> initial(members);
  for (int r = 0; r < members; ++r) {
    const auto& f = md_out.runs[r].fields.snapshots.front();
    for (int k = 1; k <= modes; ++k) {
      initial[r].push_back(compare::hcs_perturbation(f.n, f.v_x, f.T, k));
    }
  }
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto hb = compare::bin_lagrangian_state(*pairs[i].second, bins);
    std::vector<double> hydro_row, md_row, md_err, theory_row;
    const std::size_t s_index = pairs[i].first;
    for (int k = 1; k <= modes; ++k) {
      hydro_row.push_back(std::abs(compare::bin_fourier_coefficient(hb.n, k)));
      std::vector<std::vector<double>> power;  // one |n_k|^2 per member
      double theory2 = 0.0;
      for (int r = 0; r < members; ++r) {
        const auto& snaps = md_out.runs[r].fields.snapshots;
        if (s_index >= snaps.size()) continue;
        std::vector<double> relative;
        for (double n : snaps[s_index].n) relative.push_back(n / n0);
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
    const fields::FieldColumn& c = fields::field_column(out.window.first_out);
    const fields::FieldSnapshot &h = out.hydro_on_bins.snapshots[k],
                                &m = out.md_on_bins.snapshots[k];
    out.offset_sigmas = compare::box_mean_offset(h.*c.values, m.*c.values, m.*c.standard_error);
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
  s.density_modes = static_cast<int>(c.integer("compare.density_modes"));
  const long long bins = c.integer("md.bins");
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
                         const fields::FieldSeries& md_fields) {
  hydro.physics = scene.physics();
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
  std::vector<std::pair<std::size_t, const hydro::LagrangianState*>> pairs;
  for (std::size_t k = 0; k < md_out.fields.snapshots.size(); ++k) {
    const double t = sc.scaled_time(md_out.fields.snapshots[k].t);
    for (const auto& h : hydro_out.run.snapshots) {
      if (std::abs(h.state.t - t) <= 1e-9 * std::max(1.0, t)) {
        pairs.emplace_back(k, &h.state);
        break;
      }
    }
  }

  std::vector<std::string> names = {"n", "v_x", "T"};
  if (hydro.transverse) names.insert(names.begin() + 2, "v_y");
  for (const auto& name : names) {
    FieldComparison f;
    f.name = name;
    f.track.field = name;
    out.fields.push_back(std::move(f));
  }
  out.hydro_on_bins = out.md_on_bins = fields::FieldSeries::on_bins(-0.5, 1.0, bins);

  const hydro::InitialFields case_fields = hydro::make_initial_fields(hydro.initial, hydro.physics);
  const auto inertia_reference = hydro::inertia_reference(hydro.initial);
  const bool smooth = inertia_reference.has_value();
  const double inertia_tau = smooth ? inertia_reference->flow.singularity_time() : kNaN;
  const double t0 = hydro::haff_time_scale(hydro.physics);

  for (const auto& [k, h] : pairs) {
    const double t = sc.scaled_time(md_out.fields.snapshots[k].t);
    out.t.push_back(t);
    fields::FieldSnapshot hb = compare::bin_lagrangian_state(*h, bins);
    hb.t = t, hb.label = "output";
    fields::FieldSnapshot md_mean = md_mean_scaled(md_out, k, n0, out.fields);
    md_mean.t = t, md_mean.x = hb.x;
    compare_fields_at(out.fields, hb, md_mean, scene.sigmas);
    record_peak_and_energies(out, hb, md_mean, members);
    out.hydro_on_bins.snapshots.push_back(std::move(hb));
    out.md_on_bins.snapshots.push_back(std::move(md_mean));
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
