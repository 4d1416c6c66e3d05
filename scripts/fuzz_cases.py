#!/usr/bin/python3
"""Fuzz the granvv CLI with mutated case files and --set lines.

Each input is one of the shipped scenes (cases/*.toml) with mutations: a --set of a schema key
to a hostile value (integers beyond 2^31 and 2^63, reals 0, 1e-300, 1e300, nan, inf, wrong types,
arrays out of order, strings with control characters, non-UTF-8 bytes or 300 kB), an unknown or
misspelt key, or a corrupted case file (a deleted, repeated or replaced character, a truncated
line, non-UTF-8 bytes, a duplicated key). Most inputs run with --dry-run; a share runs for real
with the scene shrunk to a few dozen cells (and, for particle scenes, a few hundred disks for a
short time), so that every input ends within the time bound unless it hangs.

Asserted for every input, with the real CLI:
  - no death by a signal, and no exit code outside 0, 1, 2;
  - no hang: each run ends within --timeout seconds, or is still advancing then (its progress
    lines, one a second, show t moving: a valid long run, counted as "slow");
  - exit 2: exactly one line on stderr, "granvv: error: ...", and no output folder created;
  - exit 0 of a dry run: the resolved case it prints runs again (--dry-run of it exits 0 and
    resolves to the same keys and values);
  - exit 0 or 1 of a real run: summary.json is JSON without NaN or Infinity, /hydro of
    results.h5 holds no NaN (the md and compare groups use NaN for absent values, as
    docs/outputs.md says), the cells that ran are the cells case.toml resolved, and the
    case.toml written re-runs (--dry-run exits 0).

With --kind files (or both), the inputs are instead the files a scene reads: mutated CSV and
HDF5 tables and snapshot files (scripts/fuzz_files.py), run as initial.type = "table" or
"snapshot" with the same assertions; and damaged checkpoints and atlas cache entries. A
checkpoint is resumed (`granvv resume`): exit 2 with one line and no summary written, or a run
whose summary.json and /hydro hold no NaN and whose particle series (t, T, energies, momenta)
are finite. An atlas reads its damaged cache entry: it exits 0 (the entry's setting is run
again) with an atlas.json that is strict JSON.

Usage: fuzz_cases.py --granvv build/granvv [--count 2000] [--seed 1] [--real-fraction 0.1]
                     [--timeout 120] [--jobs 1] [--work DIR] [--kind cases|files|both]
Prints the counts; exits 1 if any input broke an assertion (each is printed with its command), 2
if stopped (SIGTERM or SIGINT) before the last input, with the counts of those it finished.
"""
import argparse
import concurrent.futures
import datetime
import json
import math
import os
import random
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(Path(__file__).resolve().parent))

# Scenes cheap enough to run for real after shrinking (hydro: a few dozen cells; particles: a
# few hundred disks for a short time).
SHRINK_HYDRO = ["hydro.cells=32", "hydro.progress_seconds=1"]
SHRINK_MD = ["md.particles=200", "md.ensemble=1", "md.box_width=20.0", "md.bins=4",
             "md.t_end=2.0", "md.output_times=[0.0, 2.0]", "md.sample_interval=0.5",
             "md.snapshot_interval=0.0", "md.time_unit='md'", "compare.density_modes=1"]
SHRINK_SCENE = {"clustering": ["initial.random_modes=8"]}

INTEGERS = [0, -1, 1, 2, 3, 4, 7, 2**31 - 1, 2**31, 2**32, 2**32 + 4, 2**53 + 1, 2**63 - 1,
            -(2**63), 10**9, 10**7, 100000, 1000]
REALS = ["0", "0.0", "-0.0", "-1", "1e-300", "1e300", "1e154", "-1e300", "nan", "inf", "-inf",
         "5e-324", "1.7976931348623157e308", "0.5", "1", "2", "1e-8", "100", "0.999999"]
STRINGS = ['""', '"x"', '"../up"', '"a/b"', '"\\u0001"', '"\\n"', '"é"', '"' + "a" * 300 + '"',
           "bare", "'single'", '"lammps"', '"md"', '"haff"', '"gaussian"', '"case"']
WRONG = ["true", "false", "[]", "[1, 2]", "[2, 1]", "[1.0, 0.5]", "[[1]]", "{a = 1}", '"3"',
         "1979-05-27", "[1, \"x\"]", "[0, 1e300]", "[-1]", "[0, 0]", "99999999999999999999",
         "1_000", "0x10", "+inf", "1e", "=", "'", ""]


