"""Mutated input files for scripts/fuzz_cases.py: the CSV and HDF5 tables and the snapshot
files (a previous run's results.h5) a scene reads with initial.type = "table" or "snapshot",
and the files granvv reads back from itself: a particle run's checkpoint (its member files,
inputs.json and case.toml, resumed with `granvv resume`) and an atlas's cache entries
(runs/*.json, read again by the same `granvv atlas`).

Each mutation starts from a valid file and breaks one or two things a user's file can have
wrong: shapes (missing, empty, short, 2D or scalar columns), dtypes (integers, float32,
strings), sizes (a chunked dataset declaring 2^40 rows in a small file, truncated files),
values (NaN, inf, 1e308, n or T <= 0, x out of order or outside the period), encodings (a
UTF-8 byte-order mark, UTF-16, non-UTF-8 bytes, CRLF line ends), and columns (missing,
repeated, unknown, a v_y column).
"""
import io
import math
import os
import tempfile

import h5py
import numpy as np

VALUES = [float("nan"), float("inf"), -float("inf"), 0.0, -1.0, 1e308, -1e308, 5e-324, 1e-300]


def base_table(rng):
    rows = rng.choice([4, 5, 8, 13, 32, 100])
    x = np.arange(rows) / rows - 0.5
    if rng.random() < 0.3:  # irregular rows
        x = np.sort(rng.sample(range(1000), rows))
        x = np.array(x) / 1000.0 - 0.5
    amplitude = rng.choice([0.0, 0.05, 0.3, 0.9])
    n = 1.0 + amplitude * np.cos(2 * np.pi * x)
    cols = {"x": x, "n": n, "v_x": 0.1 * np.sin(2 * np.pi * x),
            "T": 1.0 + 0.1 * np.sin(2 * np.pi * x) ** 2}
    if rng.random() < 0.2:
        cols["v_y"] = 0.01 * np.cos(2 * np.pi * x)
    return cols


def mutate_columns(rng, cols):
    """Values and shapes broken in place (a dict of 1D arrays, some maybe replaced)."""
    for _ in range(rng.choice([0, 1, 1, 2])):
        name = rng.choice(list(cols))
        c = np.array(cols[name], dtype=float)
        kind = rng.randrange(7)
        if kind == 0 and c.size:
            c[rng.randrange(c.size)] = rng.choice(VALUES)
        elif kind == 1:
            c = c[: rng.randrange(c.size + 1)]
        elif kind == 2:
            del cols[name]
            continue
        elif kind == 3 and c.size > 1:
            i = rng.randrange(c.size - 1)
            c[i], c[i + 1] = c[i + 1], c[i]
        elif kind == 4:
            c = c * rng.choice([-1.0, 0.0, 2.0, 1e12])
        elif kind == 5:
            c = np.append(c, c[-1:] if c.size else [0.0])
        else:
            c = c + rng.choice([1.0, -0.5, 1e-15])
        cols[name] = c
    return cols


def csv_bytes(rng, cols):
    names = list(cols)
    if rng.random() < 0.1:
        names.append(rng.choice(["x", "v_z", "rho", "", "n "]))
    rng.shuffle(names)
    rows = max((len(cols.get(n, [])) for n in names), default=0)
    lines = [",".join(names)]
    for i in range(rows):
        cells = []
        for n in names:
            c = cols.get(n, [])
            cells.append(repr(float(c[i])) if i < len(c) else "")
        lines.append(",".join(cells))
    if rng.random() < 0.1:
        lines.insert(rng.randrange(len(lines) + 1), rng.choice(["# a comment", "", " , ,", "x"]))
    end = "\r\n" if rng.random() < 0.2 else "\n"
    text = end.join(lines) + end
    kind = rng.random()
    if kind < 0.2:
        data = b"\xef\xbb\xbf" + text.encode()
    elif kind < 0.25:
        data = text.encode("utf-16")
    elif kind < 0.3:
        data = text.encode()
        i = rng.randrange(len(data) + 1)
        data = data[:i] + rng.choice([b"\xff", b"\xc3\x28", b"\x00", b"\xe9"]) + data[i:]
    elif kind < 0.35:
        data = text.encode()[: rng.randrange(len(text) + 1)]
    elif kind < 0.37:
        data = b"x,n,v_x,T\n" + b"1" * 300000 + b"\n"
    else:
        data = text.encode()
    return data


