#pragma once
// Write-then-rename, so a reader (or a run that ends midway) never sees half a file, and every
// step of the write is checked (docs/outputs.md, "The output protocol").
#include <filesystem>
#include <string>

namespace granvv::app {

// Writes text to path.partial, flushes it to the disk (fsync), closes it and renames it to path.
// Every result is checked: on any failure (a full disk, a read-only folder) path.partial is
// removed, path is left as it was, and std::runtime_error names the file and the reason.
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

// Flushes a file or a folder (its entries) to the disk; throws std::runtime_error on failure.
void sync_to_disk(const std::filesystem::path& path);

}  // namespace granvv::app
