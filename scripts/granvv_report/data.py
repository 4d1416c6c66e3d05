"""Data access of the report: the only module that opens results.h5, summary.json and sweep.json,
and names their groups and blocks (docs/outputs.md).

A figure gets a Run (one output folder) or a SweepRun (a sweep folder). Run holds the HDF5 groups
by meaning (run.hydro_ts is /hydro/timeseries, run.compare is /compare with its subgroups) as
{"data": {name: array}, "attrs": {name: value}} and reads summary.json through one accessor per
block (run.hydro_summary("energy_drift") is summary.json's hydro.energy_drift). The leaf names of
datasets and keys are written in the figure that draws them, so that a new figure whose data exist
is a change to its own file only.
"""
import json
import math
import tomllib
import urllib.parse
import warnings
from pathlib import Path

import h5py
import numpy as np

RESULTS, SUMMARY, SWEEP, ATLAS = "results.h5", "summary.json", "sweep.json", "atlas.json"

# The hydrodynamic fields, in the order of the C++ FieldSeries columns (fields/field_series.cpp,
# hydrodynamic_fields()): the fields the hydro and the particles both carry (v_y where the model has
# transverse flow) and a side-by-side comparison weighs. Which of them a comparison holds is read from
# /compare/fields (compared_fields).
HYDRODYNAMIC_FIELDS = ("n", "v_x", "v_y", "T")

# Two times read from the outputs are the same time within this, relative to max(1, |t|): the C++
# comparison's kSameTimeTolerance (fields/field_series.hpp). The files write times exactly, so a time
# of results.h5 equals its copy in summary.json.
SAME_TIME = 1e-9


class ReportError(Exception):
    """Fatal: the report cannot be built at all."""


class Skip(Exception):
    """A figure whose data are absent or uninformative for this scene."""


def _decode(v):
    if isinstance(v, bytes):
        return v.decode("utf-8", "replace")
    if isinstance(v, np.ndarray):
        if v.dtype.kind in "SO":
            return [_decode(x) for x in v.tolist()]
        return v
    if isinstance(v, np.generic):
        return v.item()
    return v


def _read_dataset(ds):
    if ds.dtype.kind in "SO" or h5py.check_string_dtype(ds.dtype) is not None:
        try:
            return np.array(ds.asstr()[()], dtype=object)
        except (TypeError, ValueError):
            return np.array([_decode(x) for x in np.atleast_1d(ds[()])], dtype=object)
    return np.asarray(ds[()], dtype=float) if ds.dtype.kind in "iufb" else ds[()]


def _read_group(f, path):
    """{'data': {name: array}, 'attrs': {name: value}} or None if absent."""
    if path not in f or not isinstance(f[path], h5py.Group):
        return None
    g = f[path]
    data = {}
    for name, obj in g.items():
        if isinstance(obj, h5py.Dataset):
            data[name] = _read_dataset(obj)
    return {"data": data, "attrs": {k: _decode(v) for k, v in g.attrs.items()}}


def _read_transport(f, path):
    """A /transport/<name> group; a pair's (two coefficients fitted jointly) also holds one
    subgroup per fitted signal, under 'signals' ({"<field>:<phase>": group})."""
    G = _read_group(f, path)
    if G is not None:
        G["signals"] = {name: _read_group(f, f"{path}/{name}") for name, obj in f[path].items()
                        if isinstance(obj, h5py.Group)}
    return G


