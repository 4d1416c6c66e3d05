#!/usr/bin/python3
"""Cost figures of the particle engine (LAMMPS bridge) on this machine. Measures, asserts nothing.

    /usr/bin/python3 scripts/md_benchmarks.py [--quick] [--out-dir DIR] [--keep DIR]

1. Bridge against bare LAMMPS. `granvv run md_haff` (10^4 disks, fixed stiffness, coarse-grained
   every 100 steps) against `/usr/bin/lmp -in FILE -log none -screen none` on the same system:
   N, box, diameter 1, mass 1, the bridge's pair_style gran/hooke line and time step, neighbour
   settings, nve/sphere disc + enforce2d, the same number of steps, random non-overlapping
   positions (a data file written here: this LAMMPS (29 Sep 2021) has no `create_atoms random
   ... overlap`) and `velocity all create 1.0 SEED dist gaussian`. LAMMPS' 2D temperature is
   KE = (dim/2) N k T with dim = 2, i.e. T = sum m|c|^2 / (2 (N - 1)) (2N - 2 degrees of
   freedom after `mom yes`), the same convention as granvv's T = m<|c|^2>/2 per particle (up to
   the factor (N - 1)/N). Two run lengths give the run-loop-only rate by differencing (start-up,
   particle sampling, the restitution calibration and output cancel). A third variant, bare lmp
   run in the bridge's 100-step segments (`run 100 pre no post no`), separates the cost of the
   segmentation from that of the coarse-graining.
2. Adaptive stiffness. A cooling gas (2000 disks, r = 0.7, box 177, t_end = 8 t0 so that T falls
   ~70x) with md.adaptive_stiffness true and false, md.ensemble = 3 each (the same seeds):
   wall seconds, steps, speed-up, and T(t) of both compared within the ensemble's standard error.
3. MPI. The part-1 run on 1 rank and under `mpirun -np 2`: wall seconds, speed-up, statistics.

Before every timing the script waits (polling, up to --max-wait s, default 300) until the 1-minute load
average is below 0.5 and records the load it started at; every timing is repeated (3x; 1x with
--quick) and the median reported. Writes DIR/md_benchmarks.{json,png,md} (default docs/; with
--quick, out/md_benchmarks_quick/ so that a smoke check leaves the committed figures alone).
"""
import argparse
import datetime
import json
import math
import os
import platform
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GRANVV = os.path.join(ROOT, "build", "granvv")
LMP = "/usr/bin/lmp"
MPIRUN = "mpirun"
SEGMENT = 100  # steps between coarse-grainings in part 1 and 3
LOAD_LIMIT = 0.5

FULL = {
    "repeats": 3, "max_wait": 300.0,
    "p1_particles": 10000, "p1_long": 100000, "p1_short": 50000,
    "p2_particles": 2000, "p2_box_width": 177.0, "p2_restitution": 0.7, "p2_t0_multiple": 8.0,
    "p2_samples": 128, "p2_ensemble": 3,
    "p3_ranks": 2,
}
QUICK = dict(FULL, repeats=1, max_wait=10.0, p1_long=4000, p1_short=2000, p2_t0_multiple=0.125,
             p2_samples=16)


def log(msg):
    print(f"[{datetime.datetime.now():%H:%M:%S}] {msg}", flush=True)


# ------------------------------------------------------------------------------------------------
# Timing under a quiet machine

def wait_for_quiet(max_wait):
    """Poll the 1-min load average until < LOAD_LIMIT (or max_wait s); return what was seen."""
    start = time.time()
    load = os.getloadavg()[0]
    while load >= LOAD_LIMIT and time.time() - start < max_wait:
        time.sleep(5.0)
        load = os.getloadavg()[0]
    return {"load1": round(load, 3), "waited_s": round(time.time() - start, 1),
            "quiet": load < LOAD_LIMIT}


def timed(cmd, max_wait, cwd=None):
    """Run cmd after waiting for a quiet machine; wall seconds of the whole process (and the CPU
    seconds of it and its children, all ranks under mpirun)."""
    quiet = wait_for_quiet(max_wait)
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    proc = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    seconds = time.perf_counter() - t
    ru2 = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        sys.exit(f"command failed ({proc.returncode}): {' '.join(cmd)}\n{proc.stdout}\n{proc.stderr}")
    quiet["load1_after"] = round(os.getloadavg()[0], 3)
    quiet["cpu_seconds"] = (ru2.ru_utime - ru.ru_utime) + (ru2.ru_stime - ru.ru_stime)
    return seconds, quiet


def loop_seconds(log_path):
    """Sum of LAMMPS' own 'Loop time of X' over the runs in a log (rank 0's wall clock)."""
    with open(log_path) as f:
        times = re.findall(r"^Loop time of ([0-9.eE+-]+) on", f.read(), flags=re.M)
    return sum(float(x) for x in times), len(times)


def shell(cmd):
    return " ".join(c if c and all(ch.isalnum() or ch in "-_./=:,[]" for ch in c) else repr(c)
                    for c in cmd)


def median(xs):
    return statistics.median(xs)


# ------------------------------------------------------------------------------------------------
# The bridge

def granvv_cmd(out, sets, ranks=1):
    cmd = [GRANVV, "run", "md_haff", "--no-report", "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    cmd += ["--out", out]
    if ranks > 1:
        cmd = [MPIRUN, "--allow-run-as-root", "-np", str(ranks)] + cmd
    return cmd


def read_summary(out):
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)["md"]


def read_series(out):
    with h5py.File(os.path.join(out, "results.h5"), "r") as f:
        ts = f["/md/timeseries"]
        return {k: ts[k][()] for k in ("t", "T", "T_mean", "T_stderr", "energy_total")}


def run_bridge(work, tag, sets, max_wait, ranks=1):
    out = os.path.join(work, tag)
    if os.path.exists(out):
        shutil.rmtree(out)
    cmd = granvv_cmd(out, sets, ranks)
    seconds, quiet = timed(cmd, max_wait)
    md = read_summary(out)
    with open(os.path.join(out, "summary.json")) as f:
        version = json.load(f).get("granvv_version")
    lmp_log = os.path.join(out, "log.lammps")
    loop, segments = loop_seconds(lmp_log) if os.path.exists(lmp_log) else (float("nan"), 0)
    return {"tag": tag, "command": shell(cmd), "process_seconds": seconds, "granvv_version": version,
            "lammps_loop_seconds": loop, "lammps_runs": segments,
            "wall_seconds": md["wall_seconds"], "steps": md["steps"], "atom_steps": md["atom_steps"],
            "ranks": ranks, **quiet}, out


