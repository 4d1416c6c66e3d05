#pragma once
// Write-then-rename, so a reader (or a run that ends midway) never sees half a file.
#include <filesystem>
#include <string>

namespace granvv::app {

// Writes text to path.partial and renames it to path; throws std::runtime_error if the write
// fails (path is then untouched).
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace granvv::app