def h5_bytes(build):
    """The bytes of an HDF5 file written by build(h5py.File)."""
    fd, path = tempfile.mkstemp(suffix=".h5")
    os.close(fd)
    try:
        with h5py.File(path, "w") as f:
            build(f)
        with open(path, "rb") as f:
            return f.read()
    finally:
        os.unlink(path)


def write_column(rng, group, name, c):
    kind = rng.random()
    if kind < 0.05:
        group.create_dataset(name, shape=(2**40,), chunks=(1024,), dtype="f8")
    elif kind < 0.1:
        group[name] = np.array([b"a"] * max(len(c), 1))
    elif kind < 0.15:
        group[name] = np.asarray(c).astype(rng.choice(["f4", "i4", "i8", "u1"]), copy=False)
    elif kind < 0.2:
        group[name] = np.tile(np.asarray(c), (2, 1))
    elif kind < 0.23:
        group[name] = float(c[0]) if len(c) else 0.0
    elif kind < 0.25:
        group.create_dataset(name, shape=(0,), dtype="f8")
    else:
        group[name] = np.asarray(c, dtype=float)


def damaged(rng, data):
    """Bytes flipped or cut off at the end, sometimes."""
    kind = rng.random()
    data = bytearray(data)
    if kind < 0.08:
        return bytes(data[: rng.randrange(len(data) + 1)])
    if kind < 0.16:
        for _ in range(rng.randint(1, 20)):
            data[rng.randrange(len(data))] = rng.randrange(256)
    return bytes(data)


def table_h5_bytes(rng, cols):
    group_name = rng.choice(["/", "/", "/", "/profiles"])

    def build(f):
        g = f if group_name == "/" else f.create_group(group_name)
        for name, c in cols.items():
            write_column(rng, g, name, c)
    return damaged(rng, h5_bytes(build)), group_name


def edited_h5(rng, base, edit):
    """The bytes of HDF5 file `base` after edit(h5py.File) (and maybe damaged())."""
    fd, path = tempfile.mkstemp(suffix=".h5")
    os.close(fd)
    try:
        with open(path, "wb") as f:
            f.write(base)
        with h5py.File(path, "a") as f:
            edit(f)
        with open(path, "rb") as f:
            return damaged(rng, f.read())
    finally:
        os.unlink(path)


def snapshot_bytes(rng, base):
    """A previous run's results.h5 (bytes `base`) with its /hydro/fields broken."""
    def edit(f):
        g = f["hydro/fields"]
        for _ in range(rng.choice([0, 1, 1, 2])):
            name = rng.choice(["x", "n", "v_x", "v_y", "T", "t", "label", "n_stderr"])
            if name not in g or g[name].size > 10**6:  # absent, or declared huge before
                continue
            old = g[name][()]
            del g[name]
            kind = rng.randrange(8)
            if kind == 0:
                continue  # missing
            if name == "label" or old.dtype.kind in "OS":
                g[name] = np.array([b"x"] * rng.randrange(4))
                continue
            a = np.array(old, dtype=float)
            if kind == 1 and a.ndim == 2:
                a = a[:, : rng.randrange(a.shape[1] + 1)]
            elif kind == 2 and a.size:
                a.flat[rng.randrange(a.size)] = rng.choice(VALUES)
            elif kind == 3:
                a = a.reshape(-1)
            elif kind == 4:
                g.create_dataset(name, shape=(2**20, 2**20), chunks=(64, 64), dtype="f8")
                continue
            elif kind == 5:
                g[name] = np.array([b"s"] * max(a.shape[0] if a.ndim else 1, 1))
                continue
            elif kind == 6:
                a = a * rng.choice([-1.0, 0.0, 1e300])
            g[name] = a
        if rng.random() < 0.05 and "geometry" in g.attrs:
            del g.attrs["geometry"]
    return edited_h5(rng, base, edit)


def make_base_snapshot(granvv, work, env, run):
    """A small hydro run's results.h5 with snapshots at t = 0.25 and 0.5 (bytes)."""
    out = os.path.join(work, "base-snapshot")
    code, _, err, _ = run([granvv, "run", "single_mode", "--set", "hydro.cells=32", "--set",
                           "convergence.cells=[]", "--set", "hydro.t_end=0.5", "--set",
                           "hydro.output_times=[0.25, 0.5]", "--quiet", "--no-report",
                           "--out", out], 120, work, env)
    if code != 0:
        raise RuntimeError("the base snapshot run failed: %r" % err[-300:])
    with open(os.path.join(out, "results.h5"), "rb") as f:
        return f.read()


