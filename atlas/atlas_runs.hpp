#pragma once
// The runs of `granvv atlas` (docs/atlas.md): one model of a scene's ladder at one setting of
// its knobs, run by its family (models/model_family.hpp) and reduced to what the atlas judges;
// and the cache that keeps each run by its resolved case, so that a re-run (a larger budget, an
// interrupted atlas) only adds runs.
#include <filesystem>
#include <string>
#include <vector>

#include "models/model_setting.hpp"

namespace granvv::app {

// Runs one setting, or takes it from cache_dir (the file named by the hash of its resolved
// case). A setting the schema or the scene refuses comes back with status "refused"; a run a
// signal stopped, with status "interrupted" (and is not cached). Particle runs call MPI: run
// them on the main thread.
AtlasRun run_atlas_setting(const AtlasScene& scene, const AtlasSetting& setting,
                           const std::filesystem::path& cache_dir);

}  // namespace granvv::app