def _read_compare(f, root="compare"):
    """The /compare group of a side-by-side run: attrs, t, x, collision_clock, and its subgroups
    (fields/<name>, peak, energy, inertia, modes, pressure), or None when the run compared nothing.
    With compare.closures, closures[<name>] holds the same for each closure (/compare/closures/<name>)."""
    top = _read_group(f, root)
    if top is None:
        return None
    out = {"attrs": top["attrs"], "data": top["data"], "fields": {}, "closures": {}}
    if f"{root}/fields" in f and isinstance(f[f"{root}/fields"], h5py.Group):
        for name in f[f"{root}/fields"]:
            g = _read_group(f, f"{root}/fields/{name}")
            if g is not None:
                out["fields"][name] = g
    for sub in ("peak", "energy", "inertia", "modes", "pressure"):
        out[sub] = _read_group(f, f"{root}/{sub}")
    if out["pressure"] is not None and f"{root}/pressure/closures" in f:
        out["pressure"]["closures"] = {name: _read_group(f, f"{root}/pressure/closures/{name}")
                                       for name in f[f"{root}/pressure/closures"]}
    if root == "compare" and "compare/closures" in f and isinstance(f["compare/closures"], h5py.Group):
        for name in f["compare/closures"]:
            out["closures"][name] = _read_compare(f, f"compare/closures/{name}")
    return out


# The groups of results.h5 a report reads (docs/outputs.md), by the attribute name of Run.
GROUPS = {"hydro_ts": "hydro/timeseries", "hydro_fields": "hydro/fields", "hydro_lagrangian": "hydro/lagrangian",
          "hydro_theory": "hydro/theory", "hydro_convergence": "hydro/convergence", "md_group": "md",
          "md_ts": "md/timeseries", "md_fields": "md/fields"}


def load_results(path):
    try:
        with h5py.File(path, "r") as f:
            res = {"attrs": {k: _decode(v) for k, v in f.attrs.items()}}
            for key, p in GROUPS.items():
                res[key] = _read_group(f, p)
            res["compare"] = _read_compare(f)
            res["transport"] = {name: _read_transport(f, f"transport/{name}")
                                for name in (f["transport"] if "transport" in f else [])}
            res["groups"] = []
            f.visit(lambda name: res["groups"].append(name) if isinstance(f[name], h5py.Group) else None)
            return res
    except FileNotFoundError:
        raise ReportError(f"{path} not found")
    except (OSError, KeyError, RuntimeError, ValueError, TypeError) as e:
        # h5py reports a damaged file body as any of these, from the first object it cannot read.
        first = (str(e).splitlines() or [type(e).__name__])[0].strip("'\"")
        raise ReportError(f"cannot read {path}, the file is damaged: {first}")


def load_summary(path, warnings):
    if not path.exists():
        warnings.append(f"{path.name} not found: headline numbers are missing from this page.")
        return {}
    try:
        with open(path) as fh:
            s = json.load(fh)
        if not isinstance(s, dict):
            raise ValueError("top level is not an object")
        return s
    except (OSError, ValueError) as e:
        warnings.append(f"{path.name} unreadable ({e}): headline numbers are missing from this page.")
        return {}


def get(d, *keys):
    """Nested lookup that tolerates None/absent levels: get(s, 'hydro', 'tau_fit_window', 't_min')."""
    for k in keys:
        if not isinstance(d, dict) or k not in d:
            return None
        d = d[k]
    return d


def num(x):
    """A finite float, or None."""
    try:
        v = float(x)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


def arr(group, name, min_len=1):
    """A finite-valued float array from a group, or None."""
    if group is None:
        return None
    a = group["data"].get(name)
    if a is None or not isinstance(a, np.ndarray) or a.dtype == object or a.size < min_len:
        return None
    return np.asarray(a, dtype=float)


def snapshot_labels(fields, ns):
    lab = fields["data"].get("label") if fields else None
    if lab is None or len(lab) != ns:
        return ["output"] * ns
    return [str(x) for x in lab]


def same_time(t, reference):
    """Whether t is the time reference (SAME_TIME)."""
    return abs(t - reference) <= SAME_TIME * max(1.0, abs(reference))


def find_snapshot_summary(run, t):
    """The summary.json snapshot record at time t (same_time)."""
    best = None
    for rec in run.hydro_summary("snapshots") or []:
        tr = num(get(rec, "t"))
        if tr is not None and same_time(tr, t):
            best = rec
    return best