def make_file_input(rng, base_snapshot):
    """(scene, files {name: bytes}, --set list) for one mutated file."""
    kind = rng.random()
    if kind < 0.4:
        name = "table.csv"
        files = {name: csv_bytes(rng, mutate_columns(rng, base_table(rng)))}
        sets = ['initial.type="table"', 'initial.from="%s"' % name]
        scene = "haff"
    elif kind < 0.7:
        name = "table.h5"
        data, group = table_h5_bytes(rng, mutate_columns(rng, base_table(rng)))
        files = {name: data}
        sets = ['initial.type="table"', 'initial.from="%s"' % name, 'initial.dataset="%s"' % group]
        scene = "haff"
    else:
        name = "snapshot.h5"
        files = {name: snapshot_bytes(rng, base_snapshot)}
        sets = ['initial.type="snapshot"', 'initial.from="%s"' % name,
                "initial.time=%s" % rng.choice(["0.25", "0.5", "0.0", "0.3"])]
        scene = "single_mode"
    if rng.random() < 0.3:
        sets.append("initial.interpolation=%s" % rng.choice(['"linear"', '"cubic"']))
    if rng.random() < 0.15:
        sets.append("hydro.transverse_velocity=true")
    return scene, files, sets


# Checkpoints and atlas cache entries: the files granvv itself wrote and reads back, edited or
# damaged as a user or a crash could leave them. A resume of a damaged checkpoint is refused
# with one line (exit 2) or runs with finite results; an atlas whose cache entry is damaged runs
# that setting again.

CHECKPOINT_CASE = ["md_haff", "--set", "md.engine=event_driven", "--set", "md.particles=400",
                   "--set", "md.box_width=80", "--set", "md.ensemble=2", "--set", "md.bins=8",
                   "--set", "md.sample_interval=1.0", "--set", "md.t_end=400",
                   "--set", "md.output_times=[0.0,2.0,400.0]", "--set", "md.snapshot_interval=0",
                   "--set", "md.checkpoint_interval=1e-6", "--set", "compare.enabled=false",
                   "--set", "hydro.cells=32", "--set", "convergence.cells=[]"]
ATLAS_ARGS = ["haff", "--budget", "1", "--jobs", "1", "--quiet", "--no-report"]


def make_base_checkpoint(granvv, work, env):
    """The checkpoint folder of a particle run stopped while its second member runs: {relative
    path: bytes} (member_0.h5 finished, member_1.h5 in progress, case.toml, inputs.json)."""
    import signal
    import subprocess
    import time
    out = os.path.join(work, "base-checkpoint")
    folder = os.path.join(out, ".granvv-checkpoint")
    p = subprocess.Popen([granvv, "run"] + CHECKPOINT_CASE + ["--quiet", "--no-report", "--out", out],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=work, env=env)
    end = time.monotonic() + 120
    while time.monotonic() < end and p.poll() is None:
        if os.path.exists(os.path.join(folder, "member_1.h5")):
            break
        time.sleep(0.002)
    p.send_signal(signal.SIGSTOP)  # its files are whole (each replaced by a rename)
    try:
        files = {}
        for name in sorted(os.listdir(folder)):
            if name.endswith(".partial"):  # a save in progress
                continue
            with open(os.path.join(folder, name), "rb") as f:
                files[name] = f.read()
    finally:
        p.kill()
        p.wait()
    if "member_1.h5" not in files:
        raise RuntimeError("the base checkpoint run ended before its second member saved")
    return files


def _decoded(names):
    return [n.decode() if isinstance(n, bytes) else str(n) for n in names]


