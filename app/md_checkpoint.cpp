#include "app/md_checkpoint.hpp"

#include <H5Cpp.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "app/atomic_file.hpp"
#include "fields/field_series_file.hpp"
#include "fields/hdf5_datasets.hpp"

namespace granvv::app {
namespace fs = std::filesystem;

namespace {

fs::path member_file(const fs::path& out_dir, int member) {
  return checkpoint_folder(out_dir) / ("member_" + std::to_string(member) + ".h5");
}

void write_state(const fs::path& file, const MemberCheckpoint& c) {
  const md::MdRunState& s = c.state;
  const md::MdRunResult& r = s.so_far;
  H5::H5File h5(file.string(), H5F_ACC_TRUNC);
  H5::Group root = h5.openGroup("/");
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
  std::vector<std::string> engine_names;
  for (const auto& [name, values] : r.series.engine) {
    engine_names.push_back(name);
    h5::write_vector(engine_series, name, values);
  }
  h5::write_strings(series, "engine_names", engine_names);

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
  h5::write_vector(engine, "x", s.engine.particles.x);
  h5::write_vector(engine, "v", s.engine.particles.v);
  h5.close();
}

MemberCheckpoint read_state(const fs::path& file) {
  MemberCheckpoint c;
  md::MdRunState& s = c.state;
  md::MdRunResult& r = s.so_far;
  const H5::H5File h5(file.string(), H5F_ACC_RDONLY);
  const H5::Group root = h5.openGroup("/");
  c.finished = h5::read_double_attribute(root, "finished") != 0.0;
  c.particle_part_wall_seconds = h5::read_double_attribute(root, "particle_part_wall_seconds");
  s.t = h5::read_double_attribute(root, "t");
  s.next_output = static_cast<std::size_t>(h5::read_double_attribute(root, "next_output"));
  s.next_frame = h5::read_double_attribute(root, "next_frame");
  r.status = h5::read_string_attribute(root, "status");
  r.stop_reason = h5::read_string_attribute(root, "stop_reason");
  r.wall_seconds = h5::read_double_attribute(root, "wall_seconds");
  r.steps = static_cast<long long>(h5::read_double_attribute(root, "steps"));

  const H5::Group series = h5.openGroup("/series");
  for (const auto& column : md::md_series_columns()) {
    r.series.*column.values = h5::read_doubles(series, column.name).values;
  }
  const H5::Group engine_series = h5.openGroup("/series/engine");
  for (const auto& name : h5::read_strings(series, "engine_names")) {
    r.series.engine.push_back({name, h5::read_doubles(engine_series, name).values});
  }
  r.fields = fields::read_field_series(h5.openGroup("/fields"));

  const H5::Group engine = h5.openGroup("/engine");
  const std::vector<std::string> names = h5::read_strings(engine, "names");
  const std::vector<double> values = h5::read_doubles(engine, "values").values;
  if (names.size() != values.size()) throw std::runtime_error("engine numbers without names");
  for (std::size_t i = 0; i < names.size(); ++i) s.engine.numbers.push_back({names[i], values[i]});
  s.engine.particles.x = h5::read_doubles(engine, "x").values;
  s.engine.particles.v = h5::read_doubles(engine, "v").values;
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

std::string checkpointed_case_difference(const std::string& checkpointed_case,
                                         const CaseConfig& config) {
  static const std::set<std::string> outside_the_results{
      "md.checkpoint_interval", "md.accept_long_run", "hydro.progress_seconds"};
  std::map<std::string, std::string> before, now;
  try {
    for (auto& [key, value] :
         CaseConfig::from_string(checkpointed_case, "the checkpoint", {}).flattened())
      before[key] = value;
  } catch (const ConfigError& e) {
    return std::string("its case.toml does not parse (") + e.what() + ")";
  }
  for (auto& [key, value] : config.flattened()) now[key] = value;
  for (const auto& [key, value] : now) {
    if (outside_the_results.count(key)) continue;
    const auto found = before.find(key);
    const std::string was = found == before.end() ? "(absent)" : found->second;
    if (was != value) return key + " = " + was + " in the checkpoint, " + value + " now";
  }
  for (const auto& [key, value] : before) {
    if (!outside_the_results.count(key) && !now.count(key))
      return key + " = " + value + " in the checkpoint, absent now";
  }
  return "";
}

void start_checkpoints(const fs::path& out_dir, const std::string& resolved_case) {
  remove_checkpoints(out_dir);
  const fs::path folder = checkpoint_folder(out_dir);
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) throw std::runtime_error("cannot make " + folder.string() + ": " + error.message());
  write_file_atomically(folder / "case.toml", resolved_case);
}

void save_member_checkpoint(const fs::path& out_dir, int member, const MemberCheckpoint& c) {
  const fs::path file = member_file(out_dir, member);
  const fs::path partial = file.string() + ".partial";
  try {
    write_state(partial, c);
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

std::vector<MemberCheckpoint> load_member_checkpoints(const fs::path& out_dir, int members) {
  H5::Exception::dontPrint();
  std::vector<MemberCheckpoint> loaded;
  for (int m = 0; m < members; ++m) {
    const fs::path file = member_file(out_dir, m);
    if (!fs::exists(file)) break;
    try {
      loaded.push_back(read_state(file));
    } catch (const H5::Exception& e) {
      throw std::runtime_error("cannot read the checkpoint " + file.string() + ": " +
                               e.getDetailMsg());
    } catch (const std::exception& e) {
      throw std::runtime_error("cannot read the checkpoint " + file.string() + ": " + e.what());
    }
    if (!loaded.back().finished) break;
  }
  return loaded;
}

void remove_checkpoints(const fs::path& out_dir) {
  std::error_code ignored;
  fs::remove_all(checkpoint_folder(out_dir), ignored);
}

}  // namespace granvv::app
