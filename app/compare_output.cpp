#include "app/compare_output.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "app/md_output.hpp"
#include "app/summary.hpp"
#include "compare/haff_fit.hpp"
#include "fields/hdf5_datasets.hpp"
#include "hydro/haff.hpp"
#include "scene/json_numbers.hpp"

namespace granvv::app {
namespace {

using h5::write_attribute;
using h5::write_vector;
using nlohmann::json;

json numbers(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(number_or_null(x));
  return a;
}

std::vector<double> flatten(const std::vector<std::vector<double>>& rows) {
  std::vector<double> all;
  for (const auto& r : rows) all.insert(all.end(), r.begin(), r.end());
  return all;
}

void write_rows(H5::Group& g, const std::string& name,
                const std::vector<std::vector<double>>& rows) {
  if (!rows.empty()) h5::write_matrix(g, name, flatten(rows), rows.size());
}

// One column of a FieldSeries as rows over its snapshots.
std::vector<std::vector<double>> column_rows(const fields::FieldSeries& series,
                                             std::vector<double> fields::FieldSnapshot::*column) {
  std::vector<std::vector<double>> rows;
  for (const auto& s : series.snapshots) rows.push_back(s.*column);
  return rows;
}

// The per-time metrics of a field, by the name both outputs use (summary.json, results.h5).
using Metric = double compare::FieldDifference::*;
const std::vector<std::pair<const char*, Metric>> kMetrics = {
    {"l1", &compare::FieldDifference::l1},
    {"l2", &compare::FieldDifference::l2},
    {"linf", &compare::FieldDifference::linf},
    {"fraction_within", &compare::FieldDifference::fraction_within},
    {"worst_z", &compare::FieldDifference::worst_z},
    {"scale", &compare::FieldDifference::scale},
};

std::vector<double> per_time(const compare::FieldTrack& track, Metric metric) {
  std::vector<double> v;
  for (const auto& d : track.at) v.push_back(d.*metric);
  return v;
}

// The flow by inertia's measures that survive noise, and the central density that does not
// (CompareOutcome::InertiaMeasure, docs/outputs.md).
json inertia_measures_summary(const CompareOutcome& out) {
  const auto series = [](const CompareOutcome::InertiaMeasure& m) {
    return json{{"md", numbers(m.md)},
                {"md_error", numbers(m.md_error)},
                {"hydro", numbers(m.hydro)},
                {"inertia", numbers(m.inertia)}};
  };
  return {{"central_window", out.central_window},
          {"v_mode", series(out.v_mode)},
          {"n_mode", series(out.n_mode)},
          {"window_mass", series(out.window_mass)},
          {"n_centre", series(out.n_centre)}};
}

// Growth of each density mode from the first to the last compared time, |n_k(t)| / |n_k(0)|:
// particles (rms over seeds), hydro, and linear theory from each seed's own t = 0 perturbation.
json modes_summary(const CompareOutcome& out) {
  if (out.theory_rate.empty() || out.md_modes.empty()) return nullptr;
  auto growth = [](const std::vector<std::vector<double>>& rows) {
    std::vector<double> g;
    for (std::size_t k = 0; k < rows.front().size(); ++k) g.push_back(rows.back()[k] / rows[0][k]);
    return numbers(g);
  };
  std::vector<double> k;
  for (std::size_t i = 1; i <= out.theory_rate.size(); ++i) k.push_back(double(i));
  return {{"k", numbers(k)},
          {"theory_rate", numbers(out.theory_rate)},
          {"growth_md", growth(out.md_modes)},
          {"growth_hydro", growth(out.hydro_modes)},
          {"growth_theory", growth(out.theory_modes)}};
}

}  // namespace

json compare_summary(const CompareScene& scene, const HydroScene& hydro,
                     const HydroOutcome& hydro_out, const MdScene& md, const MdOutcome& md_out,
                     const CompareOutcome& out) {
  const auto& sc = md.spec.scene;
  json fields = json::object();
  for (const auto& f : out.fields) {
    json& entry = fields[f.name];
    for (const auto& [name, metric] : kMetrics) entry[name] = numbers(per_time(f.track, metric));
    json agrees = json::array();
    for (const auto& d : f.track.at)
      agrees.push_back(compare::field_agrees(d, scene.agreement_fraction));
    entry["agrees"] = agrees;
    entry["agrees_throughout"] =
        std::all_of(agrees.begin(), agrees.end(), [](const json& a) { return a.get<bool>(); });
    entry["error_source"] = f.error_source;
  }
  const auto& run = hydro_out.run;
  const double cell_steps = double(run.steps) * hydro.cells;
  // The hydro's Haff time (hydro/haff.hpp) in MD units.
  const double t0_hydro = sc.md_time(hydro::haff_time_scale(*make_hydro_closure(hydro)));
  const auto& haff = md_out.haff;
  return {
      {"status", "ok"},
      {"wall_seconds", run.wall_seconds + md_out.wall_seconds},
      {"hydro_initial", scene.hydro_from_md ? "md" : "case"},
      {"sigmas", scene.sigmas},
      {"agreement_fraction", scene.agreement_fraction},
      {"times", numbers(out.t)},
      {"times_md", numbers([&] {
         std::vector<double> t;
         for (double s : out.t) t.push_back(sc.md_time(s));
         return t;
       }())},
      {"fields", fields},
      {"agreement_window", number_or_null(out.window.until)},
      {"agreement_throughout", out.window.throughout},
      {"first_field_to_leave",
       out.window.first_out.empty() ? json(nullptr) : json(out.window.first_out)},
      {"left_at", number_or_null(out.window.left_at)},
      {"verdict", out.verdict},
      {"disagreement", out.disagreement},
      {"verdict_rule",
       {{"signal_to_noise_min", scene.verdict_rule.signal_to_noise_min},
        {"offset_sigmas", scene.verdict_rule.offset_sigmas}}},
      {"first_field_offset_sigmas", number_or_null(out.offset_sigmas)},
      {"signal_to_noise", number_or_null(out.signal_to_noise)},
      {"haff",
       {{"t0_measured", number_or_null(haff.t0)},
        {"t0_measured_error", number_or_null(haff.t0_error)},
        {"t0_theory_enskog", md_out.haff_t0_theory},
        {"t0_theory_dilute", md_out.haff_t0_theory_dilute},
        {"t0_hydro", t0_hydro},
        {"deviation_enskog",
         number_or_null(compare::relative_deviation(haff.t0, md_out.haff_t0_theory))},
        {"deviation_dilute",
         number_or_null(compare::relative_deviation(haff.t0, md_out.haff_t0_theory_dilute))},
        {"deviation_hydro", number_or_null(t0_hydro / haff.t0 - 1.0)},
        {"deviation_enskog_sigmas",
         number_or_null((haff.t0 - md_out.haff_t0_theory) / haff.t0_error)},
        {"deviation_dilute_sigmas",
         number_or_null((haff.t0 - md_out.haff_t0_theory_dilute) / haff.t0_error)},
        {"measured_deviation_from_hydro", number_or_null(haff.t0 / t0_hydro - 1.0)},
        {"deviation_hydro_sigmas", number_or_null((haff.t0 - t0_hydro) / haff.t0_error)},
        {"hydro_cools_differently", bool_or_null(compare::cools_differently(t0_hydro, haff))},
        {"cools_differently_relative", compare::kCoolsDifferentlyRelative},
        {"cools_differently_sigmas", compare::kCoolsDifferentlySigmas}}},
      {"cost",
       {{"hydro",
         {{"wall_seconds", run.wall_seconds},
          {"cells", hydro.cells},
          {"steps", run.steps},
          {"cell_steps", cell_steps},
          {"cell_steps_per_second", number_or_null(cell_steps / run.wall_seconds)}}},
        {"md",
         [&] {
           json cost = md_cost_summary(md_out);
           cost["particles"] = sc.particles;
           cost["ensemble"] = md.ensemble;
           return cost;
         }()},
        {"md_to_hydro_wall_ratio", number_or_null(md_out.wall_seconds / run.wall_seconds)}}},
      {"peak",
       {{"hydro_n", numbers(out.hydro_n_peak)},
        {"md_n", numbers(out.md_n_peak)},
        {"md_n_error", numbers(out.md_n_peak_error)},
        {"inertia_n", numbers(out.inertia_n_peak)}}},
      {"energy",
       {{"hydro_thermal", numbers(out.hydro_energy_thermal)},
        {"md_thermal", numbers(out.md_energy_thermal)},
        {"hydro_kinetic", numbers(out.hydro_energy_kinetic)},
        {"md_kinetic", numbers(out.md_energy_kinetic)}}},
      {"flow_by_inertia", inertia_measures_summary(out)},
      {"density_modes", modes_summary(out)},
      {"monitors_fired_at_parting", out.window.throughout || !out.window.left_at
                                        ? json(nullptr)
                                        : json(monitors_fired_by(run.validity, out.window))},
  };
}

json closure_comparison_summary(const CompareScene& scene, const HydroScene& hydro,
                                const HydroOutcome& hydro_out, const MdScene& md,
                                const MdOutcome& md_out, const CompareOutcome& out) {
  json entry = compare_summary(scene, hydro, hydro_out, md, md_out, out);
  entry["hydro"] = hydro_summary(hydro, hydro_out);
  return entry;
}

void write_compare_results(const std::filesystem::path& file, const CompareScene& scene,
                           const MdScene& md, const CompareOutcome& out, const std::string& root) {
  H5::Exception::dontPrint();
  H5::H5File h5(file.string(), H5F_ACC_RDWR);
  H5::Group g = h5.createGroup(root);
  const auto& sc = md.spec.scene;
  write_attribute(g, "sigmas", scene.sigmas);
  write_attribute(g, "agreement_fraction", scene.agreement_fraction);
  write_attribute(g, "hydro_initial", scene.hydro_from_md ? "md" : "case");
  write_attribute(g, "agreement_window", out.window.until.value_or(std::nan("")));
  write_attribute(g, "left_at", out.window.left_at.value_or(std::nan("")));
  write_attribute(g, "first_field_to_leave", out.window.first_out);
  write_attribute(g, "verdict", out.verdict);
  write_attribute(g, "disagreement", out.disagreement);
  write_attribute(g, "signal_to_noise", out.signal_to_noise);
  write_attribute(g, "verdict_signal_to_noise_min", scene.verdict_rule.signal_to_noise_min);
  write_attribute(g, "verdict_offset_sigmas", scene.verdict_rule.offset_sigmas);
  write_attribute(g, "box_length", sc.box_length);
  write_attribute(g, "particles", double(sc.particles));
  write_vector(g, "t", out.t);
  write_vector(g, "x", out.x);
  write_vector(g, "collision_clock", out.collision_clock);

  H5::Group fields = h5.createGroup(root + "/fields");
  for (const auto& f : out.fields) {
    H5::Group fg = fields.createGroup(f.name);
    write_attribute(fg, "error_source", f.error_source);
    const fields::FieldColumn& c = fields::field_column(f.name);
    write_rows(fg, "hydro", column_rows(out.hydro_on_bins, c.values));
    write_rows(fg, "md", column_rows(out.md_on_bins, c.values));
    write_rows(fg, "md_error", column_rows(out.md_on_bins, c.standard_error));
    for (const auto& [name, metric] : kMetrics) write_vector(fg, name, per_time(f.track, metric));
  }
  H5::Group peak = h5.createGroup(root + "/peak");
  write_vector(peak, "hydro_n", out.hydro_n_peak);
  write_vector(peak, "md_n", out.md_n_peak);
  write_vector(peak, "md_n_error", out.md_n_peak_error);
  write_vector(peak, "hydro_dvdx", out.hydro_dvdx_peak);
  write_vector(peak, "md_dvdx", out.md_dvdx_peak);
  write_vector(peak, "inertia_n", out.inertia_n_peak);
  H5::Group energy = h5.createGroup(root + "/energy");
  write_vector(energy, "hydro_thermal", out.hydro_energy_thermal);
  write_vector(energy, "md_thermal", out.md_energy_thermal);
  write_vector(energy, "hydro_kinetic", out.hydro_energy_kinetic);
  write_vector(energy, "md_kinetic", out.md_energy_kinetic);
  H5::Group inertia = h5.createGroup(root + "/inertia");
  write_rows(inertia, "n", out.inertia_n);
  write_rows(inertia, "v", out.inertia_v);
  if (!out.theory_rate.empty()) {
    H5::Group modes = h5.createGroup(root + "/modes");
    std::vector<double> k;
    for (std::size_t i = 1; i <= out.theory_rate.size(); ++i) k.push_back(double(i));
    write_vector(modes, "k", k);
    write_vector(modes, "theory_rate", out.theory_rate);
    write_rows(modes, "hydro", out.hydro_modes);
    write_rows(modes, "md", out.md_modes);
    write_rows(modes, "md_error", out.md_modes_error);
    write_rows(modes, "theory", out.theory_modes);
  }
}

}  // namespace granvv::app