def haff_temperature(t, t0, T0=1.0):
    """Haff's law T0 (1 + t/t0)^-2 (hydro/haff.hpp), for a t0 read from the outputs: the one place the
    report evaluates it (the C++ writes the curve at its own samples: /hydro/timeseries haff_T,
    /md/timeseries haff_theory)."""
    return T0 * (1 + t / t0) ** -2.0


def hydro_t0(run):
    """(t0, origin): the hydro's Haff time in scaled units (/hydro/theory), or None, and where it came
    from, for a label: the closure the hydro ran with, and its cooling rate and cooling factor where
    they are not the paper's ("dilute closure", "enskog closure, exact cooling"). Only the dilute
    closure with the paper's cooling has t0 = K/4q."""
    a = run.hydro_theory["attrs"] if run.hydro_theory else {}
    closure = a.get("closure") or run.hydro_summary("closure")
    cooling = a.get("cooling") or run.hydro_summary("cooling")
    factor = num(run.hydro_summary("transport_factors", "cooling"))
    origin = f"{closure} closure" if closure else "closure"
    if cooling and cooling != "small_q":
        origin += f", {cooling} cooling"
    if factor is not None and factor != 1.0:
        origin += f", cooling factor {factor:g}"
    return num(a.get("t0")), origin


def md_value(run, key):
    """A number of the particle engine: summary.json's md block first, else the /md attribute."""
    v = num(run.md_summary(key))
    if v is None and run.md_group:
        v = num(run.md_group["attrs"].get(key))
    return v


def md_config(run, key):
    """A resolved md.* configuration value as a plain string/number (TOML quotes removed)."""
    v = run.config("md." + key)
    return v.strip().strip('"') if isinstance(v, str) else v


def md_members(G, name, size):
    """[members x size] float array of /md/timeseries (a 1-D dataset is one member), or None."""
    a = arr(G, name)
    if a is None:
        return None
    if a.ndim == 1:
        a = a[None, :]
    if a.ndim != 2 or a.shape[1] != size or a.shape[0] < 1:
        return None
    return a


def md_series(G, name, size):
    """A 1-D float array of length size from /md/timeseries, or None (also when all NaN)."""
    a = arr(G, name)
    if a is None or a.ndim != 1 or a.size != size or not np.isfinite(a).any():
        return None
    return a


def md_timeseries(run, at_least_two=False):
    """(G, t) of /md/timeseries, or Skip with the reason (naming the MD error if the run failed)."""
    G = run.md_ts
    t = arr(G, "t", 1)
    if t is None or t.ndim != 1:
        err = run.md_summary("error")
        if err:
            raise Skip(f"the particle run failed before writing its time series: {err}")
        raise Skip("no /md/timeseries in results.h5 (no particle run in this scene)")
    if at_least_two and t.size < 2:
        raise Skip("the particle time series has fewer than two samples")
    return G, t


