#!/usr/bin/python3
"""Strong and weak scaling of the LAMMPS bridge on 1 and 2 MPI ranks.

For N = 1e5 and 2e5 disks (phi = 0.05, Ly = 100 sigma, r = 0.9, one seed) and 1 and 2 ranks:
  1. the bridge, `granvv run md_cooling_sweep` to t = 2 (about 9000 steps) in 10 segments:
     md.wall_seconds, the sum of LAMMPS's loop times in its log.lammps, and the rest (the
     bridge: sampling, calibration, coarse-graining, the two particle frames);
  2. bare `lmp` on the same particles (the bridge's t = 0 frame written as a data file) and the
     same contact, one `run` of STEPS steps with LAMMPS's timer breakdown (Pair, Neigh, Comm,
     Output, Modify, Other).
The 1-min load average is recorded before each run (the machine is shared), and the CPU seconds
of all ranks (getrusage of the children), since on a loaded machine wall time is the share of a
core a process got. Writes
docs/md_scaling.json. Usage: scripts/md_scaling.py build/granvv
"""
import json
import os
import re
import resource
import subprocess
import sys
import time

import h5py

GRANVV = sys.argv[1] if len(sys.argv) > 1 else "build/granvv"
WORK = "/tmp/so_scale"
MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np"]
STEPS = 3000
SIZES = [100000, 200000]
RANKS = [1, 2]


def load():
    return os.getloadavg()[0]


def cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def bridge(n, ranks):
    out = os.path.join(WORK, f"bridge_{n}_{ranks}")
    sets = [f"md.particles={n}", "md.box_width=100", "md.time_unit='md'", "md.t_end=2",
            "md.sample_interval=0.2", "md.snapshot_interval=2", "md.ensemble=1",
            "md.checkpoint_interval=0", "md.bins=100"]
    cmd = ([] if ranks == 1 else MPIRUN + [str(ranks)]) + [GRANVV, "run", "md_cooling_sweep",
                                                           "--quiet", "--no-report", "--out", out]
    for s in sets:
        cmd += ["--set", s]
    before = load()
    cpu0 = cpu()
    start = time.time()
    subprocess.run(cmd, check=True)
    process = time.time() - start
    cpu_seconds = cpu() - cpu0
    md = json.load(open(os.path.join(out, "summary.json")))["md"]
    loops = sum(float(m) for m in re.findall(r"Loop time of ([0-9.e+-]+)",
                                             open(os.path.join(out, "log.lammps")).read()))
    return {"n": n, "ranks": ranks, "load_before": before, "load_after": load(),
            "process_seconds": process, "cpu_seconds": cpu_seconds,
            "md_wall_seconds": md["wall_seconds"], "steps": md["steps"],
            "atom_steps": md["atom_steps"], "lammps_loop_seconds": loops,
            "bridge_outside_loops_seconds": md["wall_seconds"] - loops,
            "contact": md["contact_initial"], "out": out,
            "command": " ".join(cmd)}


def data_file(out, path, lx, ly):
    with h5py.File(os.path.join(out, "particles.h5")) as f:
        x = f["particles/all/position/value"][0]
        v = f["particles/all/velocity/value"][0]
    with open(path, "w") as d:
        d.write(f"granvv md_scaling: the bridge's t = 0 particles\n\n{len(x)} atoms\n1 atom types\n\n")
        d.write(f"{-0.5 * lx!r} {0.5 * lx!r} xlo xhi\n{-0.5 * ly!r} {0.5 * ly!r} ylo yhi\n"
                "-0.5 0.5 zlo zhi\n\nAtoms # sphere\n\n")
        for i, (a, b) in enumerate(x):
            d.write(f"{i + 1} 1 1.0 1.0 {a!r} {b!r} 0.0\n")
        d.write("\nVelocities\n\n")
        for i, (a, b) in enumerate(v):
            d.write(f"{i + 1} {a!r} {b!r} 0.0 0.0 0.0 0.0\n")


def bare(n, ranks, data, contact):
    inp = os.path.join(WORK, f"bare_{n}_{ranks}.in")
    log_file = os.path.join(WORK, f"bare_{n}_{ranks}.log")
    with open(inp, "w") as f:
        f.write("\n".join([
            "units lj", "dimension 2", "atom_style sphere", "atom_modify map array",
            "boundary p p p", "comm_modify vel yes", f"read_data {data}",
            "set type 1 diameter 1.0", "set type 1 mass 1.0",
            f"pair_style gran/hooke {contact['kn']!r} 0 {contact['gamma_n']!r} 0 0 0",
            "pair_coeff * *", f"timestep {contact['dt']!r}",
            "neighbor 0.3 bin", "neigh_modify delay 0 every 1 check yes",
            "fix integrate all nve/sphere disc", "fix plane all enforce2d",
            f"run {STEPS}"]) + "\n")
    before = load()
    cmd = ([] if ranks == 1 else MPIRUN + [str(ranks)]) + ["/usr/bin/lmp", "-in", inp, "-log",
                                                           log_file, "-screen", "none"]
    cpu0 = cpu()
    subprocess.run(cmd, check=True, cwd=WORK)
    cpu_seconds = cpu() - cpu0
    text = open(log_file).read()
    loop = float(re.search(r"Loop time of ([0-9.e+-]+)", text).group(1))
    parts = {}
    for name in ["Pair", "Neigh", "Comm", "Output", "Modify", "Other"]:
        m = re.search(r"^" + name + r"\s*\|[^|]*\|[^|]*\|[^|]*\|[^|]*\|\s*([0-9.]+)", text, re.M)
        parts[name] = float(m.group(1)) if m else None  # % of the loop time
    return {"n": n, "ranks": ranks, "load_before": before, "load_after": load(),
            "cpu_seconds": cpu_seconds, "steps": STEPS, "loop_seconds": loop,
            "atom_steps_per_second": n * STEPS / loop, "percent": parts, "command": " ".join(cmd)}


def main():
    os.makedirs(WORK, exist_ok=True)
    results = {"bridge": [], "bare": [], "started": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())}
    for n in SIZES:
        for ranks in RANKS:
            b = bridge(n, ranks)
            print(json.dumps({k: b[k] for k in b if k not in ("contact", "command")}), flush=True)
            results["bridge"].append(b)
        first = results["bridge"][-2]
        summary = json.load(open(os.path.join(first["out"], "summary.json")))["md"]
        data = os.path.join(WORK, f"data_{n}.lmp")
        data_file(first["out"], data, summary["box_length"], summary["box_width"])
        for ranks in RANKS:
            r = bare(n, ranks, data, first["contact"])
            print(json.dumps(r), flush=True)
            results["bare"].append(r)
    results["ended"] = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs",
                           "md_scaling.json"), "w") as f:
        json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
