#include "scene/md_checkpoint.hpp"

#include <H5Cpp.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "fields/field_series.hpp"
#include "fields/field_series_file.hpp"
#include "fields/hdf5_datasets.hpp"
#include "md_bridge/every_rank.hpp"
#include "scene/atomic_file.hpp"
#include "scene/input_fingerprint.hpp"

namespace granvv::app {
namespace fs = std::filesystem;

namespace {

fs::path inputs_file(const fs::path& out_dir) {
  return checkpoint_folder(out_dir) / "inputs.json";
}

std::optional<std::string> inputs_text(const fs::path& out_dir) {
  std::ifstream in(inputs_file(out_dir), std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// What a member file carries to tie it to the inputs of its folder: the SHA-256 of inputs.json.
constexpr const char* kInputsAttribute = "inputs_sha256";
std::string inputs_stamp(const fs::path& out_dir) {
  const std::optional<std::string> text = inputs_text(out_dir);
  return text ? text_sha256(*text) : std::string("none");
}

fs::path member_file(const fs::path& out_dir, int member) {
  return checkpoint_folder(out_dir) / ("member_" + std::to_string(member) + ".h5");
}

// Rank k's block of member m's particles at step S: member_<m>.step<S>.rank<k>.h5.
std::string block_prefix(int member) {
  return "member_" + std::to_string(member) + ".step";
}
fs::path block_file(const fs::path& out_dir, int member, long long step, int rank) {
  return checkpoint_folder(out_dir) /
         (block_prefix(member) + std::to_string(step) + ".rank" + std::to_string(rank) + ".h5");
}

// Writes `write(file)` to file.partial, puts it on the disk and renames it to file; throws
// std::runtime_error naming file (the partial file removed).
template <class Write>
void write_replacing(const fs::path& file, const Write& write) {
  const fs::path partial = file.string() + ".partial";
  try {
    write(partial);
    sync_to_disk(partial);
    std::error_code error;
    fs::rename(partial, file, error);
    if (error) throw std::runtime_error(error.message());
    sync_to_disk(file.parent_path());
  } catch (const H5::Exception& e) {
    std::error_code ignored;
    fs::remove(partial, ignored);
    throw std::runtime_error("cannot write the checkpoint " + file.string() + ": " +
                             e.getDetailMsg());
  } catch (const std::exception& e) {
    std::error_code ignored;
    fs::remove(partial, ignored);
    throw std::runtime_error("cannot write the checkpoint " + file.string() + ": " + e.what());
  }
}

void write_particles(const fs::path& file, const md::EngineState& e) {
  H5::H5File h5(file.string(), H5F_ACC_TRUNC);
  H5::Group root = h5.openGroup("/");
  h5::write_attribute(root, "first_row", double(e.first_row));
  h5::write_vector(root, "x", e.particles.x);
  h5::write_vector(root, "v", e.particles.v);
  h5.close();
}

// Named arrays (an engine's time series, its own state arrays): each array a dataset of
// `values`, their names in order as the string list `names_key` of `holder`.
using NamedArrays = std::vector<std::pair<std::string, std::vector<double>>>;

void write_named_arrays(H5::Group& holder, const char* names_key, H5::Group& values,
                        const NamedArrays& arrays) {
  std::vector<std::string> names;
  for (const auto& [name, array] : arrays) {
    names.push_back(name);
    h5::write_vector(values, name, array);
  }
  h5::write_strings(holder, names_key, names);
}

NamedArrays read_named_arrays(const H5::Group& holder, const char* names_key,
                              const H5::Group& values) {
  NamedArrays arrays;
  for (const auto& name : h5::read_strings(holder, names_key))
    arrays.push_back({name, h5::read_doubles(values, name).values});
  return arrays;
}

void write_state(const fs::path& file, const MemberCheckpoint& c, const std::string& stamp) {
  const md::MdRunState& s = c.state;
  const md::MdRunResult& r = s.so_far;
  H5::H5File h5(file.string(), H5F_ACC_TRUNC);
  H5::Group root = h5.openGroup("/");
  h5::write_attribute(root, kInputsAttribute, stamp);
  h5::write_attribute(root, "finished", c.finished ? 1.0 : 0.0);
  h5::write_attribute(root, "particle_part_wall_seconds", c.particle_part_wall_seconds);
  h5::write_attribute(root, "t", s.t);
  h5::write_attribute(root, "next_output", double(s.next_output));
  h5::write_attribute(root, "next_frame", s.next_frame);
  h5::write_attribute(root, "status", r.status);
  h5::write_attribute(root, "stop_reason", r.stop_reason);
  h5::write_attribute(root, "wall_seconds", r.wall_seconds);
  h5::write_attribute(root, "steps", double(r.steps));

  H5::Group series = h5.createGroup("/series");
  for (const auto& column : md::md_series_columns()) {
    h5::write_vector(series, column.name, r.series.*column.values);
  }
  H5::Group engine_series = h5.createGroup("/series/engine");
  write_named_arrays(series, "engine_names", engine_series, r.series.engine);

  H5::Group fields = h5.createGroup("/fields");
  fields::write_field_series(fields, r.fields);

  H5::Group engine = h5.createGroup("/engine");
  std::vector<std::string> names;
  std::vector<double> values;
  for (const auto& [name, value] : s.engine.numbers) {
    names.push_back(name);
    values.push_back(value);
  }
  h5::write_strings(engine, "names", names);
  h5::write_vector(engine, "values", values);
  if (!s.engine.arrays.empty()) {  // the engine's own arrays, by name
    H5::Group arrays = h5.createGroup("/engine/arrays");
    write_named_arrays(engine, "array_names", arrays, s.engine.arrays);
  }
  if (s.engine.particle_blocks > 1) {  // the particles are in the ranks' block files
    h5::write_attribute(engine, "particle_blocks", double(s.engine.particle_blocks));
    h5::write_vector(engine, "x", {});
    h5::write_vector(engine, "v", {});
  } else {
    h5::write_vector(engine, "x", s.engine.particles.x);
    h5::write_vector(engine, "v", s.engine.particles.v);
  }
  h5.close();
}

// A count stored as a double attribute: an integer in [0, 2^53].
long long count_attribute(const H5::H5Object& o, const char* name) {
  const double value = h5::read_double_attribute(o, name);
  if (!(value >= 0.0 && value <= 9007199254740992.0 && value == std::floor(value)))
    throw std::runtime_error(std::string("its ") + name + " is " + std::to_string(value) +
                             ", not a count");
  return static_cast<long long>(value);
}

MemberCheckpoint read_state(const fs::path& file, const fs::path& out_dir, int member, int rank,
                            int ranks) {
  MemberCheckpoint c;
  md::MdRunState& s = c.state;
  md::MdRunResult& r = s.so_far;
  const H5::H5File h5(file.string(), H5F_ACC_RDONLY);
  const H5::Group root = h5.openGroup("/");
  if (!root.attrExists(kInputsAttribute) ||
      h5::read_string_attribute(root, kInputsAttribute) != inputs_stamp(out_dir))
    throw std::runtime_error("it was not written for the inputs of " +
                             inputs_file(out_dir).string());
  c.finished = h5::read_double_attribute(root, "finished") != 0.0;
  c.particle_part_wall_seconds = h5::read_double_attribute(root, "particle_part_wall_seconds");
  s.t = h5::read_double_attribute(root, "t");
  s.next_output = std::size_t(count_attribute(root, "next_output"));
  s.next_frame = h5::read_double_attribute(root, "next_frame");
  r.status = h5::read_string_attribute(root, "status");
  r.stop_reason = h5::read_string_attribute(root, "stop_reason");
  r.wall_seconds = h5::read_double_attribute(root, "wall_seconds");
  r.steps = count_attribute(root, "steps");

  const H5::Group series = h5.openGroup("/series");
  for (const auto& column : md::md_series_columns()) {
    r.series.*column.values = h5::read_doubles(series, column.name).values;
  }
  r.series.engine = read_named_arrays(series, "engine_names", h5.openGroup("/series/engine"));
  r.fields = fields::read_field_series(h5.openGroup("/fields"));

  const H5::Group engine = h5.openGroup("/engine");
  const std::vector<std::string> names = h5::read_strings(engine, "names");
  const std::vector<double> values = h5::read_doubles(engine, "values").values;
  if (names.size() != values.size()) throw std::runtime_error("engine numbers without names");
  for (std::size_t i = 0; i < names.size(); ++i) s.engine.numbers.push_back({names[i], values[i]});
  if (engine.nameExists("array_names"))
    s.engine.arrays = read_named_arrays(engine, "array_names", h5.openGroup("/engine/arrays"));
  s.engine.particles.x = h5::read_doubles(engine, "x").values;
  s.engine.particles.v = h5::read_doubles(engine, "v").values;
  if (engine.attrExists("particle_blocks")) {
    const int blocks =
        int(std::min<long long>(count_attribute(engine, "particle_blocks"), 1 << 30));
    if (blocks != ranks)
      throw std::runtime_error("its particles were saved in blocks by " + std::to_string(blocks) +
                               " MPI ranks, and this run has " + std::to_string(ranks) +
                               ": resume it under mpirun -np " + std::to_string(blocks));
    s.engine.particle_blocks = blocks;
    // Every rank's block, in ID order, for the checks of the whole state; this rank's is its own.
    for (int k = 0; k < blocks; ++k) {
      const fs::path path = block_file(out_dir, member, r.steps, k);
      const H5::H5File block(path.string(), H5F_ACC_RDONLY);
      const H5::Group block_root = block.openGroup("/");
      const long long first_row = count_attribute(block_root, "first_row");
      std::vector<double> x = h5::read_doubles(block_root, "x").values;
      std::vector<double> v = h5::read_doubles(block_root, "v").values;
      if (3 * first_row != (long long)c.all_blocks.x.size())
        throw std::runtime_error(path.string() + " begins at row " + std::to_string(first_row) +
                                 " where the blocks before it end at row " +
                                 std::to_string(c.all_blocks.x.size() / 3));
      if (k == rank) {
        s.engine.first_row = first_row;
        s.engine.particles = {x, v};
      }
      c.all_blocks.x.insert(c.all_blocks.x.end(), x.begin(), x.end());
      c.all_blocks.v.insert(c.all_blocks.v.end(), v.begin(), v.end());
    }
  }
  return c;
}

}  // namespace

fs::path checkpoint_folder(const fs::path& out_dir) {
  return out_dir / ".granvv-checkpoint";
}

std::optional<std::string> checkpointed_case(const fs::path& out_dir) {
  std::ifstream in(checkpoint_folder(out_dir) / "case.toml");
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string checkpoint_inputs_difference(const fs::path& out_dir, const nlohmann::json& now) {
  const std::optional<std::string> recorded = inputs_text(out_dir);
  if (!recorded) return "it has no record of its inputs (" + inputs_file(out_dir).string() + ")";
  return fingerprint_difference(nlohmann::json::parse(*recorded, nullptr, false), now);
}

void start_checkpoints(const fs::path& out_dir, const std::string& resolved_case,
                       const nlohmann::json& inputs) {
  remove_checkpoints(out_dir);
  const fs::path folder = checkpoint_folder(out_dir);
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) throw std::runtime_error("cannot make " + folder.string() + ": " + error.message());
  write_file_atomically(folder / "case.toml", resolved_case);
  write_file_atomically(inputs_file(out_dir), inputs.dump(1) + "\n");
}

void save_member_checkpoint(const fs::path& out_dir, int member, const MemberCheckpoint& c,
                            MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const md::EngineState& e = c.state.engine;
  const long long step = c.state.so_far.steps;
  const auto write_member = [&] {
    if (rank != 0) return;
    const std::string stamp = inputs_stamp(out_dir);
    write_replacing(member_file(out_dir, member),
                    [&](const fs::path& f) { write_state(f, c, stamp); });
    // The member file names this step's blocks now: the earlier ones go.
    std::error_code ignored;
    const std::string prefix = block_prefix(member), own = prefix + std::to_string(step) + ".";
    for (const auto& entry : fs::directory_iterator(checkpoint_folder(out_dir), ignored)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind(prefix, 0) == 0 && name.rfind(own, 0) != 0) fs::remove(entry, ignored);
    }
  };
  if (e.particle_blocks == 1) return write_member();  // rank 0 alone
  // Every rank its block first, under a name of this step; then rank 0 the member file.
  md::on_every_rank(comm, [&] {
    write_replacing(block_file(out_dir, member, step, rank),
                    [&](const fs::path& f) { write_particles(f, e); });
  });
  md::on_every_rank(comm, write_member);
}

std::vector<MemberCheckpoint> load_member_checkpoints(const fs::path& out_dir, int members,
                                                      int rank, int ranks) {
  H5::Exception::dontPrint();
  std::vector<MemberCheckpoint> loaded;
  for (int m = 0; m < members; ++m) {
    const fs::path file = member_file(out_dir, m);
    if (!fs::exists(file)) {
      loaded.push_back({});
      loaded.back().missing = true;
      continue;
    }
    try {
      loaded.push_back(read_state(file, out_dir, m, rank, ranks));
    } catch (const H5::Exception& e) {
      throw std::runtime_error("cannot read the checkpoint " + file.string() + ": " +
                               e.getDetailMsg());
    } catch (const std::exception& e) {
      throw std::runtime_error("cannot read the checkpoint " + file.string() + ": " + e.what());
    }
  }
  while (!loaded.empty() && loaded.back().missing) loaded.pop_back();
  return loaded;
}

namespace {

// Why a saved run state cannot belong to a run of spec ("" if it can): its loop's place, its
// series and snapshots, and its particles checked against the scene before a run uses them.
std::string state_problem(const MemberCheckpoint& c, const md::MdRunSpec& spec) {
  const md::MdRunState& s = c.state;
  const md::MdRunResult& r = s.so_far;
  const auto number = [](double v) { return std::to_string(v); };
  if (!c.finished) {
    if (!(s.t >= 0.0 && s.t <= spec.t_end)) return "t = " + number(s.t) + " outside the run";
    if (!std::isfinite(s.next_frame)) return "next_frame = " + number(s.next_frame);
    if (s.next_output > spec.output_times.size())
      return "next_output = " + std::to_string(s.next_output) + " beyond md.output_times";
    if (r.status != "running") return "an unfinished member with status '" + r.status + "'";
  } else if (r.status != "ok" && r.status != "failed") {
    return "a finished member with status '" + r.status + "'";
  }
  const std::size_t samples = r.series.t.size();
  if (!c.finished && samples == 0) return "no samples";
  for (const auto& column : md::md_series_columns()) {
    if ((r.series.*column.values).size() != samples)
      return std::string("series ") + column.name + " has " +
             std::to_string((r.series.*column.values).size()) + " values for " +
             std::to_string(samples) + " times";
  }
  for (const auto& [name, values] : r.series.engine) {
    if (values.size() != samples) return "engine series " + name + " of another length";
  }
  // What a run always measures is finite (the pressure columns may be absent, NaN).
  for (const auto* values : {&r.series.t, &r.series.T, &r.series.energy_thermal,
                             &r.series.energy_kinetic_x, &r.series.energy_kinetic_y,
                             &r.series.energy_total, &r.series.momentum_x, &r.series.momentum_y}) {
    for (const double v : *values)
      if (!std::isfinite(v)) return "a non-finite value (" + number(v) + ") in its series";
  }
  for (std::size_t k = 1; k < samples; ++k) {
    if (!(r.series.t[k] > r.series.t[k - 1])) return "series times out of order";
  }
  // A member is saved at a sample or inside the segment after it, never before its last sample
  // (continuing from an earlier t would sample the same times twice).
  if (!c.finished && s.t < r.series.t.back())
    return "t = " + number(s.t) + " before its last sample at t = " + number(r.series.t.back());
  const double lx = spec.scene.box_length;
  const auto bins = std::size_t(spec.bins);
  if (r.fields.bin_edges != fields::FieldSeries::on_bins(-0.5 * lx, lx, spec.bins).bin_edges)
    return "snapshots on other bins than md.bins = " + std::to_string(spec.bins);
  if (!c.finished && r.fields.snapshots.size() != s.next_output)
    return std::to_string(r.fields.snapshots.size()) +
           " snapshots for next_output = " + std::to_string(s.next_output);
  if (r.fields.snapshots.size() > spec.output_times.size()) return "more snapshots than outputs";
  for (const auto& snap : r.fields.snapshots) {
    for (const auto* column : {&snap.x, &snap.n, &snap.v_x, &snap.T}) {
      if (column->size() != bins)
        return "a snapshot column of " + std::to_string(column->size()) + " values for " +
               std::to_string(bins) + " bins";
      // NaN: a bin without particles (coarse_grainer.hpp); never infinite.
      for (const double v : *column)
        if (std::isinf(v)) return "an infinite value in a snapshot";
    }
    for (const double v : snap.x)
      if (!std::isfinite(v)) return "a snapshot bin at x = " + number(v);
  }
  const md::ParticleFrame& p = s.engine.particles;
  const std::size_t expected = 3 * std::size_t(spec.scene.particles);
  if (!p.x.empty() || !p.v.empty()) {
    if (s.engine.particle_blocks == 1 && (p.x.size() != expected || p.v.size() != expected))
      return std::to_string(p.x.size() / 3) + " particles for a scene of " +
             std::to_string(spec.scene.particles);
    if (p.x.size() != p.v.size() || p.x.size() % 3 != 0) return "particle arrays of other sizes";
    for (const auto* values : {&p.x, &p.v})
      for (const double v : *values)
        if (!std::isfinite(v)) return "a particle with a non-finite position or velocity";
  } else if (!c.finished && s.engine.particle_blocks == 1) {
    return "no particles";
  }
  for (const auto& [name, value] : s.engine.numbers)
    if (!std::isfinite(value)) return "the engine's " + name + " = " + number(value);
  return "";
}

}  // namespace

void check_member_checkpoints(const std::vector<MemberCheckpoint>& checkpoints,
                              const md::MdRunSpec& spec, const md::ParticleEngine& engine) {
  for (std::size_t m = 0; m < checkpoints.size(); ++m) {
    const MemberCheckpoint& c = checkpoints[m];
    if (c.missing) continue;
    std::string problem = state_problem(c, spec);
    if (problem.empty() && !c.finished) {
      md::EngineState whole = c.state.engine;
      if (whole.particle_blocks > 1) {
        whole.particles = c.all_blocks;
        whole.particle_blocks = 1;
        whole.first_row = 0;
      }
      const std::string refused = engine.state_problem(whole);
      if (!refused.empty()) problem = "a state the engine refuses (" + refused + ")";
    }
    if (!problem.empty())
      throw std::runtime_error("the checkpoint of member " + std::to_string(m) + " holds " +
                               problem);
  }
}

void remove_checkpoints(const fs::path& out_dir) {
  std::error_code ignored;
  fs::remove_all(checkpoint_folder(out_dir), ignored);
}

}  // namespace granvv::app