def log(*args):
    print(*args, flush=True)


def resolved_keys(granvv, case, env):
    """The flattened keys of a scene and their TOML types, from its --dry-run."""
    out = subprocess.run([granvv, "run", case, "--dry-run"], capture_output=True, env=env,
                         timeout=60, check=True).stdout
    table = tomllib.loads(out.decode())
    keys = {}

    def walk(t, prefix):
        for k, v in t.items():
            if isinstance(v, dict):
                walk(v, prefix + k + ".")
            else:
                keys[prefix + k] = v
    walk(table, "")
    return keys


def value_for(rng, current):
    """A hostile TOML value for a key whose resolved value is `current`."""
    pool = rng.random()
    if pool < 0.15:
        return rng.choice(WRONG)
    if isinstance(current, bool):
        return rng.choice(["true", "false", "1", "yes", '"true"'])
    if isinstance(current, int):
        if rng.random() < 0.7:
            return str(rng.choice(INTEGERS))
        return str(int(current * rng.choice([0.5, 2, 10, 1000, -1])) + rng.randint(-2, 2))
    if isinstance(current, float):
        if rng.random() < 0.6:
            return rng.choice(REALS)
        return repr(current * 10 ** rng.randint(-12, 12))
    if isinstance(current, str):
        return rng.choice(STRINGS)
    if isinstance(current, list):
        n = rng.randint(0, 4)
        if current and isinstance(current[0], int) or rng.random() < 0.3:
            items = [str(rng.choice(INTEGERS + [5, 15, 45, 125])) for _ in range(n)]
        else:
            items = [rng.choice(REALS[:8] + ["0.25", "1.0", "3.0", "250.0"]) for _ in range(n)]
        if rng.random() < 0.5:
            items.sort(key=lambda s: float(s) if s not in ("nan",) else 0)
        return "[" + ", ".join(items) + "]"
    return rng.choice(WRONG)


def mutate_text(rng, text):
    """A corrupted case file (bytes)."""
    data = bytearray(text.encode())
    kind = rng.randrange(6)
    if not data:
        return bytes(data)
    i = rng.randrange(len(data))
    if kind == 0:
        del data[i]
    elif kind == 1:
        data[i:i] = bytes([data[i]]) * rng.randint(1, 3)
    elif kind == 2:
        data[i] = rng.choice(b"=[]{}\"'#.,\n 0\xff\xfe\x00\x01")
    elif kind == 3:
        data = data[:i]
    elif kind == 4:
        data[i:i] = rng.choice([b"\xff\xfe", b"\xc3\x28", b"\xed\xa0\x80", b"\xf4\x90\x80\x80"])
    else:
        lines = bytes(data).split(b"\n")
        j = rng.randrange(len(lines))
        lines.insert(j, lines[j])  # a duplicated key or table
        data = bytearray(b"\n".join(lines))
    return bytes(data)


def make_input(rng, scenes, keys_of, real_fraction):
    """(scene, case file bytes or None, --set list, real run?) for one mutated input."""
    scene = rng.choice(scenes)
    real = rng.random() < real_fraction
    keys = keys_of[scene]
    sets = []
    file_bytes = None
    style = rng.random()
    if style < 0.15:
        text = (ROOT / "cases" / (scene + ".toml")).read_text()
        file_bytes = mutate_text(rng, text)
    for _ in range(rng.choice([1, 1, 1, 2, 3])):
        if rng.random() < 0.08:  # an unknown or misspelt key
            key = rng.choice(list(keys))
            key = rng.choice([key + "x", key[:-1], key.replace(".", "..", 1), "nosuch.key",
                              key.split(".")[0], "." + key, key.upper()])
            sets.append(key + "=" + value_for(rng, 1))
        elif rng.random() < 0.04:
            sets.append(rng.choice(["=", "x", "physics.K", "physics.K==1", " = 1"]))
        else:
            key = rng.choice(list(keys))
            sets.append(key + "=" + value_for(rng, keys[key]))
    if rng.random() < 0.03:  # a non-UTF-8 value or a long one through argv
        key = rng.choice(["case.name", "case.description", "md.kernel", "initial.type"])
        sets.append(key.encode() + b"=" + rng.choice([b"a\xff\xfeb", b"x" * 5000, b"\xc0\xaf"]))
    return scene, file_bytes, sets, real, {}, None