def _mutate_dataset(rng, group, name):
    """One dataset of group replaced by a broken one (values, shape, dtype, size), or removed."""
    old = group[name][()]
    del group[name]
    kind = rng.randrange(9)
    if kind == 0:
        return  # missing
    if getattr(old, "dtype", None) is not None and old.dtype.kind in "OSU":
        group[name] = np.array([b"x"] * rng.randrange(4)) if rng.random() < 0.5 else np.arange(3.0)
        return
    a = np.array(old, dtype=float)
    if kind == 1 and a.ndim >= 1:
        a = a[..., : rng.randrange(a.shape[-1] + 1)] if a.ndim == 2 else a[: rng.randrange(a.size + 1)]
    elif kind == 2 and a.size:
        for _ in range(rng.randint(1, 3)):
            a.flat[rng.randrange(a.size)] = rng.choice(VALUES + [-2.0, 1e9, 0.5, 3.0])
    elif kind == 3:
        a = np.concatenate([a.reshape(-1), a.reshape(-1)[:1]]) if a.size else np.zeros(1)
    elif kind == 4:
        group.create_dataset(name, shape=(2**40,), chunks=(1024,), dtype="f8")
        return
    elif kind == 5:
        group[name] = a.astype(rng.choice(["f4", "i4", "u1", "i8"]))
        return
    elif kind == 6:
        a = np.tile(a.reshape(-1), (2, 1))
    elif kind == 7:
        a = a * rng.choice([-1.0, 0.0, 1e300, 2.0])
    group[name] = a


def _mutate_attribute(rng, obj, name):
    kind = rng.randrange(5)
    if kind == 0:
        del obj.attrs[name]
    elif kind == 1:
        obj.attrs[name] = rng.choice(VALUES + [-3.0, 2.5, 1e9, 2.0**63, 7.0])
    elif kind == 2:
        obj.attrs[name] = "text"
    elif kind == 3:
        obj.attrs[name] = np.arange(rng.randint(0, 5), dtype=float)
    else:
        obj.attrs[name] = np.int64(rng.choice([0, 1, 2, -1, 2**62]))


def checkpoint_member_bytes(rng, base):
    """A member file of the base checkpoint (bytes) with one to three things broken."""
    def edit(f):
        datasets = []
        f.visititems(lambda n, o: datasets.append(n) if isinstance(o, h5py.Dataset) else None)
        for _ in range(rng.choice([1, 1, 2, 3])):
            where = rng.random()
            if where < 0.3:
                names = list(f.attrs)
                if names:
                    _mutate_attribute(rng, f, rng.choice(names))
            elif where < 0.4 and "engine" in f:
                # An engine number out of range or not finite, by name.
                g = f["engine"]
                names, values = _decoded(g["names"][()]), np.array(g["values"][()], dtype=float)
                if names:
                    values[rng.randrange(len(names))] = rng.choice(VALUES + [-1.0, 1e9, 0.5])
                    del g["values"]
                    g["values"] = values
            elif where < 0.55 and "engine/arrays" in f:
                g = f["engine/arrays"]
                name = rng.choice(list(g))
                if rng.random() < 0.5:
                    a = np.array(g[name][()], dtype=float)
                    if a.size:
                        i = rng.randrange(a.size)
                        a[i] = rng.choice([a[(i + 1) % a.size], -1.0, 1e9, float("nan"),
                                           float("inf"), a[i] + 0.5, 2.0**32])
                    del g[name]
                    g[name] = a
                else:
                    _mutate_dataset(rng, g, name)
            else:
                live = [n for n in datasets if n in f and f[n].size <= 10**6]
                if live:
                    name = rng.choice(live)
                    parent, _, leaf = name.rpartition("/")
                    _mutate_dataset(rng, f[parent] if parent else f, leaf)
    return edited_h5(rng, base, edit)


def checkpoint_inputs_bytes(rng, base):
    """inputs.json edited: a key's value, a file entry, a fingerprint, or not JSON at all."""
    import json
    kind = rng.random()
    if kind < 0.15:
        return damaged(rng, base) if rng.random() < 0.5 else base[: rng.randrange(len(base) + 1)]
    j = json.loads(base)
    if kind < 0.45 and isinstance(j.get("case"), dict) and j["case"]:
        key = rng.choice(list(j["case"]))
        j["case"][key] = rng.choice(["0.5", "nan", "", "[]", 7, None, "\"x\""])
    elif kind < 0.6:
        j["files"] = rng.choice([[{"path": "/nonexistent", "sha256": "0" * 64}], "x", None, [1]])
    elif kind < 0.75:
        j["case_sha256"] = rng.choice(["", "0" * 64, 5, None])
    elif kind < 0.9 and isinstance(j, dict) and j:
        del j[rng.choice(list(j))]
    else:
        j = rng.choice([[], "text", 1, None, {}])
    return json.dumps(j).encode()


