#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace granvv::app {
// Runs scripts/SCRIPT_NAME of the data folder with Debian's /usr/bin/python3 (or $GRANVV_PYTHON)
// and the given arguments; returns its exit code (2 with one line if the data folder is missing).
int run_python_script(const std::string& script_name, const std::vector<std::string>& args);

// Rebuilds DIR/report.html and DIR/figures/ from DIR/results.h5 and DIR/summary.json with
// scripts/report.py (Debian's /usr/bin/python3, or $GRANVV_PYTHON). Returns its exit code.
int build_report(const std::filesystem::path& dir);

// `granvv report DIR`: finishes a replacement of the outputs that a killed run left half done
// (app/output_folder.hpp), then builds the page of the run, sweep or atlas in DIR. Exit 2 (one
// line) if DIR holds none of results.h5, sweep.json and atlas.json.
int report_command(const std::filesystem::path& dir);
}  // namespace granvv::app
