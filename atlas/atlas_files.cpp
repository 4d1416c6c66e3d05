// The atlas's files (atlas/atlas_files.hpp).
#include "atlas/atlas_files.hpp"

#include <H5Cpp.h>

#include "atlas/work_precision.hpp"
#include "fields/hdf5_datasets.hpp"
#include "models/model_family.hpp"

namespace granvv::app {
namespace fs = std::filesystem;
using atlas::kNoValue;

void write_atlas_h5(const fs::path& file, const std::vector<AtlasRun>& runs,
                    const std::vector<ObservableErrors>& numerical,
                    const std::vector<ObservableErrors>& model,
                    const std::vector<std::string>& observables) {
  const fs::path tmp = file.string() + ".partial";
  {
    H5::H5File f(tmp.string(), H5F_ACC_TRUNC);
    H5::Group g = f.createGroup("runs");
    std::vector<std::string> names, status;
    std::vector<double> wall, work;
    std::map<std::string, std::vector<double>> knobs;  // every family's knobs, by name
    const std::vector<KnobSpec> columns = all_knobs();
    for (const auto& r : runs) {
      names.push_back(r.setting.model), status.push_back(r.status);
      for (const KnobSpec& k : columns) {
        const auto it = r.setting.knobs.find(k.name);
        knobs[k.name].push_back(it == r.setting.knobs.end() ? k.absent : it->second);
      }
      wall.push_back(r.cost.wall_seconds), work.push_back(r.cost.work);
    }
    h5::write_strings(g, "model", names);
    h5::write_strings(g, "status", status);
    for (const KnobSpec& k : columns) h5::write_vector(g, k.name, knobs[k.name]);
    h5::write_vector(g, "wall_seconds", wall);
    h5::write_vector(g, "work", work);
    h5::write_attribute(g, "missing",
                        "NaN: the run does not give the observable; a knob the run's model does "
                        "not have holds its neutral value (0, or 1 for a factor)");
    auto group = [&](const char* name, const std::vector<ObservableErrors>& errors,
                     bool reference_error) {
      H5::Group e = g.createGroup(name);
      for (const auto& o : observables) {
        std::vector<double> v;
        for (const auto& m : errors) {
          const auto it = m.find(o);
          v.push_back(it == m.end()     ? kNoValue
                      : reference_error ? it->second.reference_error
                                        : it->second.error);
        }
        h5::write_vector(e, o, v);
      }
    };
    group("numerical_error", numerical, false);
    group("model_error", model, false);
    group("reference_statistical_error", model, true);
  }
  fs::rename(tmp, file);
}

}  // namespace granvv::app