def make_file_input(rng, bases, real_fraction):
    """A mutated table or snapshot file as an input (the case file untouched), or a damaged
    checkpoint to resume, or a damaged atlas cache entry to read again (a command of its own)."""
    import fuzz_files
    kind = rng.random()
    if kind < 0.25:
        files, command = fuzz_files.make_checkpoint_input(rng, bases["checkpoint"])
        return "resume", None, [], True, files, command
    if kind < 0.3:
        files, command = fuzz_files.make_atlas_input(rng, bases["atlas"])
        return "atlas", None, [], True, files, command
    scene, files, sets = fuzz_files.make_file_input(rng, bases["snapshot"])
    return scene, None, sets, rng.random() < real_fraction, files, None


def run(cmd, timeout, cwd, env):
    try:
        p = subprocess.run(cmd, capture_output=True, timeout=timeout, cwd=cwd, env=env)
        return p.returncode, p.stdout, p.stderr, False
    except subprocess.TimeoutExpired as e:
        return None, e.stdout or b"", e.stderr or b"", True


def still_advancing(run_log, killed_at):
    """True if run.log shows a run that was still making progress when it was stopped: its
    last two progress lines (one a second, hydro.progress_seconds = 1) have different times t
    and the last one is recent. A valid but long run is "slow", not a hang."""
    try:
        lines = [l for l in run_log.read_text(errors="replace").splitlines() if " t=" in l]
    except OSError:
        return False
    if len(lines) < 2:
        return False
    def parse(line):
        stamp = datetime.datetime.strptime(line[1:24], "%Y-%m-%d %H:%M:%S.%f").timestamp()
        return stamp, line.split(" t=")[1].split()[0]
    try:
        (t1, v1), (t2, v2) = parse(lines[-2]), parse(lines[-1])
    except (ValueError, IndexError):
        return False
    return v1 != v2 and killed_at - t2 < 10.0


def strict_json(text):
    def no_constant(name):
        raise ValueError("summary.json holds " + name)
    return json.loads(text, parse_constant=no_constant)


def hydro_nan(path):
    try:
        import h5py
        import numpy as np
    except ImportError:
        return None
    found = []
    with h5py.File(path, "r") as f:
        if "hydro" not in f:
            return None

        def visit(name, obj):
            if isinstance(obj, h5py.Dataset) and obj.dtype.kind == "f" and obj.size:
                if np.isnan(obj[()]).any():
                    found.append("hydro/" + name)
        f["hydro"].visititems(visit)
    return found[0] if found else None


def md_nan(path):
    """The first of the particle series that every run measures holding a NaN or inf."""
    import h5py
    import numpy as np
    with h5py.File(path, "r") as f:
        if "md/timeseries" not in f:
            return None
        for name in ("t", "T", "energy_total", "energy_thermal", "momentum_x", "momentum_y"):
            if name in f["md/timeseries"] and not np.isfinite(f["md/timeseries"][name][()]).all():
                return "md/timeseries/" + name
    return None


def check_command(args, kind, command, work, env):
    """A damaged checkpoint resumed, or an atlas reading a damaged cache entry: (category,
    problem or None)."""
    code, stdout, stderr, hung = run([args.granvv] + command, args.timeout, work, env)
    kind += ":"
    if hung:
        return kind + "hang", "no answer within %g s" % args.timeout
    if code < 0:
        return kind + "signal", "killed by signal %d: %s" % (-code, stderr[-300:])
    if code not in (0, 1, 2):
        return kind + "exit%d" % code, "exit code %d" % code
    kind += "exit%d" % code
    if command[0] == "atlas":  # a damaged entry is run again: the atlas completes
        if code != 0:
            return kind, "the atlas exited %d: %r" % (code, stderr[-300:])
        try:
            strict_json((work / "atlas" / "atlas.json").read_text())
        except (OSError, ValueError) as e:
            return kind, "atlas.json: %s" % e
        return kind, None
    out = work / command[1]
    if code == 2:
        lines = stderr.decode(errors="replace").splitlines()
        if len(lines) != 1 or not lines[0].startswith("granvv: error: "):
            return kind, "exit 2 without exactly one error line: %r" % stderr[:400]
        if (out / "summary.json").exists():
            return kind, "exit 2 but a summary.json was written"
        return kind, None
    if not (out / "summary.json").exists():
        return kind, "no summary.json after exit %d" % code
    try:
        strict_json((out / "summary.json").read_text())
    except ValueError as e:
        return kind, "summary.json: %s" % e
    if (out / "results.h5").exists():
        nan = hydro_nan(out / "results.h5") or md_nan(out / "results.h5")
        if nan:
            return kind, "NaN or inf in results.h5 %s" % nan
    return kind, None


