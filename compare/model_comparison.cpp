#include "compare/model_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "compare/profile_measures.hpp"

namespace granvv::compare {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Equal bin edges up to the rounding of a unit conversion (edges scaled from sigma to Lx).
bool same_bins(const fields::FieldSeries& a, const fields::FieldSeries& b) {
  if (a.geometry != fields::Geometry::bins || b.geometry != fields::Geometry::bins) return false;
  if (a.bin_edges.size() != b.bin_edges.size() || a.bin_edges.size() < 2) return false;
  const double span = a.bin_edges.back() - a.bin_edges.front();
  for (std::size_t i = 0; i < a.bin_edges.size(); ++i) {
    if (!(std::abs(a.bin_edges[i] - b.bin_edges[i]) <= 1e-12 * std::abs(span))) return false;
  }
  return true;
}

}  // namespace

double field_scale(const std::string& field, const fields::FieldSnapshot& reference,
                   const fields::FieldSnapshot& candidate) {
  if (field == "n") return 1.0;
  const fields::FieldSnapshot& hot = reference.T.empty() ? candidate : reference;
  if (hot.T.empty()) return 1.0;  // neither side has a temperature: absolute differences
  const double T_bar = mass_weighted_mean(hot.n, hot.T);
  return field == "T" ? T_bar : std::sqrt(T_bar);
}

std::vector<std::pair<std::size_t, std::size_t>> common_snapshots(
    const fields::FieldSeries& reference, const fields::FieldSeries& candidate) {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < reference.snapshots.size(); ++i) {
    const double t = reference.snapshots[i].t;
    for (std::size_t j = 0; j < candidate.snapshots.size(); ++j) {
      if (fields::same_time(candidate.snapshots[j].t, t)) {
        pairs.emplace_back(i, j);
        break;
      }
    }
  }
  return pairs;
}

std::vector<FieldTrack> compare_field_series(
    const fields::FieldSeries& reference, const fields::FieldSeries& candidate,
    const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
    const std::vector<std::string>& field_names, double sigmas) {
  if (!same_bins(reference, candidate)) {
    throw std::invalid_argument("compare_field_series: the two series are not on the same bins");
  }
  std::vector<FieldTrack> tracks;
  for (const auto& name : field_names) {
    const fields::FieldColumn& c = fields::field_column(name);
    FieldTrack track;
    track.field = name;
    for (const auto& [i, j] : pairs) {
      const fields::FieldSnapshot &r = reference.snapshots.at(i), &k = candidate.snapshots.at(j);
      if ((r.*c.values).empty() || (k.*c.values).empty()) {
        throw std::invalid_argument("compare_field_series: field " + name +
                                    " missing at t = " + std::to_string(r.t));
      }
      const auto& error = (r.*c.standard_error).empty() ? k.*c.standard_error : r.*c.standard_error;
      const double scale = field_scale(name, r, k);
      track.at.push_back(error.empty()
                             ? deterministic_field_difference(k.*c.values, r.*c.values, scale)
                             : field_difference(k.*c.values, r.*c.values, error, scale, sigmas));
    }
    tracks.push_back(std::move(track));
  }
  return tracks;
}

ModelComparison compare_models(const fields::ModelResult& reference,
                               const fields::ModelResult& candidate, double sigmas) {
  ModelComparison out;
  out.reference = reference.model;
  out.candidate = candidate.model;
  if (reference.fields && candidate.fields && same_bins(*reference.fields, *candidate.fields)) {
    const auto pairs = common_snapshots(*reference.fields, *candidate.fields);
    std::vector<std::string> names;
    if (!pairs.empty()) {
      const auto &r = reference.fields->snapshots[pairs.front().first],
                 &k = candidate.fields->snapshots[pairs.front().second];
      for (const std::string& name : fields::hydrodynamic_fields()) {
        const auto& c = fields::field_column(name);
        if (!(r.*c.values).empty() && !(k.*c.values).empty()) names.push_back(name);
      }
    }
    for (const auto& [i, j] : pairs) out.t.push_back(reference.fields->snapshots[i].t);
    out.fields = compare_field_series(*reference.fields, *candidate.fields, pairs, names, sigmas);
  }
  for (const auto& r : reference.observables) {
    const fields::Observable* k = candidate.observable(r.name);
    if (!k) continue;
    ObservableDifference d;
    d.name = r.name;
    d.reference = r.value;
    d.candidate = k->value;
    d.relative = k->value / r.value - 1.0;
    const double se_r = std::isfinite(r.standard_error) ? r.standard_error : 0.0;
    const double se_k = std::isfinite(k->standard_error) ? k->standard_error : 0.0;
    const double se = std::sqrt(se_r * se_r + se_k * se_k);
    d.sigmas = se > 0.0 ? std::abs(k->value - r.value) / se : kNaN;
    out.observables.push_back(d);
  }
  return out;
}

}  // namespace granvv::compare