def nanmean_rows(a):
    """Mean over ensemble members, NaN (without a warning) where no member has a value."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return np.nanmean(a, axis=0)


def cmp_data(run):
    """(C, t, x) of /compare, or Skip."""
    C = run.compare
    if C is None:
        raise Skip("no /compare group in results.h5 (the scene does not compare hydro and particles)")
    t, x = arr(C, "t", 1), arr(C, "x", 2)
    if t is None or x is None or t.ndim != 1 or x.ndim != 1:
        raise Skip("/compare has no common output time (t) or no bins (x)")
    return C, t, x


def cmp_box(run):
    """Lx in sigma (MD time = scaled t * Lx), or None."""
    C = run.compare
    v = num(C["attrs"].get("box_length")) if C else None
    return v if v is not None else md_value(run, "box_length")


def compared_fields(C):
    """The fields a comparison (/compare, or one closure's) holds, in HYDRODYNAMIC_FIELDS order."""
    return [f for f in HYDRODYNAMIC_FIELDS if f in C["fields"]]


def cmp_rows(g, name, shape):
    """A [times x bins] array of a /compare subgroup with the given shape, or None."""
    a = arr(g, name, 1)
    return a if a is not None and a.shape == shape else None


def cmp_vec(g, name, size):
    a = arr(g, name, 1)
    return a if a is not None and a.ndim == 1 and a.size == size and np.isfinite(a).any() else None


def cmp_pressure(run):
    """/compare/pressure (the particles' pressure against the hydro closure's p(n, T), MD units), or Skip."""
    C = run.compare
    P = C.get("pressure") if C else None
    if P is None:
        raise Skip("no /compare/pressure (no comparison, or an engine without a contact virial)")
    return P


def cmp_window(C):
    """(window end or None, left_at or None, first field to leave or '')."""
    a = C["attrs"]
    first = a.get("first_field_to_leave")
    return num(a.get("agreement_window")), num(a.get("left_at")), first if isinstance(first, str) else ""


def compare_hydro_T(run):
    """(t_MD, <T>) of the hydro of a comparison (its Haff curve in MD time), or None."""
    if run.compare is None:
        return None
    ts = run.hydro_ts
    t, T = arr(ts, "t", 2), arr(ts, "T_mean", 2)
    L = cmp_box(run)
    if t is None or T is None or T.size != t.size or not L:
        return None
    return t * L, T


def load_sweep(path):
    try:
        with open(path) as fh:
            sw = json.load(fh)
    except (OSError, ValueError) as e:
        raise ReportError(f"cannot read {path}: {e}")
    if not isinstance(sw, dict) or not isinstance(sw.get("points"), list):
        raise ReportError(f"{path} is not a granvv sweep (no points list)")
    return sw


def sweep_points(run):
    """One record per point: value, dir, status, md block, cooling row (or None), report link."""
    rows = {}
    cool = run.cooling("points") or []
    for c in cool:
        i = c.get("point") if isinstance(c, dict) else None
        if isinstance(i, int):
            rows[i] = c
    out = []
    for i, p in enumerate(run.sweep("points")):
        p = p if isinstance(p, dict) else {}
        d = p.get("dir")
        link = None
        if isinstance(d, str) and d and (run.outdir / d / "report.html").is_file():
            link = urllib.parse.quote(f"{d}/report.html", safe="/=,.-_")
        out.append({"i": i, "value": num(p.get("value")), "dir": d, "status": p.get("status"),
                    "exit_code": p.get("exit_code"), "md": p.get("md") if isinstance(p.get("md"), dict) else {},
                    "cool": rows.get(i), "link": link, "hydro_wall": num(p.get("hydro_wall_seconds")),
                    "transport": p.get("transport") if isinstance(p.get("transport"), dict) else {}})
    return out


def sweep_cooling(run):
    """Arrays over the points with a cooling row, sorted by r; Skip if fewer than one."""
    pts = [p for p in sweep_points(run) if p["cool"]]
    if not pts:
        err = run.sweep("cooling_error")
        raise Skip("no point measured a Haff time (cooling analysis absent)" + (f": {err}" if err else ""))
    pts.sort(key=lambda p: num(p["cool"].get("restitution")) or 0.0)

    def col(key, src="cool"):
        return np.array([num(p[src].get(key)) if num(p[src].get(key)) is not None else np.nan for p in pts])

    d = {k: col(k) for k in ("restitution", "t0", "t0_error", "zeta", "zeta_error", "zeta_enskog", "zeta_dilute",
                             "zeta_paper", "zeta_paper_enskog", "deviation_enskog", "deviation_enskog_sigmas",
                             "paper_deviation", "paper_deviation_sigmas")}
    for k in ("haff_t0_theory", "haff_t0_theory_dilute", "haff_t0_paper", "area_fraction", "restitution_measured"):
        d[k] = col(k, "md")
    d["value"] = np.array([p["value"] if p["value"] is not None else np.nan for p in pts])
    d["points"] = pts
    return d



# The coefficients of summary.json's "transport" block, in the order a page shows them: each is
# {"measured", "error", "closures": {closure: value}}, divided by the elastic dilute hard-disk value.
TRANSPORT_COEFFICIENTS = ("shear_viscosity", "effective_conductivity", "conductivity", "mu")


def sweep_transport(run):
    """The points' transport blocks, coefficient by coefficient, over the points sorted by r (else
    by the swept value): {"restitution", "value", "points", "coefficients": {name: {"measured",
    "error", "closures": {closure: array}}}}, NaN where a point lacks a number. Skip if no point
    measured a coefficient."""
    pts = [p for p in sweep_points(run)
           if any(isinstance(p["transport"].get(c), dict) for c in TRANSPORT_COEFFICIENTS)]
    if not pts:
        raise Skip("no point measured a transport coefficient (no transport block in its summary.json)")
    pts.sort(key=lambda p: (num(p["md"].get("restitution")) or p["value"] or 0.0))

    def column(values):
        return np.array([v if v is not None else np.nan for v in values], dtype=float)

    coefficients = {}
    for c in TRANSPORT_COEFFICIENTS:
        blocks = [p["transport"].get(c) if isinstance(p["transport"].get(c), dict) else {} for p in pts]
        if not any(blocks):
            continue
        names = sorted({n for b in blocks if isinstance(b.get("closures"), dict) for n in b["closures"]})
        coefficients[c] = {
            "measured": column([num(b.get("measured")) for b in blocks]),
            "error": column([num(b.get("error")) for b in blocks]),
            "closures": {n: column([num(get(b, "closures", n)) for b in blocks]) for n in names}}
    return {"restitution": column([num(p["md"].get("restitution")) for p in pts]),
            "value": column([p["value"] for p in pts]), "points": pts, "coefficients": coefficients}


class Run:
    """One output folder of `granvv run`: results.h5 (required), summary.json (optional) and the
    resolved case configuration stored in results.h5. figdir is set by the page."""

    def __init__(self, outdir):
        self.outdir = Path(outdir)
        self.results_path = self.outdir / RESULTS
        if not self.results_path.is_file():
            raise ReportError(f"{self.results_path} not found" if not self.results_path.exists()
                              else f"{self.results_path} is not a file")
        res = load_results(self.results_path)
        self.warnings = []
        self.summary = load_summary(self.outdir / SUMMARY, self.warnings)
        self.attrs = res["attrs"]
        # Both files carry the id of the run that wrote them (docs/outputs.md, "The output
        # protocol"); a page is never built from the results of another run than the summary's.
        ids = (self.attrs.get("run_id"), self.summary.get("run_id"))
        if ids != (None, None) and ids[0] != ids[1]:
            raise ReportError(f"{self.results_path} (run {ids[0]}) and {SUMMARY} (run {ids[1]}) are "
                              "from different runs; run the case again")
        for key in GROUPS:
            setattr(self, key, res[key])
        self.compare = res["compare"]
        self.transport = res["transport"]  # /transport/<coefficient> groups by coefficient
        self.groups = res["groups"]
        self.config_text = self.attrs.get("config_toml")
        self.cfg = {}
        if isinstance(self.config_text, str) and self.config_text.strip():
            try:
                self.cfg = tomllib.loads(self.config_text)
            except Exception as e:  # noqa: BLE001 - any parse problem is only a warning here
                self.warnings.append(f"config_toml in results.h5 does not parse as TOML ({e}).")
        self.figdir = None

    # summary.json, one accessor per block
    def top_summary(self, key):
        return self.summary.get(key)

    def hydro_summary(self, *keys):
        return get(self.summary, "hydro", *keys)

    def md_summary(self, *keys):
        return get(self.summary, "md", *keys)

    def compare_summary(self, *keys):
        return get(self.summary, "compare", *keys)

    def transport_summary(self, *keys):
        return get(self.summary, "transport", *keys)

    def engine_blocks(self):
        """[(engine name, its summary.json block)] of the engines that wrote one."""
        return [(eng, self.summary[eng]) for eng in ("hydro", "md", "compare")
                if isinstance(self.summary.get(eng), dict) and self.summary[eng]]

    def has_hydro(self):
        return bool(self.hydro_ts or self.hydro_fields or self.summary.get("hydro"))

    def has_md(self):
        return bool(self.md_group or self.md_ts or self.md_fields or self.summary.get("md"))

    def has_compare(self):
        return bool(self.compare or self.summary.get("compare"))

    def config(self, dotted):
        """A resolved configuration value: root attribute 'a.b', else the parsed TOML."""
        v = self.attrs.get(dotted)
        if v is None and self.cfg:
            d = self.cfg
            for part in dotted.split("."):
                d = d.get(part) if isinstance(d, dict) else None
            v = d
        return v

    def config_table(self, *keys):
        """A table of the parsed case configuration (e.g. config_table("case"))."""
        return get(self.cfg, *keys)


class SweepRun:
    """A folder of `granvv sweep`: sweep.json and the sub-folders of its points."""

    def __init__(self, outdir):
        self.outdir = Path(outdir)
        self.sweep_path = self.outdir / SWEEP
        self.sw = load_sweep(self.sweep_path)
        self.figdir = None

    def sweep(self, *keys):
        """A value of sweep.json: sweep("key"), sweep("points")."""
        return get(self.sw, *keys)

    def cooling(self, *keys):
        """A value of sweep.json's cooling analysis: cooling("power_of_one_minus_r2")."""
        return get(self.sw, "cooling", *keys)

    def without_points(self):
        """sweep.json without the per-point blocks."""
        return {k: v for k, v in self.sw.items() if k != "points"}


def is_sweep_folder(outdir):
    """A sweep folder holds sweep.json and no results.h5."""
    outdir = Path(outdir)
    return not (outdir / RESULTS).exists() and (outdir / SWEEP).is_file()


class AtlasRun:
    """A folder of `granvv atlas`: atlas.json (docs/atlas.md)."""

    def __init__(self, outdir):
        self.outdir = Path(outdir)
        self.atlas_path = self.outdir / ATLAS
        try:
            with open(self.atlas_path) as fh:
                self.at = json.load(fh)
        except (OSError, ValueError) as e:
            raise ReportError(f"cannot read {self.atlas_path}: {e}")
        if not isinstance(self.at, dict) or not isinstance(self.at.get("runs"), list):
            raise ReportError(f"{self.atlas_path} is not a granvv atlas (no runs list)")
        self.figdir = None

    def atlas(self, *keys):
        """A value of atlas.json: atlas("recommendation", "model")."""
        return get(self.at, *keys)

    def runs(self, model=None):
        """The runs (dicts of atlas.json), of one model if given."""
        return [r for r in self.at["runs"] if isinstance(r, dict) and (model is None or r.get("model") == model)]

    def models(self):
        """The models that ran, in ladder order."""
        return [rung["model"] for rung in self.atlas("ladder") or [] if rung.get("runs")]

    def model_style(self, model):
        """The (colour, marker) the model's family declares (atlas.json ladder[].style); black
        crosses for a model the ladder does not list (an atlas.json written before styles were)."""
        for rung in self.atlas("ladder") or []:
            style = rung.get("style") if rung.get("model") == model else None
            if isinstance(style, dict) and style.get("color") and style.get("marker"):
                return style["color"], style["marker"]
        return "k", "x"


def is_atlas_folder(outdir):
    """An atlas folder holds atlas.json and no results.h5."""
    outdir = Path(outdir)
    return not (outdir / RESULTS).exists() and (outdir / ATLAS).is_file()
