#include "app/sweep_command.hpp"

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "app/mpi_ranks.hpp"
#include "app/output_folder.hpp"
#include "app/report_command.hpp"
#include "app/run_command.hpp"
#include "app/summary.hpp"
#include "compare/cooling_sweep.hpp"
#include "models/compare_scene.hpp"
#include "scene/atomic_file.hpp"
#include "scene/case_catalog.hpp"
#include "scene/case_config.hpp"
#include "scene/hydro_scene.hpp"
#include "scene/input_fingerprint.hpp"
#include "scene/interruption.hpp"
#include "scene/json_numbers.hpp"
#include "scene/md_checkpoint.hpp"
#include "scene/md_scene.hpp"

namespace granvv::app {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct SweptKey {
  std::string key;
  std::vector<std::string> values;
};

std::vector<std::string> split_commas(const std::string& s) {
  std::vector<std::string> parts;
  std::string part;
  for (char c : s) {
    if (c == ',') {
      parts.push_back(part), part.clear();
    } else {
      part += c;
    }
  }
  parts.push_back(part);
  return parts;
}

// The one --set whose value is a comma-separated list (not a TOML array or string) is swept;
// the others apply to every point.
SweptKey split_sweep(const std::vector<std::string>& sets, std::vector<std::string>& fixed) {
  std::optional<SweptKey> swept;
  for (const auto& s : sets) {
    const auto eq = s.find('=');
    const std::string value = eq == std::string::npos ? "" : s.substr(eq + 1);
    const bool list = eq != std::string::npos && value.find(',') != std::string::npos &&
                      value.front() != '[' && value.front() != '"' && value.front() != '\'';
    if (!list) {
      fixed.push_back(s);
      continue;
    }
    if (swept) {
      throw ConfigError("--set " + s + ": only one key can be swept, and --set " + swept->key +
                        "=... already is");
    }
    swept = SweptKey{s.substr(0, eq), split_commas(value)};
    for (const auto& v : swept->values) {
      if (v.empty()) throw ConfigError("--set " + s + ": an empty value in the list");
    }
  }
  if (!swept) {
    throw ConfigError(
        "granvv sweep needs one --set KEY=V1,V2,... with the values to sweep (e.g. --set "
        "md.restitution=0.7,0.8,0.9)");
  }
  const KeySpec* spec = find_key_spec(swept->key);
  if (spec && spec->type != ValueType::real && spec->type != ValueType::integer) {
    throw ConfigError("--set " + swept->key + "=...: " + swept->key + " is " +
                      type_phrase(spec->type) + "; only numeric keys can be swept");
  }
  return *swept;
}

std::string folder_name(const std::string& key, const std::string& value) {
  std::string s = key + "=" + value;
  for (char& c : s) {
    if (c == '/' || c == '\\' || c == ' ') c = '_';
  }
  return s;
}

json value_or_null(const json& j, const char* key) {
  return j.is_object() && j.contains(key) ? j[key] : json(nullptr);
}

json read_json_or_null(const fs::path& file) {
  std::ifstream in(file);
  if (!in) return nullptr;
  try {
    json j;
    in >> j;
    return j;
  } catch (const json::exception&) {
    return nullptr;
  }
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Why a point folder does not hold a finished run of exactly this resolved case and these
// input files ("" if it does: a re-run of the sweep keeps it instead of running it again).
std::string point_not_complete(const fs::path& point_dir, const std::string& resolved_toml,
                               const json& inputs) {
  const json summary = read_json_or_null(point_dir / "summary.json");
  const json status = value_or_null(summary, "status");
  if (!(status == "ok" || status == "singularity" || status == "closure_limit"))
    return "no finished run";
  if (read_text(point_dir / "case.toml") != resolved_toml) return "another case";
  return fingerprint_difference(value_or_null(summary, "inputs"), inputs);
}

// Two values that resolve to the same number, or that would share a folder, are one point.
void refuse_repeated_values(const SweptKey& swept, const std::vector<double>& numeric_values) {
  for (std::size_t i = 0; i < swept.values.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (numeric_values[i] == numeric_values[j] ||
          folder_name(swept.key, swept.values[i]) == folder_name(swept.key, swept.values[j])) {
        throw ConfigError("--set " + swept.key + "=...: the values " + swept.values[j] + " and " +
                          swept.values[i] + " are the same point; give each value once");
      }
    }
  }
}

void write_sweep_json(const fs::path& dir, const json& sweep) {
  write_file_atomically(dir / "sweep.json", summary_text(sweep));
}

// The regression on the restitution coefficient over the points that measured a Haff time.
json cooling_analysis(const json& points, double power_r_min, double sigmas) {
  std::vector<compare::CoolingPoint> cooling;
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const json& md = points[i]["md"];
    if (!md.is_object() || !md["haff_t0_measured"].is_number() ||
        !md["haff_t0_measured_error"].is_number()) {
      continue;
    }
    compare::CoolingPoint p;
    p.restitution = md["restitution"].get<double>();
    p.t0 = md["haff_t0_measured"].get<double>();
    p.t0_error = md["haff_t0_measured_error"].get<double>();
    p.t0_enskog = md["haff_t0_theory"].get<double>();
    p.t0_dilute = md["haff_t0_theory_dilute"].get<double>();
    p.t0_paper = md["haff_t0_paper"].get<double>();
    if (!(p.t0_error > 0) || !(p.restitution < 1)) continue;
    cooling.push_back(p);
    index.push_back(i);
  }
  if (cooling.empty()) return nullptr;
  const auto s = compare::analyse_cooling_sweep(cooling, power_r_min, sigmas);
  json rows = json::array();
  for (std::size_t i = 0; i < cooling.size(); ++i) {
    rows.push_back({{"point", index[i]},
                    {"restitution", cooling[i].restitution},
                    {"t0", cooling[i].t0},
                    {"t0_error", cooling[i].t0_error},
                    {"zeta", s.zeta[i]},
                    {"zeta_error", s.zeta_error[i]},
                    {"zeta_enskog", s.zeta_enskog[i]},
                    {"zeta_dilute", s.zeta_dilute[i]},
                    {"zeta_paper", s.zeta_paper[i]},
                    {"zeta_paper_enskog", s.zeta_paper_enskog[i]},
                    {"deviation_enskog", s.enskog_deviation[i]},
                    {"deviation_enskog_sigmas", s.enskog_deviation_sigmas[i]},
                    {"enskog_beyond_sigmas", bool(s.enskog_beyond_sigmas[i])},
                    {"paper_deviation", s.paper_deviation[i]},
                    {"paper_deviation_sigmas", s.paper_deviation_sigmas[i]},
                    {"paper_beyond_sigmas", bool(s.paper_beyond_sigmas[i])}});
  }
  json power = nullptr;
  if (s.power) {
    power = {
        {"power", s.power->power},         {"power_error", s.power->power_error},
        {"prefactor", s.power->prefactor}, {"chi2_per_dof", number_or_null(s.power->chi2_per_dof)},
        {"points", s.power->points},       {"r_min", power_r_min}};
    // Kinetic theory: zeta ~ (1 - r^2)^1 (docs/physics.md §4).
    power["deviation_from_one_sigmas"] = number_or_null(s.power_deviation_from_one_sigmas);
    power["consistent_with_one"] = bool_or_null(s.power_consistent_with_one);
  }
  return {{"points", rows},
          {"power_of_one_minus_r2", power},
          {"paper_departs_at_r", number_or_null(s.paper_departs_at)},
          {"sigmas", sigmas}};
}

