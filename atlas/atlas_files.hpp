#pragma once
// atlas.h5 (docs/atlas.md, "Files"): every run's model, status, knobs (every family's, by name:
// models/model_family.hpp all_knobs), cost, and its numerical and model errors per judged
// observable with the reference's statistical error; written aside and renamed into place.
#include <filesystem>
#include <string>
#include <vector>

#include "atlas/atlas_analysis.hpp"

namespace granvv::app {

void write_atlas_h5(const std::filesystem::path& file, const std::vector<AtlasRun>& runs,
                    const std::vector<ObservableErrors>& numerical,
                    const std::vector<ObservableErrors>& model,
                    const std::vector<std::string>& observables);

}  // namespace granvv::app
