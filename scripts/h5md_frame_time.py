#!/usr/bin/python3
"""Wall time of one H5MD particle frame for 2e5 disks on 1 and 2 MPI ranks.

Each measurement is two `granvv run md_cooling_sweep` runs of the same particles to t = 0.2
(about 900 steps), stopping every 0.002: one writing a particle frame at every stop (101
frames), one writing none. The difference of their md.wall_seconds over 101 is the cost of a
frame: the
exchange of the particles to their ID-block owners, the writes and flushes of every rank's file
(and, for an older binary, its gather). Best of REPEATS pairs (the machine is shared). Prints one
JSON line per binary and rank count. Usage: scripts/h5md_frame_time.py build/granvv [OLD_BINARY]
"""
import json
import os
import shutil
import subprocess
import sys

BINARIES = sys.argv[1:] or ["build/granvv"]
WORK = "/tmp/h5md_frame_time"
MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np"]
N = 200000
FRAMES = 101
REPEATS = 3


def wall(binary, ranks, frames, out):
    sets = [f"md.particles={N}", "md.box_width=100", "md.time_unit='md'", "md.t_end=0.2",
            "md.sample_interval=0.002", f"md.snapshot_interval={0.002 if frames else 0}",
            "md.ensemble=1", "md.checkpoint_interval=0", "md.bins=100"]
    cmd = ([] if ranks == 1 else MPIRUN + [str(ranks)]) + [binary, "run", "md_cooling_sweep",
                                                           "--quiet", "--no-report", "--out", out]
    for s in sets:
        cmd += ["--set", s]
    shutil.rmtree(out, ignore_errors=True)
    subprocess.run(cmd, check=True)
    return json.load(open(os.path.join(out, "summary.json")))["md"]["wall_seconds"]


for binary in BINARIES:
    for ranks in (1, 2):
        per_frame = []
        for repeat in range(REPEATS):
            out = os.path.join(WORK, f"r{ranks}_{repeat}")
            with_frames = wall(binary, ranks, True, out + "_frames")
            without = wall(binary, ranks, False, out + "_none")
            per_frame.append((with_frames - without) / FRAMES)
            files = sorted(f for f in os.listdir(out + "_frames") if f.startswith("particles"))
            shutil.rmtree(out + "_frames")
            shutil.rmtree(out + "_none")
        print(json.dumps({"binary": binary, "n": N, "ranks": ranks, "frames": FRAMES,
                          "seconds_per_frame": per_frame, "best": min(per_frame),
                          "load": os.getloadavg()[0], "files": files}), flush=True)