def probe(work, sets):
    """A short untimed run for the contact model, the box and t0."""
    out = os.path.join(work, "probe_" + str(abs(hash(tuple(sets))) % 10**8))
    cmd = granvv_cmd(out, sets)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return read_summary(out)


# ------------------------------------------------------------------------------------------------
# Bare LAMMPS

def write_data_file(path, n, lx, ly, seed):
    """n disks of diameter 1, uniform, non-overlapping (periodic), centred box like the bridge's."""
    rng = np.random.default_rng(seed)
    nx, ny = max(1, int(lx)), max(1, int(ly))
    grid = {}
    pos = np.empty((n, 2))
    placed = 0
    while placed < n:
        x, y = (rng.random() - 0.5) * lx, (rng.random() - 0.5) * ly
        cx, cy = min(nx - 1, int((x + 0.5 * lx) / lx * nx)), min(ny - 1, int((y + 0.5 * ly) / ly * ny))
        ok = True
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for j in grid.get(((cx + dx) % nx, (cy + dy) % ny), ()):
                    ddx, ddy = pos[j, 0] - x, pos[j, 1] - y
                    ddx -= lx * round(ddx / lx)
                    ddy -= ly * round(ddy / ly)
                    if ddx * ddx + ddy * ddy < 1.0:
                        ok = False
                        break
                if not ok:
                    break
            if not ok:
                break
        if not ok:
            continue
        pos[placed] = (x, y)
        grid.setdefault((cx, cy), []).append(placed)
        placed += 1
    with open(path, "w") as f:
        f.write("granvv md_benchmarks: uniform non-overlapping disks\n\n")
        f.write(f"{n} atoms\n1 atom types\n\n")
        f.write(f"{-0.5 * lx!r} {0.5 * lx!r} xlo xhi\n{-0.5 * ly!r} {0.5 * ly!r} ylo yhi\n"
                "-0.5 0.5 zlo zhi\n\nAtoms # sphere\n\n")
        for i, (x, y) in enumerate(pos):
            f.write(f"{i + 1} 1 1.0 1.0 {x!r} {y!r} 0.0\n")


def lammps_input(path, data, contact, steps, seed, t_file, cpu_file, segmented=False):
    """The bare-LAMMPS equivalent of the bridge's run (md_bridge/md_run.cpp)."""
    lines = [
        "units lj", "dimension 2", "atom_style sphere", "atom_modify map array", "boundary p p p", "comm_modify vel yes",
        f"read_data {data}",
        # read_data's density column gives the 3D mass pi/6: set diameter, then mass, explicitly
        "set type 1 diameter 1.0", "set type 1 mass 1.0",
        f"velocity all create 1.0 {seed} dist gaussian",
        f"pair_style gran/hooke {contact['kn']!r} 0 {contact['gamma_n']!r} 0 0 0",
        "pair_coeff * *",
        f"timestep {contact['dt']!r}",
        "neighbor 0.3 bin", "neigh_modify delay 0 every 1 check yes",
        "fix integrate all nve/sphere disc", "fix plane all enforce2d",
        # the default thermo (step temp epair emol etotal press, first and last step of a run)
    ]
    if segmented:  # as the bridge drives it: segments of SEGMENT steps, setup only before the first
        # (and, like the bridge, with a log file: its loop times are summed from it)
        assert steps % SEGMENT == 0
        lines += [f"run {SEGMENT} post no",
                  f"variable seg loop {steps // SEGMENT - 1}",
                  "label segments",
                  f"run {SEGMENT} pre no post no",
                  "next seg",
                  "jump SELF segments"]
    else:
        # LAMMPS' own loop time: the thermo keyword cpu (seconds since the run's loop began),
        # printed at the last step (a fix that acts on one step only)
        lines += ["variable cpu equal cpu",
                  f'fix looptime all print {steps} "${{cpu}}" file {cpu_file} screen no',
                  f"run {steps}"]
    # untimed check after the timed run(s): T = KE/N, the mass and the diameter of the disks
    # (a `run 0` evaluates the computes; the loop-time fix is removed first)
    if not segmented:
        lines.append("unfix looptime")
    lines += ["compute ke all ke",
              "compute r all property/atom radius", "compute rmax all reduce max c_r",
              "thermo_style custom step temp epair emol etotal press c_ke c_rmax",
              "variable T equal c_ke/atoms",
              "variable m equal mass[1]", "variable d equal 2*c_rmax",
              "run 0 post no",
              f'print "${{T}} ${{m}} ${{d}}" file {t_file}']
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def run_lammps(work, tag, data, contact, steps, seed, max_wait, segmented=False):
    inp = os.path.join(work, tag + ".in")
    t_file = os.path.join(work, tag + ".T")
    cpu_file = os.path.join(work, tag + ".cpu")
    log_file = os.path.join(work, tag + ".log")
    lammps_input(inp, data, contact, steps, seed, t_file, cpu_file, segmented)
    cmd = [LMP, "-in", inp, "-log", log_file if segmented else "none", "-screen", "none"]
    seconds, quiet = timed(cmd, max_wait, cwd=work)
    with open(t_file) as f:
        T, m, d = (float(v) for v in f.read().split())
    if segmented:
        loop, runs = loop_seconds(log_file)
    else:
        with open(cpu_file) as f:
            loop, runs = float(f.read().split()[-1]), 1
    return {"tag": tag, "command": shell(cmd), "process_seconds": seconds, "steps": steps,
            "lammps_loop_seconds": loop, "lammps_runs": runs,
            "T_final": T, "mass": m, "diameter": d, **quiet}


# ------------------------------------------------------------------------------------------------
# Part 1 and 3: bridge against bare LAMMPS, 1 rank against 2

