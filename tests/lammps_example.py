#!/usr/bin/python3
"""examples/lammps as a user runs it: Debian's lmp runs the shipped in.disks as it is (only
shorter: 25000 steps, 5 time units, 11 frames), then `granvv run examples/lammps/disks.toml`
compares its dump against the hydro and writes the report. Checks the summary (the recorded
engine, the dump's N and box, the compared times, a verdict, the dump's SHA-256) and that
report.html exists.

    tests/lammps_example.py GRANVV_BINARY SOURCE_DIR
"""
import hashlib
import json
import subprocess
import sys
import tempfile
from pathlib import Path


def main() -> int:
    granvv, source = Path(sys.argv[1]).resolve(), Path(sys.argv[2]).resolve()
    with tempfile.TemporaryDirectory(prefix="granvv_lammps_example_") as tmp:
        work = Path(tmp)
        subprocess.run(["lmp", "-var", "steps", "25000", "-in",
                        str(source / "examples/lammps/in.disks"), "-log", "none", "-screen",
                        "none", "-nocite"], cwd=work, check=True)
        dump = work / "dump.disks.txt"
        lines = dump.read_text().splitlines()
        n = int(lines[3])
        frames = sum(1 for line in lines if line == "ITEM: TIMESTEP")
        assert frames == 11, f"{frames} frames in the dump"
        run = subprocess.run([str(granvv), "run", str(source / "examples/lammps/disks.toml"),
                              "--out", "out", "--quiet",
                              "--set", "md.output_times=[0.0, 2.5, 5.0]"],
                             cwd=work, capture_output=True, text=True)
        assert run.returncode == 0, run.stdout + run.stderr
        summary = json.loads((work / "out/summary.json").read_text())
        md = summary["md"]
        assert summary["status"] == "ok", summary.get("error")
        assert md["engine"] == "recorded" and md["particles"] == n, md
        assert md["box_length"] == 100.0 and md["box_width"] == 10.0, md
        assert md["restitution"] == 0.9, md
        assert md["snapshot_times"] == [0.0, 2.5, 5.0], md["snapshot_times"]
        sha = hashlib.sha256(dump.read_bytes()).hexdigest()
        assert md["input_files"][0]["sha256"] == sha, md["input_files"]
        verdict = summary["compare"]["verdict"]
        assert verdict, summary["compare"]
        assert (work / "out/report.html").stat().st_size > 0
        print(f"{n} disks, {frames} frames; compare: {verdict}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