// One point of the sweep: its run (or the finished run already in its folder, or its
// checkpoints continued), and its row of sweep.json; status is the run's exit code.
json sweep_point(const SweepOptions& options, const Ranks& ranks, const fs::path& dir,
                 const SweptKey& swept, const std::vector<std::string>& fixed, std::size_t index,
                 double numeric_value, const std::string& resolved, const json& inputs,
                 int& status) {
  const std::string& value = swept.values[index];
  RunOptions run;
  run.case_name = options.case_name;
  run.out_dir = (dir / folder_name(swept.key, value)).string();
  run.sets = fixed;
  run.sets.push_back(swept.key + "=" + value);
  run.quiet = options.quiet;
  run.report = options.report;
  // Rank 0 decides (every rank then runs the point, or none): its folder is the one written.
  const std::string not_complete =
      writers_value(ranks, ranks.writer() ? point_not_complete(run.out_dir, resolved, inputs) : "");
  const bool reused = not_complete.empty();
  // A point stopped midway continues from its checkpoints if they are of these very inputs.
  run.resume =
      !reused &&
      writers_value(ranks, ranks.writer() && checkpointed_case(run.out_dir) &&
                                   checkpoint_inputs_difference(run.out_dir, inputs).empty()
                               ? "resume"
                               : "") == "resume";
  // A finished run of this case made from other files is run again, and the log says why.
  const bool inputs_changed =
      !reused && not_complete != "no finished run" && not_complete != "another case";
  if (ranks.writer())
    std::cerr << "sweep: point " << index + 1 << "/" << swept.values.size() << ": " << swept.key
              << " = " << value
              << (reused       ? ": already complete in "
                  : run.resume ? ": continues its checkpoint in "
                  : inputs_changed
                      ? ": its inputs changed since (" + not_complete + "), runs again -> "
                      : " -> ")
              << run.out_dir << "\n";
  status = reused ? 0 : run_command(run);
  if (!ranks.writer()) return nullptr;  // the writer's summary.json may not be there yet
  json point = {{"value", numeric_value},
                {"dir", fs::path(run.out_dir).filename().string()},
                {"exit_code", status},
                {"reused", reused}};
  // An interrupted run leaves the point's previous outputs in place: they are not its result.
  const bool stopped = !reused && interruption_signal() && status == interrupted_exit_code();
  const json summary =
      stopped ? json(nullptr) : read_json_or_null(fs::path(run.out_dir) / "summary.json");
  point["status"] = stopped ? json("interrupted") : value_or_null(summary, "status");
  point["md"] = value_or_null(summary, "md");
  point["hydro_wall_seconds"] = summary.is_object() && summary["hydro"].is_object()
                                    ? summary["hydro"]["wall_seconds"]
                                    : json(nullptr);
  point["compare"] = value_or_null(summary, "compare");
  // The coefficients measured from the particles, where the scene measures them (the sweep
  // page draws them against the swept key); absent otherwise, so other sweeps are unchanged.
  if (summary.is_object() && summary.contains("transport"))
    point["transport"] = summary["transport"];
  return point;
}

