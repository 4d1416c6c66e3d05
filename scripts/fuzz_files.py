"""Mutated input files for scripts/fuzz_cases.py: the CSV and HDF5 tables and the snapshot
files (a previous run's results.h5) a scene reads with initial.type = "table" or "snapshot".

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


def snapshot_bytes(rng, base):
    """A previous run's results.h5 (bytes `base`) with its /hydro/fields broken."""
    fd, path = tempfile.mkstemp(suffix=".h5")
    os.close(fd)
    try:
        with open(path, "wb") as f:
            f.write(base)
        with h5py.File(path, "a") as f:
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
        with open(path, "rb") as f:
            return damaged(rng, f.read())
    finally:
        os.unlink(path)


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
