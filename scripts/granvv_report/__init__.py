"""granvv_report: the report of one granvv output folder (scripts/report.py is its command line).

Modules, each with one concern:
  data        the only reader of results.h5, summary.json and sweep.json (Run, SweepRun)
  style       matplotlib settings, units, colours and drawing helpers
  formatting  numbers and verdict badges for the page
  registry    @figure: each figure declared once with its file, page section and caption template
  frames      the particle frames of a run (H5MD) and the density profiles drawn beside them
  figures_hydro, figures_md, figures_compare, figures_pressure, figures_sweep, figures_transport,
  figures_particles
              the figures of each model family (importing a module registers its figures)
  tables      the page's tables (run header, side-by-side verdict, numbers, sweep points)
  page        page assembly with the jinja2 templates beside this package

The figures follow Efrati, Livne & Meerson, PRL 94, 088001 (2005). Numbers on the page are read
from the files written by the C++ program; the only quantities evaluated here are those needed to
draw a curve.
"""
import os
import tempfile

PROG = "report.py"

# Matplotlib wants a writable config/cache dir; the caller's HOME may be read-only. This runs before
# any module of the package imports matplotlib.
if not os.access(os.environ.get("MPLCONFIGDIR", os.path.expanduser("~")), os.W_OK):
    import atexit
    import shutil
    os.environ["MPLCONFIGDIR"] = tempfile.mkdtemp(prefix="granvv-mpl-")
    atexit.register(shutil.rmtree, os.environ["MPLCONFIGDIR"], True)

import matplotlib  # noqa: E402

matplotlib.use("Agg")