// The points of the sweep and sweep.json (rank 0's), once its folder is locked; the exit code.
int sweep_points(const SweepOptions& options, const Ranks& ranks, const fs::path& dir,
                 const SweptKey& swept, const std::vector<std::string>& fixed,
                 const std::string& case_name, const std::vector<double>& numeric_values,
                 const std::vector<std::string>& resolved, const std::vector<json>& inputs);

}  // namespace

int sweep_command(const SweepOptions& options) {
  // 1. Every point's case is validated before anything runs or is written.
  std::vector<std::string> fixed;
  SweptKey swept;
  std::string case_name;
  std::vector<double> numeric_values;  // each value as the case resolved it
  std::vector<std::string> resolved;   // each point's resolved case (its case.toml)
  std::vector<json> inputs;            // and the fingerprint of its inputs
  try {
    swept = split_sweep(options.sets, fixed);
    const CaseSource source = locate_case(options.case_name);
    for (const auto& value : swept.values) {
      auto sets = fixed;
      sets.push_back(swept.key + "=" + value);
      const CaseConfig config = CaseConfig::from_string(source.text, source.origin, sets);
      refuse_keys_of_models_not_run(config);
      HydroScene hydro = hydro_scene_from(config);
      (void)md_scene_from(config, hydro);
      (void)compare_scene_from(config);
      case_name = config.name();
      numeric_values.push_back(find_key_spec(swept.key)->type == ValueType::integer
                                   ? double(config.integer(swept.key))
                                   : config.real(swept.key));
      resolved.push_back(config.resolved_toml());
      inputs.push_back(input_fingerprint(config));
    }
    refuse_repeated_values(swept, numeric_values);
  } catch (const ConfigError& e) {
    report_input_error(e);
    return 2;
  }
  std::string key_name = swept.key;
  for (char& c : key_name) c = c == '.' ? '_' : c;
  const fs::path dir = options.out_dir.empty()
                           ? fs::path("out") / (case_name + "-sweep-" + key_name)
                           : fs::path(options.out_dir);
  // Under mpirun every rank runs each point (its particle part is collective) and rank 0 alone
  // holds the lock and writes sweep.json; every rank ends with rank 0's exit code.
  const Ranks ranks = join_ranks(false);
  std::optional<FolderLock> lock;  // one sweep at a time in a folder
  std::string lock_error;
  if (ranks.writer()) {
    try {
      lock.emplace(dir);
    } catch (const OutputFolderError& e) {
      lock_error = e.what();
    }
  }
  if (!all_ranks_ok(ranks, lock_error.empty())) {
    if (ranks.writer()) std::cerr << "granvv: error: " << lock_error << "\n";
    return 2;
  }
  // As in `granvv run`: several ranks must not stop at their own safe points.
  if (ranks.size == 1) catch_interruptions();
  const int exit_code =
      sweep_points(options, ranks, dir, swept, fixed, case_name, numeric_values, resolved, inputs);
  return writers_exit_code(ranks, exit_code);
}

