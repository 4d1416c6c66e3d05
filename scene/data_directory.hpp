#pragma once
// Where granvv finds its shipped data (scenes in cases/, the report scripts in scripts/):
// the GRANVV_DATA_DIR environment variable if set, else beside the running binary, in the
// installed layout (PREFIX/bin/granvv with PREFIX/share/granvv/) or the build tree's
// (build/granvv with build/share/granvv/). Never through the path of the source tree the
// binary was built from, so an installed or relocated granvv keeps working.
#include <filesystem>

namespace granvv::app {

// The data folder; throws ConfigError naming the places searched when none holds cases/
// and scripts/.
std::filesystem::path data_directory();

}  // namespace granvv::app