def check_one(index, args, item, env):
    """Runs one input; returns (category, problem or None, command text). With --keep-failures,
    a failing input's files and its command are kept in that folder (input_<index>/), so that it
    can be run again by hand."""
    kind, problem, text = check_input(index, args, item, env)
    if problem and args.keep_failures:
        keep = Path(args.keep_failures) / ("input_%d" % index)
        for name, data in item[4].items():
            (keep / name).parent.mkdir(parents=True, exist_ok=True)
            (keep / name).write_bytes(data)
        if item[1] is not None:
            (keep / (item[0] + ".toml")).write_bytes(item[1])
        keep.mkdir(parents=True, exist_ok=True)
        (keep / "command.txt").write_text("%s\n%s\n" % (text, problem))
    return kind, problem, text


def check_input(index, args, item, env):
    scene, file_bytes, sets, real, files, command = item
    work = Path(tempfile.mkdtemp(prefix="fuzz-%d-" % index, dir=args.work))
    try:
        for name, data in files.items():
            (work / name).parent.mkdir(parents=True, exist_ok=True)
            (work / name).write_bytes(data)
        if command:
            kind, problem = check_command(args, scene, command, work, env)
            text = "(in a folder with %s) %s" % (", ".join(sorted(files)), " ".join(
                shlex.quote(c) for c in [args.granvv] + command))
            return kind, problem, text
        case = scene
        if file_bytes is not None:
            case = str(work / (scene + ".toml"))
            Path(case).write_bytes(file_bytes)
        out = work / "out"
        cmd = [args.granvv, "run", case]
        if real:
            # The particle keys too: a mutation may switch the particles on in any scene.
            shrink = SHRINK_HYDRO + SHRINK_SCENE.get(scene, []) + SHRINK_MD
            for s in shrink:  # the mutations come last and win
                cmd += ["--set", s]
        for s in sets:
            cmd += ["--set", s]
        cmd += ["--out", str(out), "--quiet", "--no-report"]
        if not real:
            cmd.append("--dry-run")
        if files:
            text = "(in a folder with %s) " % ", ".join(files)
        else:
            text = ""
        text += " ".join(shlex.quote(os.fsdecode(c)) if isinstance(c, bytes) else shlex.quote(c)
                        for c in cmd)
        code, stdout, stderr, hung = run(cmd, args.timeout, work, env)
        kind = ("run" if real else "dry") + ":"
        if hung:
            if real and still_advancing(out / "run.log", time.time()):
                return kind + "slow", None, text
            return kind + "hang", "no answer within %g s" % args.timeout, text
        if code < 0:
            return kind + "signal", "killed by signal %d: %s" % (-code, stderr[-300:]), text
        if code not in (0, 1, 2):
            return kind + "exit%d" % code, "exit code %d" % code, text
        kind += "exit%d" % code
        if code == 2:
            lines = stderr.decode(errors="replace").splitlines()
            if len(lines) != 1 or not lines[0].startswith("granvv: error: "):
                return kind, "exit 2 without exactly one error line: %r" % stderr[:400], text
            if out.exists():
                return kind, "exit 2 but %s was created" % out, text
            return kind, None, text
        if not real:
            if code != 0:
                return kind, "a dry run exited %d: %r" % (code, stderr[:300]), text
            again = work / "resolved.toml"
            again.write_bytes(stdout)
            c2, s2, e2, h2 = run([args.granvv, "run", str(again), "--dry-run"], args.timeout,
                                 work, env)
            if h2 or c2 != 0:
                return kind, "the printed resolved case does not run again: %r" % e2[:300], text
            body = lambda b: [l for l in b.decode().splitlines() if not l.startswith("#")]
            if body(s2) != body(stdout):
                return kind, "the resolved case resolves differently when re-run", text
            return kind, None, text
        # A real run (exit 0 or 1).
        summary = out / "summary.json"
        if not summary.exists():
            return kind, "no summary.json after exit %d" % code, text
        try:
            written = strict_json(summary.read_text())
        except ValueError as e:
            return kind, "summary.json: %s" % e, text
        # What ran is what the resolved case says (a truncated integer would differ).
        try:
            resolved = tomllib.loads((out / "case.toml").read_text())
        except (OSError, ValueError) as e:
            return kind, "case.toml unreadable: %s" % e, text
        hydro = written.get("hydro")
        if isinstance(hydro, dict) and hydro.get("cells") != resolved["hydro"]["cells"]:
            return kind, "summary.json says %s cells, case.toml %s" % (
                hydro.get("cells"), resolved["hydro"]["cells"]), text
        if (out / "results.h5").exists():
            nan = hydro_nan(out / "results.h5")
            if nan:
                return kind, "NaN in results.h5 %s" % nan, text
        case_toml = out / "case.toml"
        if not case_toml.exists():
            return kind, "no case.toml", text
        c2, s2, e2, h2 = run([args.granvv, "run", str(case_toml), "--dry-run"], args.timeout,
                             work, env)
        if h2 or c2 != 0:
            return kind, "case.toml does not run again: %r" % e2[:300], text
        return kind, None, text
    finally:
        shutil.rmtree(work, ignore_errors=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--granvv", required=True)
    ap.add_argument("--count", type=int, default=200)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--real-fraction", type=float, default=0.1)
    ap.add_argument("--timeout", type=float, default=120.0)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--work", default=None)
    ap.add_argument("--kind", choices=["cases", "files", "both"], default="cases")
    ap.add_argument("--keep-failures", default=None,
                    help="folder where each failing input's files and command are kept")
    args = ap.parse_args()
    args.granvv = os.path.abspath(args.granvv)
    env = dict(os.environ)
    for v in ("OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"):
        env.pop(v, None)
    own_work = args.work is None
    args.work = args.work or tempfile.mkdtemp(prefix="granvv-fuzz-")
    rng = random.Random(args.seed)
    scenes = sorted(p.stem for p in (ROOT / "cases").glob("*.toml"))
    keys_of = {s: resolved_keys(args.granvv, s, env) for s in scenes}
    bases = None
    if args.kind != "cases":
        import fuzz_files
        bases = {"snapshot": fuzz_files.make_base_snapshot(args.granvv, args.work, env, run),
                 "checkpoint": fuzz_files.make_base_checkpoint(args.granvv, args.work, env),
                 "atlas": fuzz_files.make_base_atlas(args.granvv, args.work, env, run)}

    def one():
        if args.kind == "files" or (args.kind == "both" and rng.random() < 0.5):
            return make_file_input(rng, bases, args.real_fraction)
        return make_input(rng, scenes, keys_of, args.real_fraction)
    items = [one() for _ in range(args.count)]
    counts, failures = {}, []

    # SIGTERM or SIGINT stops a long run with the counts of the inputs finished so far (the
    # inputs are drawn before any runs, so those are the first inputs of the seed, give or take
    # the ones running in parallel).
    def stop(signum, frame):
        raise KeyboardInterrupt
    signal.signal(signal.SIGTERM, stop)
    done, stopped = 0, False
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(check_one, i, args, item, env) for i, item in enumerate(items)]
        try:
            for f in concurrent.futures.as_completed(futures):
                kind, problem, text = f.result()
                done += 1
                counts[kind] = counts.get(kind, 0) + 1
                if problem:
                    failures.append((kind, problem, text))
                    log("FAIL [%s] %s\n    %s" % (kind, problem, text[:2000]))
        except KeyboardInterrupt:
            stopped = True
            pool.shutdown(wait=False, cancel_futures=True)
    if own_work:
        shutil.rmtree(args.work, ignore_errors=True)
    log("fuzz_cases: %d inputs (seed %d)%s: %s" %
        (done, args.seed, " (stopped before the other %d)" % (args.count - done) if stopped else "",
         ", ".join("%s %d" % kv for kv in sorted(counts.items()))))
    log("fuzz_cases: %d failures" % len(failures))
    return 1 if failures else 2 if stopped else 0


if __name__ == "__main__":
    sys.exit(main())
