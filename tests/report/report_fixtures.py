"""What the report package's tests share: the package on the path, and real output folders made by
the real binary (GRANVV_BINARY, set by tests/CMakeLists.txt; else build/granvv of this tree)."""
import atexit
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "scripts"))

BINARY = Path(os.environ.get("GRANVV_BINARY", SOURCE / "build" / "granvv"))

# A tiny particle scene with its comparison: md_haff with 400 hard disks to t = 5, two members
# (about 1 s; the event-driven engine needs no LAMMPS).
TINY_MD = ["--set", "md.engine=event_driven", "--set", "md.particles=400", "--set", "md.box_width=40",
           "--set", "md.t_end=5", "--set", "md.output_times=[0, 5]", "--set", "md.ensemble=2",
           "--set", "md.sample_interval=1"]

_runs = {}


def granvv_run(case, *args):
    """The output folder of `granvv run CASE ARGS --quiet --no-report`, made once per process and
    removed at exit; the test is skipped if the binary is not built."""
    key = (case,) + args
    if key not in _runs:
        if not BINARY.is_file():
            raise unittest.SkipTest(f"{BINARY} not built (set GRANVV_BINARY)")
        out = Path(tempfile.mkdtemp(prefix=f"granvv-report-{case}-")) / "run"
        done = subprocess.run([str(BINARY), "run", case, "--out", str(out), "--quiet", "--no-report", *args],
                              capture_output=True, text=True, timeout=120)
        if done.returncode != 0:
            raise AssertionError(f"granvv run {case} exited {done.returncode}: {done.stdout}{done.stderr}")
        _runs[key] = out
    return _runs[key]


def scratch(test):
    """A fresh folder, removed when the test ends."""
    folder = tempfile.TemporaryDirectory(prefix="granvv-report-test-")
    test.addCleanup(folder.cleanup)
    return Path(folder.name)


def copy_of(folder, test):
    """A copy of an output folder that the test may change, removed when it ends."""
    dest = scratch(test) / "run"
    shutil.copytree(folder, dest)
    return dest


def _remove_runs():
    for out in _runs.values():
        shutil.rmtree(out.parent, ignore_errors=True)


atexit.register(_remove_runs)
