#pragma once
// `granvv atlas CASE [--set k=v]... [--tolerance X] [--budget SECONDS] [--jobs N] [--out DIR]`
// (docs/atlas.md): every model of the scene's ladder that applies, each swept over its cost
// knobs within the budget; their errors against their own finest run and against the richest
// model, the work-precision fronts, the stability boundaries, the ladder timeline and the
// cheapest adequate model, in DIR/atlas.json, DIR/atlas.h5 and DIR/atlas.html.
#include <string>
#include <vector>

namespace granvv::app {

struct AtlasOptions {
  std::string case_name;
  std::vector<std::string> sets;
  double tolerance = 1e-2;  // relative
  double budget = 300.0;    // wall seconds for the runs
  int jobs = 0;             // 0 = the core count
  std::string out_dir;      // default out/<case>-atlas
  bool quiet = false;
  bool report = true;
};

// Exit 0 when the atlas is complete, 1 if it could not be written, 2 for bad input (one line,
// nothing run), 130/143 when interrupted (the runs so far stay cached in DIR/runs/).
int atlas_command(const AtlasOptions& options);

}  // namespace granvv::app