def checkpoint_case_bytes(rng, base):
    """case.toml edited: a value changed, a line removed, or its bytes damaged."""
    text = base.decode()
    lines = text.split("\n")
    kind = rng.random()
    if kind < 0.4:
        i = rng.randrange(len(lines))
        if "=" in lines[i]:
            key = lines[i].split("=")[0]
            lines[i] = key + "= " + rng.choice(["0.5", "nan", "1e300", '"x"', "[]", "-1", "true"])
        return "\n".join(lines).encode()
    if kind < 0.7:
        del lines[rng.randrange(len(lines))]
        return "\n".join(lines).encode()
    return damaged(rng, base) if rng.random() < 0.7 else b"\xff\xfe" + base


def make_checkpoint_input(rng, base_checkpoint):
    """(files {relative path: bytes}, command) for a resume of a damaged checkpoint."""
    files = {"out/.granvv-checkpoint/" + n: d for n, d in base_checkpoint.items()}
    target = rng.random()
    if target < 0.7:
        member = rng.choice([n for n in base_checkpoint if n.startswith("member_")])
        files["out/.granvv-checkpoint/" + member] = checkpoint_member_bytes(rng, base_checkpoint[member])
    elif target < 0.85:
        files["out/.granvv-checkpoint/inputs.json"] = checkpoint_inputs_bytes(
            rng, base_checkpoint["inputs.json"])
    else:
        files["out/.granvv-checkpoint/case.toml"] = checkpoint_case_bytes(
            rng, base_checkpoint["case.toml"])
    members = sorted(n for n in files if "/member_" in n)
    if members and rng.random() < 0.05:  # a member's file gone (of those the base run left)
        del files[rng.choice(members)]
    return files, ["resume", "out", "--quiet", "--no-report"]


def make_base_atlas(granvv, work, env, run):
    """The cache entries of a small atlas: {relative path: bytes} of its runs/*.json."""
    out = os.path.join(work, "base-atlas")
    code, _, err, _ = run([granvv, "atlas"] + ATLAS_ARGS + ["--out", out], 600, work, env)
    if code != 0:
        raise RuntimeError("the base atlas failed: %r" % err[-300:])
    runs = os.path.join(out, "runs")
    files = {}
    for name in sorted(os.listdir(runs)):
        with open(os.path.join(runs, name), "rb") as f:
            files["atlas/runs/" + name] = f.read()
    if not files:
        raise RuntimeError("the base atlas cached no runs")
    return files


def _edit_json(rng, value, depth=0):
    """One value somewhere inside a JSON value replaced by a hostile one."""
    hostile = [None, "", "x", [], {}, -1, 0, 1e308, -1e308, 2**63, 3.5, True, [1e308], [None],
               ["a"], {"a": 1}]
    if isinstance(value, dict) and value and depth < 4:
        key = rng.choice(list(value))
        if rng.random() < 0.15:
            del value[key]
        else:
            value[key] = _edit_json(rng, value[key], depth + 1)
        return value
    if isinstance(value, list) and value and depth < 4:
        i = rng.randrange(len(value))
        kind = rng.random()
        if kind < 0.2:
            return value[:i]
        if kind < 0.3:
            return value + value[-1:]
        value[i] = _edit_json(rng, value[i], depth + 1)
        return value
    return rng.choice(hostile)


def atlas_entry_bytes(rng, base):
    import json
    kind = rng.random()
    if kind < 0.15:
        return damaged(rng, base) if rng.random() < 0.5 else base[: rng.randrange(len(base) + 1)]
    j = json.loads(base)
    if kind < 0.3:
        j[rng.choice(["times", "thermal", "flow"])] = rng.choice([[], [0.0], [1e308], None, "x"])
    elif kind < 0.4 and isinstance(j.get("inputs"), dict):
        j["inputs"]["case_sha256"] = "0" * 64
    elif kind < 0.45:
        return json.dumps(j).replace("0.", "NaN", 1).encode()  # not JSON
    else:
        for _ in range(rng.choice([1, 1, 2, 3])):
            j = _edit_json(rng, j)
    return json.dumps(j).encode()


def make_atlas_input(rng, base_atlas):
    files = dict(base_atlas)
    for _ in range(rng.choice([1, 1, 1, 2])):
        name = rng.choice(list(base_atlas))
        files[name] = atlas_entry_bytes(rng, files[name])
    return files, ["atlas"] + ATLAS_ARGS + ["--out", "atlas"]