def part_bridge_vs_lammps(cfg, work):
    n = cfg["p1_particles"]
    # md.ensemble = 1: one run, as bare lmp does (the case's default may be an ensemble)
    base = ["md.adaptive_stiffness=false", f"md.particles={n}", "md.ensemble=1"]
    p = probe(work, base + ["md.t_end=0.05", "md.sample_interval=0.05"])
    contact = p["contact_initial"]
    dt = contact["dt"]
    lx, ly = p["box_length"], p["box_width"]
    interval = SEGMENT * dt
    lengths = {"long": cfg["p1_long"], "short": cfg["p1_short"]}

    def sets(steps):  # t_end = steps dt exactly: steps / SEGMENT segments of SEGMENT steps
        return base + [f"md.t_end={steps * dt!r}", f"md.sample_interval={interval!r}"]

    data = os.path.join(work, "disks.data")
    write_data_file(data, n, lx, ly, seed=20240611)
    log(f"part 1: N={n}, box {lx:.4f} x {ly:.4f}, dt={dt:.6g}, kn={contact['kn']:.6g}, "
        f"gamma_n={contact['gamma_n']:.6g}, steps {lengths}")
    runs = []
    for rep in range(cfg["repeats"]):
        for name, steps in lengths.items():
            r, out = run_bridge(work, f"bridge_{name}_{rep}", sets(steps), cfg["max_wait"])
            s = read_series(out)
            r.update(kind="bridge", length=name, rep=rep, T_initial=float(s["energy_total"][0, 0]) / n,
                     T_final=float(s["energy_total"][0, -1]) / n)
            assert r["steps"] == steps, (r["steps"], steps)
            runs.append(r)
            log(f"  bridge {name} rep {rep}: md.wall {r['wall_seconds']:.2f} s, process "
                f"{r['process_seconds']:.2f} s (load {r['load1']})")
            for seg in (False, True):
                kind = "lammps_segmented" if seg else "lammps"
                r = run_lammps(work, f"{kind}_{name}_{rep}", data, contact, steps, 4928459 + rep,
                               cfg["max_wait"], segmented=seg)
                r.update(kind=kind, length=name, rep=rep, T_initial=(n - 1) / n)
                runs.append(r)
                log(f"  {kind} {name} rep {rep}: process {r['process_seconds']:.2f} s "
                    f"(load {r['load1']})")

    def med(kind, length, key):
        return median([r[key] for r in runs if r["kind"] == kind and r["length"] == length])

    dsteps = lengths["long"] - lengths["short"]
    dsegments = dsteps // SEGMENT
    rates = {}  # atom-steps/s, medians over the repeats of the long run
    for label, kind, key in (("bridge_md_wall", "bridge", "wall_seconds"),
                             ("bridge_process", "bridge", "process_seconds"),
                             ("bridge_process_cpu", "bridge", "cpu_seconds"),
                             ("bridge_lammps_loop", "bridge", "lammps_loop_seconds"),
                             ("lammps_process", "lammps", "process_seconds"),
                             ("lammps_process_cpu", "lammps", "cpu_seconds"),
                             ("lammps_loop", "lammps", "lammps_loop_seconds"),
                             ("lammps_segmented_process", "lammps_segmented", "process_seconds"),
                             ("lammps_segmented_loop", "lammps_segmented", "lammps_loop_seconds")):
        whole = [n * r["steps"] / r[key] for r in runs if r["kind"] == kind and r["length"] == "long"]
        rates[label] = {"median": median(whole), "min": min(whole), "max": max(whole),
                        "seconds_long_median": med(kind, "long", key),
                        "seconds_short_median": med(kind, "short", key),
                        # the brief's run-loop-only estimate: two lengths, medians differenced
                        "differenced": n * dsteps / (med(kind, "long", key) - med(kind, "short", key))}
    # The bridge's time outside LAMMPS' run loops (md.wall - sum of 'Loop time'), split into a
    # per-segment part (setup_minimal of `run pre no`, thermo, coarse-graining, library calls)
    # and a fixed part (particle sampling, restitution calibration, first setup) from the lengths.
    for r in runs:
        if r["kind"] == "bridge":
            r["outside_loop_seconds"] = r["wall_seconds"] - r["lammps_loop_seconds"]
    out_long, out_short = med("bridge", "long", "outside_loop_seconds"), med("bridge", "short", "outside_loop_seconds")
    per_segment = (out_long - out_short) / dsegments
    fixed = out_long - per_segment * (lengths["long"] // SEGMENT)
    bridge_run = med("bridge", "long", "lammps_loop_seconds") + per_segment * (lengths["long"] // SEGMENT)
    rates["bridge_run_loop_with_segment_overhead"] = {"median": n * lengths["long"] / bridge_run}
    bare = rates["lammps_process"]["median"]
    bare_loop = rates["lammps_loop"]["median"]

    def rel(a, b):
        return a / b - 1

    def paired(kind_a, key_a, kind_b, key_b):  # per repeat (adjacent runs), then the median
        xs = []
        for rep in range(cfg["repeats"]):
            a = [r for r in runs if r["kind"] == kind_a and r["length"] == "long" and r["rep"] == rep][0]
            b = [r for r in runs if r["kind"] == kind_b and r["length"] == "long" and r["rep"] == rep][0]
            xs.append(b[key_b] / a[key_a] - 1)  # rate a / rate b - 1
        return {"median": median(xs), "min": min(xs), "max": max(xs)}

    comparison = {  # relative rate differences (negative: the bridge is slower)
        "bridge_md_wall_vs_lammps_process": rel(rates["bridge_md_wall"]["median"], bare),
        "bridge_md_wall_vs_lammps_process_per_repeat":
            paired("bridge", "wall_seconds", "lammps", "process_seconds"),
        "bridge_process_vs_lammps_process": rel(rates["bridge_process"]["median"], bare),
        "bridge_process_cpu_vs_lammps_process_cpu":
            rel(rates["bridge_process_cpu"]["median"], rates["lammps_process_cpu"]["median"]),
        "bridge_vs_lammps_differenced": rel(rates["bridge_md_wall"]["differenced"],
                                            rates["lammps_process"]["differenced"]),
        "bridge_run_loop_vs_lammps_loop":
            rel(rates["bridge_run_loop_with_segment_overhead"]["median"], bare_loop),
        "bridge_lammps_loop_vs_lammps_loop": rel(rates["bridge_lammps_loop"]["median"], bare_loop),
        "bridge_lammps_loop_vs_lammps_loop_per_repeat":
            paired("bridge", "lammps_loop_seconds", "lammps", "lammps_loop_seconds"),
        "lammps_segmented_loop_vs_lammps_loop": rel(rates["lammps_segmented_loop"]["median"], bare_loop),
        "lammps_segmented_process_vs_lammps_process":
            rel(rates["lammps_segmented_process"]["median"], bare),
        "bridge_outside_loop_seconds_long": out_long,
        "bridge_outside_loop_seconds_short": out_short,
        "bridge_outside_loop_fraction_long": out_long / med("bridge", "long", "wall_seconds"),
        "bridge_outside_loop_per_segment_ms": 1e3 * per_segment,
        "bridge_outside_loop_fixed_seconds": fixed,
        "bridge_process_minus_md_wall_seconds":
            med("bridge", "long", "process_seconds") - med("bridge", "long", "wall_seconds"),
        "lammps_process_minus_loop_seconds":
            med("lammps", "long", "process_seconds") - med("lammps", "long", "lammps_loop_seconds"),
    }
    physics = {  # the two systems should cool alike: T(end)/T(0) over the same steps
        "bridge_T_ratio_long": median([r["T_final"] / r["T_initial"] for r in runs
                                       if r["kind"] == "bridge" and r["length"] == "long"]),
        "lammps_T_ratio_long": median([r["T_final"] / r["T_initial"] for r in runs
                                       if r["kind"] == "lammps" and r["length"] == "long"]),
        "haff_t0_theory": p["haff_t0_theory"],
        "haff_T_ratio_theory": (1 + lengths["long"] * dt / p["haff_t0_theory"]) ** -2,
        "lammps_mass_diameter": [runs[1]["mass"], runs[1]["diameter"]],
    }
    data_cmd = {
        "bridge": runs[0]["command"],
        "lammps": next(r["command"] for r in runs if r["kind"] == "lammps"),
        "lammps_input": open(os.path.join(work, "lammps_long_0.in")).read(),
        "lammps_segmented_input_tail": "\n".join(
            open(os.path.join(work, "lammps_segmented_long_0.in")).read().splitlines()[-8:]),
    }
    return {"particles": n, "box": [lx, ly], "contact": contact, "sample_interval": interval,
            "steps": lengths, "t_end": {k: v * dt for k, v in lengths.items()},
            "runs": runs, "rates_atom_steps_per_s": rates, "relative": comparison,
            "physics_check": physics, "commands": data_cmd, "sets": sets(lengths["long"]),
            "target": "bridge within 5 % of bare LAMMPS"}


def part_mpi(cfg, work, p1):
    n = p1["particles"]
    ranks = cfg["p3_ranks"]
    runs, outs = [], {}
    for rep in range(cfg["repeats"]):
        for length, steps in p1["steps"].items():
            sets = p1["sets"][:-2] + [f"md.t_end={steps * p1['contact']['dt']!r}",
                                      f"md.sample_interval={p1['sample_interval']!r}"]
            for np_ in (1, ranks):
                r, out = run_bridge(work, f"mpi{np_}_{length}_{rep}", sets, cfg["max_wait"], np_)
                r.update(length=length, rep=rep, summary={
                    k: read_summary(out)[k] for k in ("haff_t0_measured", "haff_t0_measured_error",
                                                      "haff_T0_measured", "haff_t0_theory")})
                outs[(np_, length, rep)] = out
                runs.append(r)
                log(f"  {np_} rank(s) {length} rep {rep}: md.wall {r['wall_seconds']:.2f} s, "
                    f"process {r['process_seconds']:.2f} s (load {r['load1']})")

    def med(np_, length, key):
        return median([r[key] for r in runs if r["ranks"] == np_ and r["length"] == length])

    dsteps = p1["steps"]["long"] - p1["steps"]["short"]
    res = {}
    for np_ in (1, ranks):
        res[str(np_)] = {
            "wall_seconds_long": med(np_, "long", "wall_seconds"),
            "process_seconds_long": med(np_, "long", "process_seconds"),
            "cpu_seconds_long": med(np_, "long", "cpu_seconds"),
            "lammps_loop_seconds_long": med(np_, "long", "lammps_loop_seconds"),
            "atom_steps_per_s_wall": n * p1["steps"]["long"] / med(np_, "long", "wall_seconds"),
            "atom_steps_per_s_loop": n * dsteps / (med(np_, "long", "wall_seconds")
                                                   - med(np_, "short", "wall_seconds")),
        }
    speedup = {
        "md_wall": res["1"]["wall_seconds_long"] / res[str(ranks)]["wall_seconds_long"],
        "process": res["1"]["process_seconds_long"] / res[str(ranks)]["process_seconds_long"],
        "loop_only": res[str(ranks)]["atom_steps_per_s_loop"] / res["1"]["atom_steps_per_s_loop"],
        "lammps_loops": res["1"]["lammps_loop_seconds_long"] / res[str(ranks)]["lammps_loop_seconds_long"],
    }
    # statistics (the runs are deterministic for a seed and a rank count: take rep 0, long)
    s1, s2 = (read_summary(outs[(k, "long", 0)]) for k in (1, ranks))
    a, b = (read_series(outs[(k, "long", 0)]) for k in (1, ranks))
    m = min(a["T"].shape[1], b["T"].shape[1])
    rel = np.abs(b["T"][0, :m] / a["T"][0, :m] - 1)
    stats = {
        "haff_t0_measured": [s1["haff_t0_measured"], s2["haff_t0_measured"]],
        "haff_t0_measured_error": [s1["haff_t0_measured_error"], s2["haff_t0_measured_error"]],
        "haff_t0_z": (s2["haff_t0_measured"] - s1["haff_t0_measured"])
        / math.hypot(s1["haff_t0_measured_error"], s2["haff_t0_measured_error"]),
        "haff_t0_theory": s1["haff_t0_theory"],
        "T_initial": [float(a["T"][0, 0]), float(b["T"][0, 0])],
        "T_final": [float(a["T"][0, m - 1]), float(b["T"][0, m - 1])],
        "T_max_relative_difference": float(rel.max()),
        "steps": [s1["steps"], s2["steps"]],
        "restitution_measured": [s1["restitution_measured"], s2["restitution_measured"]],
    }
    return {"ranks": ranks, "runs": runs, "median": res, "speedup": speedup, "statistics": stats,
            "series": {"t": a["t"][:m].tolist(), "T_1": a["T"][0, :m].tolist(),
                       f"T_{ranks}": b["T"][0, :m].tolist()},
            "commands": {"1": next(r["command"] for r in runs if r["ranks"] == 1),
                         str(ranks): next(r["command"] for r in runs if r["ranks"] == ranks)}}


# ------------------------------------------------------------------------------------------------
# Part 2: adaptive stiffness

def part_adaptive(cfg, work):
    base = [f"md.particles={cfg['p2_particles']}", f"md.box_width={cfg['p2_box_width']!r}",
            f"md.restitution={cfg['p2_restitution']!r}", f"md.ensemble={cfg['p2_ensemble']}"]
    p = probe(work, base[:3] + ["md.t_end=0.05", "md.sample_interval=0.05", "md.ensemble=1"])
    t0 = p["haff_t0_theory"]
    t_end = cfg["p2_t0_multiple"] * t0
    interval = t_end / cfg["p2_samples"]
    common = base + [f"md.t_end={t_end!r}", f"md.sample_interval={interval!r}"]
    # the same seeds (members 1..3) for both: the same initial particles, so the paired difference
    # per member removes the initial-condition noise; the unpaired test (the two ensembles'
    # standard errors combined as if independent) is the conservative one
    variants = {"fixed": common + ["md.adaptive_stiffness=false", "md.seed=1"],
                "adaptive": common + ["md.adaptive_stiffness=true", "md.seed=1"]}
    log(f"part 2: t0 = {t0:.4g}, t_end = {t_end:.4g}, sample interval {interval:.4g}")
    runs, outs = [], {}
    for rep in range(cfg["repeats"]):
        for name, sets in variants.items():
            r, out = run_bridge(work, f"adapt_{name}_{rep}", sets, cfg["max_wait"])
            md = read_summary(out)
            r.update(variant=name, rep=rep, stiffness_changes=md["stiffness_changes"],
                     contact_initial=md["contact_initial"], contact_final=md["contact_final"],
                     haff_t0_measured=md["haff_t0_measured"],
                     haff_t0_measured_error=md["haff_t0_measured_error"])
            outs[(name, rep)] = out
            runs.append(r)
            log(f"  {name} rep {rep}: md.wall {r['wall_seconds']:.2f} s, {r['steps']} steps, "
                f"{r['stiffness_changes']} stiffness changes (load {r['load1']})")

    def med(name, key):
        return median([r[key] for r in runs if r["variant"] == name])

    f, a = (read_series(outs[(k, 0)]) for k in ("fixed", "adaptive"))
    tf, ta = f["t"], a["t"]
    # the adaptive run's samples sit at nearly the same times (llround(S/dt) steps each, t of
    # member 0 stored): put it onto the fixed run's times, interpolating in log T
    Tf = f["T"]
    m = min(len(tf), len(ta))
    if len(tf) == len(ta) and np.allclose(tf, ta, rtol=0, atol=1e-9 * t_end):
        Ta = a["T"]
    else:
        Ta = np.array([np.exp(np.interp(tf, ta[:len(row)], np.log(row))) for row in a["T"]])
    k = Tf.shape[0]
    mf, ma = np.nanmean(Tf, axis=0), np.nanmean(Ta, axis=0)
    ef = np.nanstd(Tf, axis=0, ddof=1) / np.sqrt(k)
    ea = np.nanstd(Ta, axis=0, ddof=1) / np.sqrt(k)
    sel = tf > 0
    z = np.zeros_like(mf)
    z[sel] = (ma[sel] - mf[sel]) / np.hypot(ef[sel], ea[sel])
    d = Ta - Tf  # paired, per member
    ed = np.nanstd(d, axis=0, ddof=1) / np.sqrt(k)
    md_ = np.nanmean(d, axis=0)
    # before the first stiffness change the members are the same runs (round-off apart): z = 0
    same = np.all(np.abs(d) <= 1e-12 * np.abs(Tf), axis=0)
    zp = np.zeros_like(mf)
    ok = sel & ~same & (ed > 0)
    zp[ok] = md_[ok] / ed[ok]
    rel = (Ta / Tf - 1)[:, sel]
    # bias over the whole run: each member's time-averaged relative difference, then over members
    D = np.nanmean(rel, axis=1)
    sf = read_summary(outs[("fixed", 0)])
    sa = read_summary(outs[("adaptive", 0)])
    comparison = {
        "max_abs_z": float(np.max(np.abs(z[sel]))),
        "median_abs_z": float(np.median(np.abs(z[sel]))),
        "fraction_abs_z_above_2": float(np.mean(np.abs(z[sel]) > 2)),
        "max_abs_z_paired": float(np.max(np.abs(zp[ok]))) if ok.any() else 0.0,
        "median_abs_z_paired": float(np.median(np.abs(zp[ok]))) if ok.any() else 0.0,
        "fraction_abs_z_paired_above_2": float(np.mean(np.abs(zp[ok]) > 2)) if ok.any() else 0.0,
        "samples_paired": int(ok.sum()),
        "max_relative_difference_of_means": float(np.max(np.abs(ma[sel] / mf[sel] - 1))),
        "mean_relative_difference_of_means": float(np.mean(ma[sel] / mf[sel] - 1)),
        "max_relative_difference_per_member": float(np.nanmax(np.abs(rel))),
        "time_averaged_relative_difference": float(np.mean(D)),
        "time_averaged_relative_difference_stderr": float(np.std(D, ddof=1) / np.sqrt(len(D))),
        "relative_stderr_of_mean_median": float(np.median(ef[sel] / mf[sel])),
        "haff_t0_measured": {"fixed": [sf["haff_t0_measured"], sf["haff_t0_measured_error"]],
                             "adaptive": [sa["haff_t0_measured"], sa["haff_t0_measured_error"]]},
        "haff_t0_z": (sa["haff_t0_measured"] - sf["haff_t0_measured"])
        / math.hypot(sf["haff_t0_measured_error"], sa["haff_t0_measured_error"]),
        "T_fall": {"fixed": float(mf[0] / mf[-1]), "adaptive": float(ma[0] / ma[-1])},
        "samples": int(sel.sum()),
        "sample_time_offset_max": float(np.max(np.abs(ta[:m] - tf[:m]))),
        "samples_identical_before_first_stiffness_change": int(np.sum(same & sel)),
    }
    res = {name: {"wall_seconds_median": med(name, "wall_seconds"),
                  "process_seconds_median": med(name, "process_seconds"),
                  "steps": med(name, "steps"), "stiffness_changes": med(name, "stiffness_changes")}
           for name in variants}
    return {"particles": cfg["p2_particles"], "box_width": cfg["p2_box_width"],
            "restitution": cfg["p2_restitution"], "ensemble": cfg["p2_ensemble"],
            "haff_t0_theory": t0, "t_end": t_end, "sample_interval": interval,
            "runs": runs, "median": res,
            "speedup_wall": res["fixed"]["wall_seconds_median"] / res["adaptive"]["wall_seconds_median"],
            "steps_ratio": res["fixed"]["steps"] / res["adaptive"]["steps"],
            "comparison": comparison,
            "series": {"t": tf.tolist(), "T_fixed": mf.tolist(), "T_fixed_stderr": ef.tolist(),
                       "T_adaptive": ma.tolist(), "T_adaptive_stderr": ea.tolist(),
                       "z": z.tolist(), "z_paired": zp.tolist(),
                       "T_fixed_members": Tf.tolist(), "T_adaptive_members": Ta.tolist()},
            "commands": {k: next(r["command"] for r in runs if r["variant"] == k) for k in variants}}


# ------------------------------------------------------------------------------------------------
# Outputs

def plot(res, path):
    p1, p2, p3 = res["bridge_vs_lammps"], res["adaptive_stiffness"], res["mpi"]
    fig, ax = plt.subplots(2, 2, figsize=(12, 9))
    # (a) throughput
    r = p1["rates_atom_steps_per_s"]
    labels = ["lmp\nprocess", "lmp\nloop", "lmp in\nsegments\nloops", "bridge\nLAMMPS\nloops",
              "bridge\nloops +\nsegment\ncost", "bridge\nmd.wall", "bridge\nprocess"]
    keys = ["lammps_process", "lammps_loop", "lammps_segmented_loop", "bridge_lammps_loop",
            "bridge_run_loop_with_segment_overhead", "bridge_md_wall", "bridge_process"]
    vals = [r[k]["median"] for k in keys]
    colors = ["#777", "#444", "#999", "#9fbfe9", "#5f8fd0", "#3f77c0", "#1f4f90"]
    a = ax[0, 0]
    bars = a.bar(range(len(vals)), np.array(vals) / 1e6, color=colors)
    for i, (b, v, k) in enumerate(zip(bars, vals, keys)):
        top = max(v, r[k].get("max", v))
        a.text(b.get_x() + b.get_width() / 2, top / 1e6 + 0.5, f"{v / 1e6:.1f}", ha="center",
               va="bottom", fontsize=8)
        if "min" in r[k]:
            a.plot([i, i], [r[k]["min"] / 1e6, r[k]["max"] / 1e6], c="k", lw=1)
    a.axhline(0.95 * r["lammps_process"]["median"] / 1e6, ls="--", c="k", lw=0.8,
              label="95 % of bare lmp (process)")
    a.set_xticks(range(len(vals)))
    a.set_xticklabels(labels, fontsize=8)
    a.set_ylabel("10⁶ atom-steps / s")
    a.set_title(f"(a) {p1['particles']} disks, fixed kn, {p1['steps']['long']} steps "
                f"(median, min–max of {res['config']['repeats']})", fontsize=10)
    a.legend(fontsize=8, loc="lower right")
    # (b) T(t)
    s = p2["series"]
    t = np.array(s["t"])
    a = ax[0, 1]
    for key, c, lab in (("T_fixed", "C0", "fixed kn"), ("T_adaptive", "C3", "adaptive kn")):
        T, e = np.array(s[key]), np.array(s[key + "_stderr"])
        a.plot(t, T, c=c, lw=1, label=lab)
        a.fill_between(t, T - e, T + e, color=c, alpha=0.3, lw=0)
    a.plot(t, s["T_fixed"][0] * (1 + t / p2["haff_t0_theory"]) ** -2, "k--", lw=0.8,
           label="Haff, t0 from theory")
    a.set_yscale("log")
    a.set_xlabel("t (MD units)")
    a.set_ylabel("T (ensemble mean ± stderr)")
    m = p2["median"]
    a.set_title(f"(b) {p2['particles']} disks, r = {p2['restitution']}, ensemble {p2['ensemble']}: "
                f"adaptive {m['adaptive']['wall_seconds_median']:.1f} s vs fixed "
                f"{m['fixed']['wall_seconds_median']:.1f} s", fontsize=10)
    a.legend(fontsize=8)
    # (c) z(t)
    a = ax[1, 0]
    a.plot(t[1:], s["z"][1:], lw=0.8, label="ΔT / combined stderr (ensembles as independent)")
    a.plot(t[1:], s["z_paired"][1:], lw=0.8, label="paired: mean of per-member ΔT / its stderr")
    for y in (-2, 2):
        a.axhline(y, c="k", ls=":", lw=0.8)
    a.set_xlabel("t (MD units)")
    a.set_ylabel("(T_adaptive − T_fixed) / σ")
    a.set_title(f"(c) max |z| = {p2['comparison']['max_abs_z']:.2f} (paired "
                f"{p2['comparison']['max_abs_z_paired']:.2f}), max |ΔT̄|/T̄ = "
                f"{100 * p2['comparison']['max_relative_difference_of_means']:.2f} %", fontsize=10)
    a.legend(fontsize=8)
    # (d) MPI
    a = ax[1, 1]
    k = str(p3["ranks"])
    w = [p3["median"]["1"]["wall_seconds_long"], p3["median"][k]["wall_seconds_long"]]
    bars = a.bar([0, 1], w, color=["#3f77c0", "#1f4f90"])
    for b, v in zip(bars, w):
        a.text(b.get_x() + b.get_width() / 2, v, f"{v:.2f} s", ha="center", va="bottom")
    st = p3["statistics"]
    a.set_xticks([0, 1])
    a.set_xticklabels([f"1 rank\nt0 = {st['haff_t0_measured'][0]:.3f} ± {st['haff_t0_measured_error'][0]:.3f}",
                       f"{k} ranks\nt0 = {st['haff_t0_measured'][1]:.3f} ± {st['haff_t0_measured_error'][1]:.3f}"])
    a.set_ylabel("md.wall_seconds")
    a.set_title(f"(d) MPI, {p1['particles']} disks: speed-up {p3['speedup']['md_wall']:.2f}× "
                f"(LAMMPS loops {p3['speedup']['lammps_loops']:.2f}×)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def markdown(res):
    p1, p2, p3 = res["bridge_vs_lammps"], res["adaptive_stiffness"], res["mpi"]
    r, rel = p1["rates_atom_steps_per_s"], p1["relative"]
    loads = lambda runs: f"{min(x['load1'] for x in runs):.3f}–{max(x['load1'] for x in runs):.3f}"  # noqa: E731
    L = [f"# Particle-engine benchmarks ({res['generated']}{', QUICK' if res['quick'] else ''})", "",
         f"Made by `/usr/bin/python3 scripts/md_benchmarks.py`; raw numbers in `md_benchmarks.json`, "
         f"chart `md_benchmarks.png`. {res['machine']['cores']} cores; medians of "
         f"{res['config']['repeats']} timings, each started when the 1-min load average was < "
         f"{LOAD_LIMIT} (or after {res['config']['max_wait']:.0f} s of waiting).", "",
         f"## 1. Bridge against bare LAMMPS ({p1['particles']} disks, fixed kn, coarse-grained "
         f"every {SEGMENT} steps, {p1['steps']['long']} steps; loads {loads(p1['runs'])})", "",
         "| | atom-steps/s | seconds (long / short run) |", "|---|---|---|",
         *[f"| {name} | {r[k]['median']:.4g} | {r[k]['seconds_long_median']:.3f} / "
           f"{r[k]['seconds_short_median']:.3f} |" for name, k in (
               ("bare `lmp`, whole process", "lammps_process"),
               ("bare `lmp`, LAMMPS loop time (thermo `cpu`)", "lammps_loop"),
               (f"bare `lmp` in {SEGMENT}-step `run pre no post no` segments, with a log: whole process",
                "lammps_segmented_process"),
               ("the same, sum of LAMMPS loop times", "lammps_segmented_loop"),
               ("bridge, `md.wall_seconds`", "bridge_md_wall"),
               ("bridge, whole `granvv` process", "bridge_process"),
               ("bridge, sum of LAMMPS loop times (its log.lammps)", "bridge_lammps_loop"))],
         f"| bridge, LAMMPS loops + per-segment cost (no fixed costs) | "
         f"{r['bridge_run_loop_with_segment_overhead']['median']:.4g} | |",
         "",
         f"- Whole runs: bridge `md.wall_seconds` against the whole `lmp` process "
         f"{100 * rel['bridge_md_wall_vs_lammps_process']:+.1f} % (per repeat "
         f"{100 * rel['bridge_md_wall_vs_lammps_process_per_repeat']['min']:+.1f} … "
         f"{100 * rel['bridge_md_wall_vs_lammps_process_per_repeat']['max']:+.1f} %); whole `granvv` "
         f"process against whole `lmp` process {100 * rel['bridge_process_vs_lammps_process']:+.1f} % "
         f"(CPU seconds {100 * rel['bridge_process_cpu_vs_lammps_process_cpu']:+.1f} %).",
         f"- Run loops by differencing the two lengths (the brief's method; noisy): "
         f"{100 * rel['bridge_vs_lammps_differenced']:+.1f} %.",
         f"- Run loops from LAMMPS' own timers: the bridge's LAMMPS loops against bare lmp's "
         f"{100 * rel['bridge_lammps_loop_vs_lammps_loop']:+.1f} % (per repeat "
         f"{100 * rel['bridge_lammps_loop_vs_lammps_loop_per_repeat']['min']:+.1f} … "
         f"{100 * rel['bridge_lammps_loop_vs_lammps_loop_per_repeat']['max']:+.1f} %); with the bridge's "
         f"per-segment cost {100 * rel['bridge_run_loop_vs_lammps_loop']:+.1f} %. Bare lmp run in "
         f"{SEGMENT}-step segments: {100 * rel['lammps_segmented_loop_vs_lammps_loop']:+.1f} % (loops), "
         f"{100 * rel['lammps_segmented_process_vs_lammps_process']:+.1f} % (process).",
         f"- The bridge outside LAMMPS' loops: {rel['bridge_outside_loop_seconds_long']:.3f} s of "
         f"{r['bridge_md_wall']['seconds_long_median']:.2f} s "
         f"({100 * rel['bridge_outside_loop_fraction_long']:.1f} %) = "
         f"{rel['bridge_outside_loop_per_segment_ms']:.3f} ms per {SEGMENT}-step segment (setup of `run pre "
         f"no`, thermo, coarse-graining) + {rel['bridge_outside_loop_fixed_seconds']:.3f} s fixed "
         f"(sampling, restitution calibration). Outside `md.wall_seconds` the `granvv` process spends "
         f"{rel['bridge_process_minus_md_wall_seconds']:.2f} s (start-up, HDF5/JSON output); bare `lmp` "
         f"{rel['lammps_process_minus_loop_seconds']:.2f} s outside its loop (start-up, read_data, setup).",
         "- Target: bridge within 5 % of bare LAMMPS.",
         f"- Physics check: T(end)/T(0) = {p1['physics_check']['bridge_T_ratio_long']:.4f} (bridge), "
         f"{p1['physics_check']['lammps_T_ratio_long']:.4f} (lmp), Haff "
         f"{p1['physics_check']['haff_T_ratio_theory']:.4f}.", "",
         f"## 2. Adaptive stiffness ({p2['particles']} disks, r = {p2['restitution']}, t_end = "
         f"{p2['t_end']:.4g} = {p2['t_end'] / p2['haff_t0_theory']:.3g} t0, ensemble {p2['ensemble']}; "
         f"loads {loads(p2['runs'])})", "",
         "| | wall s | steps (all members) | stiffness changes | T fall | Haff t0 fitted |",
         "|---|---|---|---|---|---|"]
    c = p2["comparison"]
    for k in ("fixed", "adaptive"):
        m = p2["median"][k]
        L.append(f"| {k} | {m['wall_seconds_median']:.2f} | {m['steps']:.0f} | "
                 f"{m['stiffness_changes']:.0f} | {c['T_fall'][k]:.1f}× | "
                 f"{c['haff_t0_measured'][k][0]:.2f} ± {c['haff_t0_measured'][k][1]:.2f} |")
    L += ["", f"Speed-up {p2['speedup_wall']:.2f}× (steps {p2['steps_ratio']:.2f}×). Same seeds "
          f"(same initial particles) for both. T(t) over {c['samples']} samples: max |ΔT̄|/σ = "
          f"{c['max_abs_z']:.2f} with the two ensembles' standard errors combined (median "
          f"{c['median_abs_z']:.2f}, {100 * c['fraction_abs_z_above_2']:.0f} % of samples above 2); "
          f"paired per member (over the {c['samples_paired']} samples after the first stiffness change): "
          f"max {c['max_abs_z_paired']:.2f} (median {c['median_abs_z_paired']:.2f}, "
          f"{100 * c['fraction_abs_z_paired_above_2']:.0f} % above 2; 3 members: 2 dof). "
          f"Max |ΔT̄|/T̄ = {100 * c['max_relative_difference_of_means']:.2f} % (mean "
          f"{100 * c['mean_relative_difference_of_means']:+.2f} %; stderr of the mean "
          f"{100 * c['relative_stderr_of_mean_median']:.2f} %); time-averaged paired difference "
          f"{100 * c['time_averaged_relative_difference']:+.2f} ± "
          f"{100 * c['time_averaged_relative_difference_stderr']:.2f} %; Haff t0 fit Δ/σ = {c['haff_t0_z']:+.2f}.",
          "", f"## 3. MPI ({p1['particles']} disks, part-1 settings; loads {loads(p3['runs'])})", "",
          "| ranks | md.wall s | process s | CPU s (all ranks) | LAMMPS loops s | atom-steps/s (differenced) | Haff t0 fitted |",
          "|---|---|---|---|---|---|---|"]
    st = p3["statistics"]
    for i, k in enumerate(("1", str(p3["ranks"]))):
        m = p3["median"][k]
        L.append(f"| {k} | {m['wall_seconds_long']:.2f} | {m['process_seconds_long']:.2f} | "
                 f"{m['cpu_seconds_long']:.2f} | {m['lammps_loop_seconds_long']:.2f} | "
                 f"{m['atom_steps_per_s_loop']:.3g} | {st['haff_t0_measured'][i]:.4f} ± "
                 f"{st['haff_t0_measured_error'][i]:.4f} |")
    L += ["", f"Speed-up {p3['speedup']['md_wall']:.2f}× (md.wall), {p3['speedup']['process']:.2f}× "
          f"(process), {p3['speedup']['lammps_loops']:.2f}× (LAMMPS loops), "
          f"{p3['speedup']['loop_only']:.2f}× (differenced). Statistics: Δt0/σ = "
          f"{st['haff_t0_z']:+.3g}; max |ΔT|/T over the run {st['T_max_relative_difference']:.2g}. "
          "Both start from the same particles (the sampler is serial and seeded), so this checks that "
          "the domain decomposition changes nothing, not that two independent samples agree"
          + (": here the two runs coincide to round-off." if st["T_max_relative_difference"] < 1e-10
             else "."), ""]
    return "\n".join(L)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="short runs, one repeat (smoke check)")
    ap.add_argument("--out-dir", help="where to write md_benchmarks.{json,png,md}")
    ap.add_argument("--max-wait", type=float, help="seconds to wait for load < 0.5 before a timing")
    ap.add_argument("--from-json", help="only redraw the chart and table from this md_benchmarks.json")
    ap.add_argument("--keep", help="keep the runs' outputs in this directory (default: a temp dir)")
    args = ap.parse_args()
    cfg = dict(QUICK if args.quick else FULL)
    if args.max_wait is not None:
        cfg["max_wait"] = args.max_wait
    outdir = args.out_dir or os.path.join(ROOT, "out/md_benchmarks_quick" if args.quick else "docs")
    os.makedirs(outdir, exist_ok=True)
    if args.from_json:
        with open(args.from_json) as f:
            res = json.load(f)
        plot(res, os.path.join(outdir, "md_benchmarks.png"))
        with open(os.path.join(outdir, "md_benchmarks.md"), "w") as f:
            f.write(markdown(res))
        return
    for exe in (GRANVV, LMP):
        if not os.access(exe, os.X_OK):
            sys.exit(f"{exe} not found (build first: scripts/setup.sh)")
    work = args.keep or tempfile.mkdtemp(prefix="md_benchmarks_")
    os.makedirs(work, exist_ok=True)
    try:
        started = time.time()
        res = {"generated": datetime.datetime.now().strftime("%Y-%m-%d %H:%M"), "quick": args.quick,
               "config": cfg, "load_limit": LOAD_LIMIT,
               "granvv_binary_mtime": datetime.datetime.fromtimestamp(
                   os.path.getmtime(GRANVV)).strftime("%Y-%m-%d %H:%M:%S"),
               "machine": {"cores": os.cpu_count(), "platform": platform.platform(),
                           "lammps": subprocess.run([LMP, "-h"], capture_output=True, text=True)
                           .stdout.splitlines()[1].strip()}}
        res["bridge_vs_lammps"] = part_bridge_vs_lammps(cfg, work)
        res["adaptive_stiffness"] = part_adaptive(cfg, work)
        log("part 3: MPI")
        res["mpi"] = part_mpi(cfg, work, res["bridge_vs_lammps"])
        res["total_seconds"] = time.time() - started
        res["granvv_binary_mtime_end"] = datetime.datetime.fromtimestamp(
            os.path.getmtime(GRANVV)).strftime("%Y-%m-%d %H:%M:%S")
        with open(os.path.join(outdir, "md_benchmarks.json"), "w") as f:
            json.dump(res, f, indent=1)
        plot(res, os.path.join(outdir, "md_benchmarks.png"))
        with open(os.path.join(outdir, "md_benchmarks.md"), "w") as f:
            f.write(markdown(res))
        print(markdown(res))
        log(f"wrote {outdir}/md_benchmarks.{{json,png,md}} in {res['total_seconds']:.0f} s")
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
