#pragma once
#include <filesystem>

namespace granvv::app {
// Rebuilds DIR/report.html and DIR/figures/ from DIR/results.h5 and DIR/summary.json with
// scripts/report.py (Debian's /usr/bin/python3, or $GRANVV_PYTHON). Returns its exit code.
int build_report(const std::filesystem::path& dir);
}  // namespace granvv::app