namespace {

int sweep_points(const SweepOptions& options, const Ranks& ranks, const fs::path& dir,
                 const SweptKey& swept, const std::vector<std::string>& fixed,
                 const std::string& case_name, const std::vector<double>& numeric_values,
                 const std::vector<std::string>& resolved, const std::vector<json>& inputs) {
  const bool writer = ranks.writer();

  // 2. One run per value; sweep.json is rewritten after every point, so a stopped sweep keeps
  // what it finished. Its status says "incomplete" until the sweep ends (it is true both while
  // the sweep runs and after it was killed); a point that already holds a finished run of the
  // same resolved case is kept, so a re-run resumes an interrupted sweep.
  const auto start = std::chrono::steady_clock::now();
  json sweep = {{"case", case_name},
                {"key", swept.key},
                {"values", swept.values},
                {"fixed_sets", fixed},
                {"granvv_version", GRANVV_VERSION},
                {"status", "incomplete"},
                {"pid", ::getpid()},
                {"points", json::array()},
                {"cooling", nullptr}};
  int exit_code = 0;
  try {
    if (writer) write_sweep_json(dir, sweep);
    for (std::size_t i = 0; i < swept.values.size() && !interruption_signal(); ++i) {
      int status = 0;
      const json point = sweep_point(options, ranks, dir, swept, fixed, i, numeric_values[i],
                                     resolved[i], inputs[i], status);
      if (!writer) continue;
      const std::string& value = swept.values[i];
      if (status != 0) exit_code = 1;
      sweep["points"].push_back(point);
      const json& md = point["md"];
      if (md.is_object() && md["haff_t0_measured"].is_number()) {
        std::cerr << "sweep: " << swept.key << " = " << value
                  << ": Haff t0 = " << md["haff_t0_measured"].get<double>() << " +- "
                  << value_or_null(md, "haff_t0_measured_error")
                  << " (kinetic theory with chi: " << md["haff_t0_theory"].get<double>() << ")\n";
      }
      sweep["wall_seconds"] =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      write_sweep_json(dir, sweep);
      if (hdf5_broken()) {  // a full disk: the next points cannot be written either
        sweep["status"] = "failed";
        write_sweep_json(dir, sweep);
        std::cerr << "granvv: error: sweep stopped after a failed write; "
                  << (dir / "sweep.json").string() << " holds the points so far\n";
        end_process_now(1);
      }
    }
    if (!writer) return 0;  // rank 0's exit code is the sweep's
    if (interruption_signal()) {
      sweep["status"] = "interrupted";
      write_sweep_json(dir, sweep);
      std::cerr << "granvv: sweep interrupted; " << (dir / "sweep.json").string()
                << " holds the points finished so far, and a re-run of the same sweep keeps them\n";
      return interrupted_exit_code();
    }
  } catch (const std::exception& e) {
    std::cerr << "granvv: error: " << e.what() << "\n";
    return 1;
  }
  try {
    sweep["cooling"] =
        cooling_analysis(sweep["points"], options.power_r_min, compare::kCoolingSweepSigmas);
  } catch (const std::exception& e) {
    sweep["cooling_error"] = e.what();
  }
  sweep["status"] = exit_code == 0 ? "ok" : "failed";
  try {
    write_sweep_json(dir, sweep);
  } catch (const std::exception& e) {
    std::cerr << "granvv: error: " << e.what() << "\n";
    return 1;
  }
  if (sweep["cooling"].is_object() && sweep["cooling"]["power_of_one_minus_r2"].is_object()) {
    const auto& p = sweep["cooling"]["power_of_one_minus_r2"];
    std::cerr << "sweep: cooling rate ~ (1 - r^2)^p with p = " << p["power"].get<double>() << " +- "
              << p["power_error"].get<double>() << " over r >= " << options.power_r_min << "\n";
  }
  std::cerr << "sweep: wrote " << (dir / "sweep.json").string() << "\n";
  if (options.report) {
    const int status = build_report(dir);
    if (status != 0) {
      std::cerr << "granvv: error: sweep report failed (exit " << status
                << "); sweep.json is complete\n";
      exit_code = exit_code ? exit_code : 1;
    }
  }
  return exit_code;
}

}  // namespace

}  // namespace granvv::app
