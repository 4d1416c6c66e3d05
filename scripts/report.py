#!/usr/bin/python3
"""Build the granvv report of one output folder.

    /usr/bin/python3 scripts/report.py DIR [--strict]

Reads DIR/results.h5 (required, unless DIR holds a sweep) and DIR/summary.json (optional), writes the
figures to DIR/figures/*.png and the page to DIR/report.html (rendered from
scripts/report_template.html with the style of scripts/report_style.html, written to a temporary file and renamed, so a
failed run never leaves a half-written page).

Every figure is drawn only when its data are present, so the same script serves
every scene (hydro only, Haff, single mode, particle runs). The figures follow
Efrati, Livne & Meerson, PRL 94, 088001 (2005): Fig. 1 (profiles), Fig. 2
(energy), Fig. 3 (flow-by-inertia collapse), Fig. 4 (approach to the
singularity), plus Haff's law, the linear theory of the homogeneous cooling
state and a self-convergence study. A particle run (/md, LAMMPS) adds four figures in MD
units (sigma, sqrt(m/T0)): Haff's law against kinetic theory, the energy split with the
transverse (shear) flow, the coarse-grained fields, and the contact model (adaptive
stiffness). A side-by-side run (/compare) gets its own section first: the program's verdict with its
signal-to-noise and what kind of disagreement it is, four figures (cmp1 fields at the compared times,
cmp2 peak, gradient and energies against time, cmp3 agreement metrics, cmp4 density modes against
linear theory), the metrics per field and time, the Haff times and the cost of both engines; the hydro's
<T> is added to md1. Numbers printed next to the figures are
read from summary.json (the C++ program computes its own metrics); the only
quantities evaluated here are those needed to draw a curve.

A sweep folder (DIR/sweep.json from `granvv sweep`, no results.h5) gets a sweep page instead
(scripts/sweep_template.html): what was run, the verdict sentences, the points with links to their own
reports, and s1 t0(r), s2 zeta against 1 - r^2 with the fitted power, s3 theory against the measured
rate, s4 cost per point.

Exit status: 0 report written; 1 results.h5 missing or unreadable (one line on
stderr); 2 a figure failed and --strict was given (the report is still written).
Needs only Debian's python3-numpy, -matplotlib, -h5py, -jinja2.
"""
import argparse
import datetime
import json
import math
import os
import sys
import tempfile
import traceback
import urllib.parse
import warnings
from pathlib import Path

# Matplotlib wants a writable config/cache dir; the caller's HOME may be read-only.
if not os.access(os.environ.get("MPLCONFIGDIR", os.path.expanduser("~")), os.W_OK):
    import atexit
    import shutil
    os.environ["MPLCONFIGDIR"] = tempfile.mkdtemp(prefix="granvv-mpl-")
    atexit.register(shutil.rmtree, os.environ["MPLCONFIGDIR"], True)

import numpy as np  # noqa: E402
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import h5py  # noqa: E402
import jinja2  # noqa: E402
from markupsafe import Markup, escape  # noqa: E402

PROG = "report.py"
TEMPLATE = "report_template.html"
PAPER = "Efrati, Livne &amp; Meerson, PRL 94, 088001 (2005)"

# Paper thresholds quoted in the text (used only for the verdict badges).
COLLAPSE_TOLERANCE = 0.015   # Fig. 3: "all the curves in figure b coincide within 1.5 %"
TAU_TOLERANCE = 0.02         # Fig. 4a: tau = 1/(2 pi |a|) "agrees within 2 %"
MAX_CURVES = 7               # snapshots per panel

plt.rcParams.update({
    "figure.dpi": 110, "savefig.dpi": 130, "font.size": 9.5, "axes.titlesize": 10,
    "axes.labelsize": 10, "legend.fontsize": 8.5, "legend.framealpha": 0.85,
    "axes.grid": True, "grid.alpha": 0.25, "grid.linewidth": 0.6,
    "lines.linewidth": 1.4, "axes.titleweight": "bold", "axes.titlelocation": "left",
    "mathtext.fontset": "dejavusans",
})


class ReportError(Exception):
    """Fatal: the report cannot be built at all."""


class Skip(Exception):
    """A figure whose data are absent or uninformative for this scene."""


# --------------------------------------------------------------------------- data

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


def _read_compare(f):
    """The /compare group of a side-by-side run: attrs, t, x, collision_clock, and its subgroups
    (fields/<name>, peak, energy, inertia, modes), or None when the run compared nothing."""
    top = _read_group(f, "compare")
    if top is None:
        return None
    out = {"attrs": top["attrs"], "data": top["data"], "fields": {}}
    if "compare/fields" in f and isinstance(f["compare/fields"], h5py.Group):
        for name in f["compare/fields"]:
            g = _read_group(f, f"compare/fields/{name}")
            if g is not None:
                out["fields"][name] = g
    for sub in ("peak", "energy", "inertia", "modes"):
        out[sub] = _read_group(f, f"compare/{sub}")
    return out


def load_results(path):
    try:
        with h5py.File(path, "r") as f:
            res = {"attrs": {k: _decode(v) for k, v in f.attrs.items()}}
            for key, p in [("ts", "hydro/timeseries"), ("fields", "hydro/fields"),
                           ("lag", "hydro/lagrangian"), ("theory", "hydro/theory"),
                           ("conv", "hydro/convergence"), ("md", "md"),
                           ("md_ts", "md/timeseries"), ("md_fields", "md/fields")]:
                res[key] = _read_group(f, p)
            res["cmp"] = _read_compare(f)
            res["groups"] = []
            f.visit(lambda name: res["groups"].append(name) if isinstance(f[name], h5py.Group) else None)
            return res
    except FileNotFoundError:
        raise ReportError(f"{path} not found")
    except OSError as e:
        raise ReportError(f"cannot read {path}: {str(e).splitlines()[0]}")


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


# ------------------------------------------------------------------- formatting

_SUP = str.maketrans("-0123456789", "−0123456789")


def fmt(x, digits=4):
    """HTML-safe number: 3.183, 1.2 × 10<sup>−15</sup>, — for absent."""
    if x is None:
        return Markup("—")
    if isinstance(x, bool):
        return Markup("yes" if x else "no")
    if isinstance(x, (int, np.integer)):
        return Markup(f"{int(x):,}".replace(",", "\u2009"))
    if isinstance(x, str):
        return escape(x)
    v = num(x)
    if v is None:
        return Markup("NaN") if isinstance(x, float) else escape(str(x))
    if v == 0:
        return Markup("0")
    if 1e-3 <= abs(v) < 1e5 and "e" not in f"{v:.{digits}g}":
        return Markup(f"{v:.{digits}g}".replace("-", "−"))
    m, e = f"{v:.{max(digits - 2, 1)}e}".split("e")
    return Markup(f"{m} × 10<sup>{int(e)}</sup>".replace("-", "−"))


def pct(x, digits=3):
    v = num(x)
    return Markup("—") if v is None else Markup(f"{100 * v:.{digits}g} %".replace("-", "−"))


def verdict(ok, yes="within paper bound", no="outside paper bound"):
    """Badge for the page: (css class, text), or None when there is nothing to judge."""
    if ok is None:
        return None
    return ("pass", yes) if ok else ("fail", no)


def tex_num(v, digits=3):
    """Number for a matplotlib label."""
    if v is None:
        return "?"
    if v != 0 and not 1e-3 <= abs(v) < 1e5:
        m, e = f"{v:.{digits - 1}e}".split("e")
        return rf"{m}\times10^{{{int(e)}}}"
    return f"{v:.{digits}g}"


# ----------------------------------------------------------------- plot helpers

T_UNIT = r"$t$  [$L_x/\sqrt{T_0/m}$]"
X_UNIT = r"$x$  [$L_x$]"
N_UNIT = r"$n$  [$n_0$]"
V_UNIT = r"$v$  [$\sqrt{T_0/m}$]"
T_FIELD = r"$T$  [$T_0$]"


def time_colors(ts):
    """One colour per snapshot, ordered in time (by rank: output times crowd near a singularity)."""
    m = len(ts)
    cmap = plt.get_cmap("viridis")
    return [cmap(0.88 * i / (m - 1)) if m > 1 else cmap(0.4) for i in range(m)]


def pick(indices, k=MAX_CURVES):
    """At most k indices, evenly spread, always keeping the first and the last."""
    indices = list(indices)
    if len(indices) <= k:
        return indices
    pos = np.unique(np.round(np.linspace(0, len(indices) - 1, k)).astype(int))
    return [indices[i] for i in pos]


def thin(*arrays, limit=20000):
    """Subsample long time series for drawing (keeps the last point)."""
    n = arrays[0].size
    if n <= limit:
        return arrays
    idx = np.unique(np.append(np.linspace(0, n - 1, limit).astype(int), n - 1))
    return tuple(a[idx] for a in arrays)


def marker_every(t, count=18):
    """markevery indices roughly evenly spaced in log t."""
    pos = np.flatnonzero(t > 0)
    if pos.size <= count:
        return list(pos)
    lt = np.log(t[pos])
    targets = np.linspace(lt[0], lt[-1], count)
    return sorted(set(int(pos[np.argmin(np.abs(lt - g))]) for g in targets))


def power_scale(*arrays):
    """(factor, label suffix) so that the largest |value| of the arrays is O(1..1000)."""
    m = max((float(np.nanmax(np.abs(a))) for a in arrays if a is not None and np.isfinite(a).any()), default=0.0)
    if not m > 0 or 1e-2 <= m < 1e3:
        return 1.0, ""
    e = int(math.floor(math.log10(m)))
    return 10.0 ** -e, rf"  [$\times 10^{{{e}}}$]"


def wrap(x):
    return ((np.asarray(x, dtype=float) + 0.5) % 1.0) - 0.5


def sorted_periodic(x, *ys):
    xw = wrap(x)
    o = np.argsort(xw, kind="stable")
    return (xw[o],) + tuple(np.asarray(y)[o] for y in ys)


def tlabel(t, label=None):
    s = f"$t={t:.4g}$"
    if label in ("initial", "final"):
        s += f" ({label})"
    return s


def save(fig, figdir, name):
    """Write atomically: a crash mid-write never leaves a truncated PNG."""
    fd, tmp = tempfile.mkstemp(prefix="." + name, suffix=".png", dir=figdir)
    os.close(fd)
    try:
        fig.savefig(tmp, format="png")
        os.chmod(tmp, 0o644)
        os.replace(tmp, figdir / name)
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.unlink(tmp)
    return f"figures/{name}"


def snapshot_labels(fields, ns):
    lab = fields["data"].get("label") if fields else None
    if lab is None or len(lab) != ns:
        return ["output"] * ns
    return [str(x) for x in lab]


def find_snapshot_summary(summary, t):
    """The summary.json snapshot record closest to time t (within 1e-6 relative)."""
    best = None
    for rec in get(summary, "hydro", "snapshots") or []:
        tr = num(get(rec, "t"))
        if tr is not None and abs(tr - t) <= 1e-6 * max(1.0, abs(t)):
            best = rec
    return best


def config_value(res, cfg, dotted):
    """A resolved configuration value: root attribute 'a.b', else the parsed TOML."""
    v = res["attrs"].get(dotted)
    if v is None and cfg:
        d = cfg
        for part in dotted.split("."):
            d = d.get(part) if isinstance(d, dict) else None
        v = d
    return v


def hydro_physics(ctx):
    """(K, q) the hydro ran with: /hydro/theory attributes (in a comparison the particle
    scene's), else the case's physics.K and physics.q."""
    theory = ctx.res.get("theory") or {}
    K, q = num(theory.get("attrs", {}).get("K")), num(theory.get("attrs", {}).get("q"))
    if K is None or q is None:
        K = num(config_value(ctx.res, ctx.cfg, "physics.K"))
        q = num(config_value(ctx.res, ctx.cfg, "physics.q"))
    return K, q


# --------------------------------------------------------------------- figures
# Each figure function returns a dict for the template, or raises Skip(reason).

def fig_profiles(ctx):
    """Paper Fig. 1: density (log) and velocity (and temperature) profiles at the output times."""
    F = ctx.res["fields"]
    if F is None:
        raise Skip("no /hydro/fields in results.h5")
    t, x, n = arr(F, "t"), arr(F, "x", 2), arr(F, "n", 2)
    vx, vy, T = arr(F, "v_x", 2), arr(F, "v_y", 2), arr(F, "T", 2)
    if t is None or x is None or n is None or x.ndim != 2 or n.shape != x.shape or x.shape[0] != t.size:
        raise Skip("/hydro/fields lacks t, x, n of matching shapes")
    ns = t.size
    labels = snapshot_labels(F, ns)
    dn = max(np.nanmax(np.abs(n[i] / np.nanmean(n[i]) - 1)) for i in range(ns))
    dv = max(np.nanmax(np.abs(vx[i])) for i in range(ns)) if vx is not None else 0.0
    if dn < 1e-8 and dv < 1e-8:
        raise Skip("the profiles stay uniform (homogeneous cooling state): nothing to draw")
    idx = pick(range(ns))
    cols = time_colors(t[idx])
    last = idx[-1]
    clustered = np.nanmax(n[last]) > 5
    has_T = T is not None and T.shape == n.shape
    has_vy = vy is not None and vy.shape == n.shape and np.nanmax(np.abs(vy)) > 0
    rows = 2 + int(has_T)
    fig = plt.figure(figsize=(10.5 if clustered else 7.5, 2.6 * rows + 0.4), layout="constrained")
    gs = fig.add_gridspec(rows, 2 if clustered else 1, width_ratios=[2.1, 1] if clustered else None)
    ax_n = fig.add_subplot(gs[0, 0])
    ax_v = fig.add_subplot(gs[1, 0], sharex=ax_n)
    ax_T = fig.add_subplot(gs[2, 0], sharex=ax_n) if has_T else None
    # density axis: log for clusters, linear for mild contrast, n - 1 for linear perturbations
    n_mode = "delta" if dn < 1e-2 else ("log" if np.nanmax(n[idx]) / np.nanmin(n[idx]) > 3 else "lin")
    n_f, n_suffix = power_scale(n[idx] - 1.0) if n_mode == "delta" else (1.0, "")
    v_f, v_suffix = power_scale(*(a[idx] for a in (vx, vy if has_vy else None) if a is not None))
    for c, i in zip(cols, idx):
        xs, ni, *rest = sorted_periodic(x[i], n[i], *(a[i] for a in (vx, vy, T) if a is not None))
        lw = 1.8 if i == last else 1.1
        ax_n.plot(xs, (ni - 1.0) * n_f if n_mode == "delta" else ni, color=c, lw=lw, label=tlabel(t[i], labels[i]))
        k = 0
        if vx is not None:
            ax_v.plot(xs, rest[k] * v_f, color=c, lw=lw)
            k += 1
        if vy is not None:
            if has_vy:
                ax_v.plot(xs, rest[k] * v_f, color=c, lw=0.9, ls="--")
            k += 1
        if ax_T is not None:
            ax_T.plot(xs, rest[k], color=c, lw=lw)
    if n_mode == "log":
        ax_n.set_yscale("log")
        ax_n.set_ylabel(N_UNIT)
    elif n_mode == "delta":
        ax_n.set_ylabel(r"$n - 1$  [$n_0$]" + n_suffix)
        ax_n.axhline(0, color="0.5", lw=0.6)
    else:
        ax_n.set_ylabel(N_UNIT)
    ax_n.set_title("(a) density" + (" perturbation" if n_mode == "delta" else ""))
    ax_n.legend(loc="best", ncol=2 if len(idx) > 4 else 1)
    ax_v.set_ylabel(r"$v$  [$\sqrt{T_0/m}$]" + v_suffix)
    ax_v.set_title("(b) velocity" + ("  (solid $v_x$, dashed $v_y$)" if has_vy else ""))
    ax_v.axhline(0, color="0.5", lw=0.6)
    if ax_T is not None:
        ax_T.set_yscale("log")
        ax_T.set_ylabel(T_FIELD)
        ax_T.set_title("(c) granular temperature")
    (ax_T or ax_v).set_xlabel(X_UNIT)
    ax_n.set_xlim(-0.5, 0.5)
    for a in (ax_n, ax_v) + ((ax_T,) if ax_T else ()):
        if a is not (ax_T or ax_v):
            plt.setp(a.get_xticklabels(), visible=False)

    zoom_text = ""
    if clustered:
        ip = int(np.nanargmax(n[last]))
        xp = float(x[last, ip])
        xp_label = round(xp, 4) + 0.0   # + 0.0: no "-0.0000" in the label
        d = wrap(x[last] - xp)
        # half-width: 1.5 x the extent where the final peak exceeds 3 x the median density
        thr = 3.0 * max(1.0, float(np.nanmedian(n[last])))
        inside = np.abs(d[n[last] > thr])
        w = float(np.clip(1.5 * inside.max() if inside.size else 0.02, 5.0 / n.shape[1], 0.25))
        ax_z = fig.add_subplot(gs[:, 1])
        # paper's inset: earlier density history around the major peak
        zidx = [i for i in idx]
        for c, i in zip(cols, zidx):
            di = wrap(x[i] - xp)
            sel = np.abs(di) <= w
            o = np.argsort(di[sel])
            ax_z.plot(di[sel][o], n[i][sel][o], color=c, lw=1.8 if i == last else 1.1,
                      marker="." if i == last else None, ms=2.5)
        ax_z.set_yscale("log")
        ax_z.set_xlim(-w, w)
        ax_z.set_xlabel(rf"$x - x_{{\rm peak}}$  [$L_x$],  $x_{{\rm peak}} = {xp_label:.4f}$")
        ax_z.set_ylabel(N_UNIT)
        ax_z.set_title("(d) history around the major peak")
        zoom_text = "Panel (d) plays the role of the paper's inset, in a fixed window around the final peak."
    name = save(fig, ctx.figdir, "fig1_profiles.png")
    measured = [
        ("linearly unstable clustering modes", fmt(get(ctx.s, "hydro", "unstable_modes")), None),
        ("cells", fmt(get(ctx.s, "hydro", "cells") or n.shape[1]), None),
        (f"peak density at t = {fmt(t[last])} (last plotted snapshot)", fmt(float(np.nanmax(n[last]))), None),
        (f"cells with n &gt; 10<sup>2</sup> at t = {fmt(t[last])} (counted in the plotted snapshot)",
         fmt(int(np.sum(n[last] > 100))), None),
    ]
    return {
        "id": "profiles", "title": "Density and velocity profiles (paper Fig. 1)", "img": name,
        "paper": ("Fig. 1: with K = 4·10<sup>−4</sup>, q = 10<sup>−2</sup> (79 linearly unstable modes) "
                  "the gas develops high, narrow density peaks with steepening velocity gradients; "
                  "with 2000 Lagrangian mesh points the major peak holds more than 50 mesh points "
                  "above n = 10<sup>2</sup> shortly before it becomes singular. The inset shows the "
                  "earlier density history around the major peak."),
        "measured": measured,
        "note": Markup(zoom_text + " Profiles are drawn at cell centres, sorted in x on the periodic domain."),
    }


def fig_energy(ctx):
    """Paper Fig. 2: energy split on log-log axes with Haff's law, and the energy balance."""
    ts = ctx.res["ts"]
    t, E = arr(ts, "t", 3), arr(ts, "energy", 3)
    if t is None or E is None or E.size != t.size:
        raise Skip("no energy time series")
    Eth, Ek = arr(ts, "energy_thermal"), arr(ts, "energy_kinetic")
    Eky, Ec, haff = arr(ts, "energy_kinetic_y"), arr(ts, "energy_cooled"), arr(ts, "haff_T")
    P = arr(ts, "momentum")
    ok = lambda a: a is not None and a.size == t.size  # noqa: E731
    pos = t > 0
    if pos.sum() < 2:
        raise Skip("energy time series has fewer than two positive times")
    t0 = num(ctx.res["theory"]["attrs"].get("t0")) if ctx.res["theory"] else None
    has_balance = ok(Ec)
    fig, axes = plt.subplots(1, 2 if has_balance else 1, figsize=(11 if has_balance else 6.2, 4.3),
                             layout="constrained", squeeze=False)
    ax = axes[0, 0]
    tt = t[pos]
    me = marker_every(tt, 16)
    ax.plot(tt, E[pos], color="k", lw=2.6, label=r"total $E$ (Eq. 3)")
    if ok(Eth):
        ax.plot(tt, Eth[pos], color="C3", ls="none", marker="o", mfc="none", ms=5, markevery=me,
                label=r"thermal $\int nT\,dx$")
        ax.plot(tt, Eth[pos], color="C3", lw=0.7, alpha=0.6)
    if ok(Ek) and np.nanmax(Ek[pos]) > 0:
        ax.plot(tt, Ek[pos], color="C0", ls="none", marker="s", mfc="none", ms=5, markevery=me,
                label=r"kinetic $\int n v_x^2/2\,dx$")
        ax.plot(tt, Ek[pos], color="C0", lw=0.7, alpha=0.6)
    if ok(Eky) and np.nanmax(Eky[pos]) > 0:
        ax.plot(tt, Eky[pos], color="C2", ls="none", marker="^", mfc="none", ms=5, markevery=me,
                label=r"transverse kinetic $\int n v_y^2/2\,dx$")
        ax.plot(tt, Eky[pos], color="C2", lw=0.7, alpha=0.6)
    if ok(haff):
        ref = Eth[0] if ok(Eth) else E[0]
        ax.plot(tt, ref * haff[pos], color="0.35", lw=0.9,
                label=r"Haff: $E_{\rm th}(0)\,(1+t/t_0)^{-2}$")
    ax.set_xscale("log")
    ax.set_yscale("log")
    lo = tt.min()
    if t0:
        lo = max(lo, 0.1 * t0)
        if lo < t0 < tt.max():
            ax.axvline(t0, color="0.6", lw=0.7, ls=":")
            ax.text(t0, 0.5, r" $t_0$", transform=ax.get_xaxis_transform(), color="0.4", fontsize=8)
    ax.set_xlim(lo, tt.max() * 1.15)
    ax.set_xlabel(T_UNIT)
    ax.set_ylabel(r"energy  [$N T_0$]")
    ax.set_title("(a) energy split")
    ax.legend(loc="best")
    if has_balance:
        ax2 = axes[0, 1]
        E0 = E[0]
        bal = (E + Ec - E0) / E0
        pm = (P - P[0]) / math.sqrt(2 * E0) if ok(P) else None
        f, suffix = power_scale(bal, pm)
        tb, bal_t = thin(t, bal * f)
        ax2.plot(tb, bal_t, color="k", lw=0.9, label=r"$(E + E_{\rm cooled} - E(0))\,/\,E(0)$")
        if pm is not None:
            tb, pm_t = thin(t, pm * f)
            ax2.plot(tb, pm_t, color="C1", lw=0.9, label=r"$(P - P(0))\,/\,\sqrt{2E(0)}$")
        ax2.axhline(0, color="0.5", lw=0.6)
        ax2.set_xlabel(T_UNIT)
        ax2.set_ylabel("relative drift" + suffix)
        ax2.set_title("(b) conservation: energy balance and momentum")
        ax2.legend(loc="best")
    name = save(fig, ctx.figdir, "fig2_energy.png")
    measured = [
        ("energy balance drift |E + E<sub>cooled</sub> − E(0)| / E(0)", fmt(get(ctx.s, "hydro", "energy_drift")), None),
        ("momentum drift", fmt(get(ctx.s, "hydro", "momentum_drift")), None),
    ]
    if ok(Eth) and ok(Ek):
        measured.append((f"at the last time t = {fmt(t[-1])}: E<sub>kin</sub>/E, E<sub>th</sub>/E "
                         "(read off the time series)",
                         Markup(f"{fmt(Ek[-1] / E[-1], 3)}, {fmt(Eth[-1] / E[-1], 3)}"), None))
        if ok(haff):
            measured.append(("E<sub>th</sub>(t<sub>end</sub>) / [E<sub>th</sub>(0)(1+t<sub>end</sub>/t<sub>0</sub>)<sup>−2</sup>] "
                             "(read off the time series)", fmt(Eth[-1] / (Eth[0] * haff[-1]), 3), None))
    return {
        "id": "energy", "title": "Energy: total, thermal, kinetic (paper Fig. 2)", "img": name,
        "paper": ("Fig. 2: E(t) follows Haff's law at early times and deviates later. Thermal and macroscopic "
                  "kinetic energy both decay at first, the thermal one faster; at late times the kinetic "
                  "energy approaches a constant (flow by inertia), so E is dominated by thermal energy early "
                  "and by kinetic energy late. The thermal energy keeps following Haff's law until the "
                  "singularity. Panel (b) is not in the paper: it checks that the scheme conserves "
                  "E + E<sub>cooled</sub> and momentum to round-off."),
        "measured": measured,
    }


def fig_collapse(ctx):
    """Paper Fig. 3: v vs x, v vs xi = x - t v with the initial profile, and the collapse error."""
    L, F = ctx.res["lag"], ctx.res["fields"]
    if L is None:
        raise Skip("no /hydro/lagrangian in results.h5")
    X, V, XI, V0 = (arr(L, k, 2) for k in ("node_x", "node_v_x", "xi", "inertia_v0"))
    t = arr(F, "t") if F else None
    if any(a is None for a in (X, V, XI, V0, t)) or not (X.shape == V.shape == XI.shape == V0.shape) \
            or X.ndim != 2 or X.shape[0] != t.size:
        raise Skip("/hydro/lagrangian lacks node_x, node_v_x, xi, inertia_v0 matching /hydro/fields/t")
    amp = float(np.nanmax(np.abs(V0)))
    if not amp > 0:
        raise Skip("initial velocity profile is zero: no flow by inertia to test")
    tau_in = num(ctx.res["theory"]["attrs"].get("inertia_tau")) if ctx.res["theory"] else None
    collapse = [num(get(r, "collapse_error")) for r in get(ctx.s, "hydro", "snapshots") or []]
    if tau_in is None and all(c is None for c in collapse):
        raise Skip("the program makes no flow-by-inertia prediction for this initial condition "
                   "(inertia_tau absent/NaN, no collapse_error in summary.json)")
    labels = snapshot_labels(F, t.size)
    later = [i for i in range(t.size) if t[i] > 0]
    if not later:
        raise Skip("no snapshot after t = 0")
    idx = pick(later, 6)
    cols = time_colors(t[idx])
    i0 = next((i for i in range(t.size) if t[i] == 0), None)
    fig = plt.figure(figsize=(10.5, 7.4), layout="constrained")
    gs = fig.add_gridspec(2, 2, height_ratios=[1.25, 1])
    ax_a = fig.add_subplot(gs[0, 0])
    ax_b = fig.add_subplot(gs[0, 1], sharey=ax_a)
    ax_c = fig.add_subplot(gs[1, :])
    if i0 is not None:
        xs, vs = sorted_periodic(X[i0], V[i0])
        ax_a.plot(xs, vs, color="0.6", lw=1.0, ls="--", label="$t=0$")
    # v0 as a smooth reference over the full period
    ref_i = idx[-1]
    xr, v0r = sorted_periodic(XI[ref_i], V0[ref_i])
    ax_b.plot(xr, v0r, color="k", lw=3.2, alpha=0.25, label=r"initial profile $v_0(\xi)$", zorder=1)
    for c, i in zip(cols, idx):
        xs, vs = sorted_periodic(X[i], V[i])
        ax_a.plot(xs, vs, color=c, label=tlabel(t[i], labels[i]))
        xis, vis, v0s = sorted_periodic(XI[i], V[i], V0[i])
        ax_b.plot(xis, vis, color=c, lw=1.1, label=tlabel(t[i], labels[i]), zorder=2)
        rec = find_snapshot_summary(ctx.s, float(t[i]))
        ce = num(get(rec, "collapse_error"))
        lab = tlabel(t[i]) + (f"  (summary: {100 * ce:.2f} %)" if ce is not None else "")
        ax_c.plot(xis, 100 * (vis - v0s) / amp, color=c, lw=1.1, label=lab)
    ax_a.set_xlim(-0.5, 0.5)
    ax_b.set_xlim(-0.5, 0.5)
    ax_a.set_xlabel(X_UNIT)
    ax_a.set_ylabel(V_UNIT)
    ax_a.set_title("(a) velocity vs Eulerian $x$")
    ax_a.legend(loc="best", fontsize=7.5)
    ax_b.set_xlabel(r"$\xi = x - t\,v$  [$L_x$]")
    ax_b.set_title(r"(b) velocity vs $\xi$: collapse onto $v_0$")
    ax_b.legend(loc="best", fontsize=7.5)
    plt.setp(ax_b.get_yticklabels(), visible=False)
    ax_c.axhspan(-100 * COLLAPSE_TOLERANCE, 100 * COLLAPSE_TOLERANCE, color="C2", alpha=0.12,
                 label="paper: ±1.5 %")
    for s in (-1, 1):
        ax_c.axhline(s * 100 * COLLAPSE_TOLERANCE, color="C2", lw=0.8, ls="--")
    ax_c.axhline(0, color="0.5", lw=0.6)
    ax_c.set_xlim(-0.5, 0.5)
    ax_c.set_xlabel(r"$\xi$  [$L_x$]")
    ax_c.set_ylabel(r"$(v - v_0(\xi))\,/\,|a|$  [%]")
    ax_c.set_title(rf"(c) deviation from the initial profile, $|a| = \max|v_0| = {amp:.4g}$")
    ymax = max(2.5 * 100 * COLLAPSE_TOLERANCE, 1.1 * float(np.nanmax(np.abs(ax_c.dataLim.intervaly))))
    ax_c.set_ylim(-ymax, ymax)
    ax_c.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize=7.5)
    name = save(fig, ctx.figdir, "fig3_inertia_collapse.png")
    errs = [(num(get(r, "t")), num(get(r, "collapse_error"))) for r in get(ctx.s, "hydro", "snapshots") or []]
    errs = [(tt, e) for tt, e in errs if tt is not None and e is not None]
    measured = []
    for tt, e in errs:
        measured.append((f"collapse error at t = {fmt(tt)}", pct(e), verdict(e <= COLLAPSE_TOLERANCE)))
    if errs:
        worst = max(e for _, e in errs)
        measured.insert(0, ("largest collapse error over the snapshots", pct(worst),
                            verdict(worst <= COLLAPSE_TOLERANCE)))
    tol_cfg = num(config_value(ctx.res, ctx.cfg, "analysis.collapse_tolerance"))
    if tol_cfg is not None and abs(tol_cfg - COLLAPSE_TOLERANCE) > 1e-12:
        measured.append(("collapse tolerance set in the case file (analysis.collapse_tolerance)", pct(tol_cfg), None))
    return {
        "id": "collapse", "title": "Flow by inertia: velocity collapse (paper Fig. 3)", "img": name,
        "paper": ("Fig. 3: the velocity plotted against ξ = x − v t at times 1, 2 and 3.225 collapses onto a "
                  "single curve, the initial profile v<sub>0</sub> = a sin 2πx (a = −0.05); "
                  "all curves coincide within 1.5 %. Panel (c) shows that difference directly, in per cent of "
                  "the amplitude, with the paper's ±1.5 % band."),
        "measured": measured,
        "note": Markup("Collapse error = max over nodes of |v − v<sub>0</sub>(ξ)| / |a|, as computed by the "
                       "C++ code (summary.json); the legend of (c) repeats it."),
    }


def fig_singularity(ctx):
    """Paper Fig. 4a: n and |dv/dx| at the peak vs t, and their inverses with the fitted line to tau."""
    ts = ctx.res["ts"]
    t, nmax, g = arr(ts, "t", 3), arr(ts, "n_max", 3), arr(ts, "dvdx_peak", 3)
    if t is None or nmax is None or nmax.size != t.size:
        raise Skip("no n_max time series")
    if np.nanmax(nmax) < 3 * max(nmax[0], 1e-300):
        raise Skip(f"peak density grows only to {np.nanmax(nmax):.3g}: no singularity to follow")
    g = np.abs(g) if g is not None and g.size == t.size else None
    tau = num(get(ctx.s, "hydro", "singularity_time"))
    tau_in = num(get(ctx.s, "hydro", "inertia_singularity_time"))
    if tau_in is None and ctx.res["theory"]:
        tau_in = num(ctx.res["theory"]["attrs"].get("inertia_tau"))
    win = get(ctx.s, "hydro", "tau_fit_window") or {}
    tw0, tw1 = num(win.get("t_min")), num(win.get("t_max"))
    with np.errstate(divide="ignore", invalid="ignore"):
        inv_n = 1.0 / nmax
        inv_g = np.where(g > 0, 1.0 / g, np.nan) if g is not None else None
    # markers evenly spaced in t, plus log-spaced in the time left to the end (dt shrinks there)
    rem = t[-1] - t
    me = [int(np.argmin(np.abs(t - v))) for v in np.linspace(t[0], t[-1], 22)]
    if rem[0] > 0 and np.any(rem > 0):
        small = rem[rem > 0].min()
        me += [int(np.argmin(np.abs(rem - v))) for v in np.geomspace(max(small, 1e-6 * rem[0]), 0.1 * rem[0], 12)]
    me = sorted(set(me))
    ncol = 3 if tau is not None else 2
    fig, axes = plt.subplots(1, ncol, figsize=(4.4 * ncol, 4.4), layout="constrained")
    ax, ax2 = axes[0], axes[1]
    sty_n = dict(color="C0", lw=0.8, marker="o", mfc="white", ms=4.5, markevery=me)
    sty_g = dict(color="C3", lw=0.8, marker="s", ms=3.8, markevery=me)
    ax.plot(t, nmax, label=r"$n$ at the peak, $n_{\max}$", **sty_n)
    if g is not None:
        ax.plot(t, g, label=r"$|\partial v/\partial x|$ at the peak", **sty_g)
    ax.set_yscale("log")
    for a in (ax, ax2):
        if tau is not None:
            a.axvline(tau, color="k", lw=1.0, label=rf"$\tau$ fitted $= {tau:.4f}$")
        if tau_in is not None:
            a.axvline(tau_in, color="C2", lw=1.0, ls="--",
                      label=rf"$\tau = 1/(2\pi|a|) = {tau_in:.4f}$ (inertia)")
        if tw0 is not None and tw1 is not None:
            a.axvspan(tw0, tw1, color="C1", alpha=0.12, lw=0, label="fit window" if a is ax2 else None)
    ax.set_xlabel(T_UNIT)
    ax.set_ylabel(r"$n_{\max}$ [$n_0$],  $|\partial v/\partial x|$ [$\sqrt{T_0/m}/L_x$]")
    ax.set_title("(a) peak density and velocity gradient")
    ax.legend(loc="upper left")
    # inverses: linear in t, both vanish at tau (paper's inset)
    ax2.plot(t, inv_n, label=r"$1/n_{\max}$", **sty_n)
    if inv_g is not None:
        ax2.plot(t, inv_g, label=r"$1/|\partial v/\partial x|$", **sty_g)
    if tau is not None:
        # straight line through (tau, 0); slope: least squares inside the fit window (drawing aid only)
        sel = (t >= (tw0 if tw0 is not None else -np.inf)) & (t <= (tw1 if tw1 is not None else np.inf)) & (t < tau)
        tl = np.linspace(t[0], tau, 60)
        for y, col in ((inv_n, "#0b3c66"), (inv_g, "#6b1010")):
            if y is None:
                continue
            m = sel & np.isfinite(y)
            if m.sum() < 2:
                continue
            A = np.sum(y[m] * (tau - t[m])) / np.sum((tau - t[m]) ** 2)
            ax2.plot(tl, A * (tau - tl), color=col, lw=1.0, ls="--", zorder=4)
        ax2.plot([], [], color="0.2", lw=1.0, ls="--", label=r"fit $\propto(\tau - t)$ in the window")
    # robust top: an isolated spike of 1/|dv/dx| (the peak cell hopping early on) must not flatten the rest
    tops = [float(np.nanmax(inv_n))]
    if inv_g is not None and np.isfinite(inv_g).any():
        tops.append(float(np.nanpercentile(inv_g, 98)))
    ax2.set_ylim(0, 1.12 * max(tops))
    ax2.set_xlabel(T_UNIT)
    ax2.set_ylabel(r"$1/n_{\max}$ [$1/n_0$],  $1/|\partial v/\partial x|$ [$L_x/\sqrt{T_0/m}$]")
    ax2.set_title("(b) inverses (paper's inset)")
    ax2.legend(loc="upper right")
    # Panel (c) counts time from the blow-up (extrapolated from the last samples of 1/n_max), the
    # time n_max really diverges; pressure in the peak bends 1/n_max, so the window fit comes earlier.
    tau_c = num(get(ctx.s, "hydro", "blowup_time")) or tau
    if tau is not None:
        ax3 = axes[2]
        before = t < tau_c
        dtau = tau_c - t[before]
        me3 = [int(i) for i in np.unique([np.argmin(np.abs(np.log(dtau) - v))
                                          for v in np.linspace(np.log(dtau.min()), np.log(dtau.max()), 25)])]
        ax3.plot(dtau, nmax[before], **{**sty_n, "markevery": me3}, label=r"$n_{\max}$")
        if g is not None:
            ax3.plot(dtau, g[before], **{**sty_g, "markevery": me3}, label=r"$|\partial v/\partial x|$")
        ref = np.geomspace(dtau.min(), dtau.max(), 10)
        ax3.plot(ref, 1.0 / ref, color="k", lw=1.0, ls=":", label=r"$(\tau - t)^{-1}$")
        ax3.set_xscale("log")
        ax3.set_yscale("log")
        ax3.invert_xaxis()
        ax3.set_xlabel(rf"$\tau_b - t$  [$L_x/\sqrt{{T_0/m}}$],  blow-up $\tau_b = {tau_c:.5f}$")
        ax3.set_title("(c) divergence as $(\\tau - t)^{-1}$")
        ax3.legend(loc="upper left")
        after = ~before
        if after.any():
            ax3.text(0.98, 0.03, f"not shown: {int(after.sum())} samples with $t \\geq \\tau_b$,\n"
                     f"reaching $n_{{\\max}} = {tex_num(float(np.nanmax(nmax[after])))}$ at $t = {t[after][-1]:.4f}$",
                     transform=ax3.transAxes, ha="right", va="bottom", fontsize=7.5,
                     bbox=dict(boxstyle="round,pad=0.3", fc="white", ec="0.8"))
    name = save(fig, ctx.figdir, "fig4a_singularity.png")
    dev = num(get(ctx.s, "hydro", "singularity_time_deviation"))
    measured = [
        ("singularity time τ (fit of 1/n<sub>max</sub> in the window)", fmt(tau), None),
        ("fit window", Markup(f"n ∈ [{fmt(num(win.get('n_min')))}, {fmt(num(win.get('n_max')))}], "
                              f"t ∈ [{fmt(tw0)}, {fmt(tw1)}]") if win else fmt(None), None),
        ("blow-up time τ<sub>b</sub> (1/n<sub>max</sub> extrapolated from the last two samples)",
         fmt(num(get(ctx.s, "hydro", "blowup_time"))), None),
        ("relative deviation τ<sub>b</sub>/τ<sub>inertia</sub> − 1",
         pct(num(get(ctx.s, "hydro", "blowup_time_deviation"))), None),
        ("flow-by-inertia prediction τ = 1/(2π|a|)", fmt(tau_in), None),
        ("relative deviation τ/τ<sub>inertia</sub> − 1", pct(dev),
         verdict(abs(dev) <= TAU_TOLERANCE) if dev is not None else None),
    ]
    pdt = get(ctx.s, "hydro", "peak_density_times")
    if isinstance(pdt, dict) and pdt:
        measured.append(("time the peak density first reaches " +
                         ", ".join(escape(k) for k in pdt), Markup(", ".join(str(fmt(num(v))) for v in pdt.values())),
                         None))
    return {
        "id": "singularity", "title": "Approach to the singularity (paper Fig. 4a)", "img": name,
        "paper": ("Fig. 4a: |∂v/∂x| and n at x = 0 grow without bound; their inverses (inset) decrease linearly "
                  "in time — the linear dependence sets in already at early times — and vanish at the "
                  "singularity. Flow by inertia from v<sub>0</sub> = a sin 2πx predicts τ = 1/(2π|a|) ≃ 3.18, "
                  "which agrees with the simulation within 2 %. In flow by inertia "
                  "1/|∂v/∂x| = τ − t exactly and n = n<sub>0</sub>(0)(1 − t/τ)<sup>−1</sup> at the peak; "
                  "panel (c), not in the paper, shows this power law against the time left."),
        "measured": measured,
        "note": Markup("The dashed straight lines in (b) pass through (τ, 0) with τ from summary.json; their "
                       "slopes are least-squares fits inside the shaded window, drawn only to guide the eye."),
    }


def fig_density_profile(ctx):
    """Paper Fig. 4b: n vs |x - x_peak| on log-log axes near the singularity, x^{-2/3} reference."""
    F = ctx.res["fields"]
    if F is None:
        raise Skip("no /hydro/fields in results.h5")
    t, x, n = arr(F, "t"), arr(F, "x", 2), arr(F, "n", 2)
    if t is None or x is None or n is None or n.shape != x.shape or x.shape[0] != t.size:
        raise Skip("/hydro/fields lacks t, x, n of matching shapes")
    ps = get(ctx.s, "hydro", "profile_slope") or {}
    t_fit = num(ps.get("t"))
    cand = [i for i in range(t.size) if t[i] > 0 and np.nanmax(n[i]) > 10]
    if not cand:
        raise Skip("no snapshot with a density peak above 10 n0")
    idx = cand[-3:]
    i_fit = None
    if t_fit is not None:
        i_fit = int(np.argmin(np.abs(t - t_fit)))
        if abs(t[i_fit] - t_fit) > 1e-6 * max(1, t_fit):
            i_fit = None
        elif i_fit not in idx:
            idx = sorted(set(idx[-2:] + [i_fit]))
    labels = snapshot_labels(F, t.size)
    cols = time_colors(t[idx])
    fig, ax = plt.subplots(figsize=(7.4, 5.0), layout="constrained")
    dmin = np.inf
    for c, i in zip(cols, idx):
        ip = int(np.nanargmax(n[i]))
        d = wrap(x[i] - x[i, ip])
        for side, ls, mk in ((d > 0, "-", None), (d < 0, "none", "o")):
            o = np.argsort(np.abs(d[side]))
            dd, nn = np.abs(d[side])[o], n[i][side][o]
            if dd.size:
                dmin = min(dmin, dd.min())
            ax.plot(dd, nn, color=c, ls=ls, marker=mk, ms=2.2, mfc="none", mew=0.6,
                    lw=1.6 if i == i_fit else 1.1,
                    label=tlabel(t[i], labels[i]) + (" — fitted" if i == i_fit else "") if side is not None and ls == "-" else None)
    ax.set_xscale("log")
    ax.set_yscale("log")
    xlo = max(dmin * 0.7, 1e-7)
    ax.set_xlim(xlo, 0.5)
    vis = [n[i][np.abs(wrap(x[i] - x[i, int(np.nanargmax(n[i]))])) >= xlo] for i in idx]
    top = max((float(np.nanmax(v)) for v in vis if v.size), default=None)
    if top:
        ax.set_ylim(top=3 * top)
    slope = num(ps.get("slope"))
    x0, x1 = num(ps.get("x_min")), num(ps.get("x_max"))
    ref_i = i_fit if i_fit is not None else idx[-1]
    ipr = int(np.nanargmax(n[ref_i]))
    dref = np.abs(wrap(x[ref_i] - x[ref_i, ipr]))
    xa, xb = (x0, x1) if x0 and x1 and 0 < x0 < x1 else (1e-3, 2e-2)
    xm = math.sqrt(xa * xb)
    sel = (dref >= xa) & (dref <= xb) & (n[ref_i] > 0)

    def anchor(p):
        """n at xm of the power law with exponent p that best matches the data in the window (log space)."""
        if not sel.any():
            return float(np.nanmedian(n[ref_i]))
        return float(np.exp(np.mean(np.log(n[ref_i][sel]) - p * np.log(dref[sel] / xm))))

    if x0 and x1:
        ax.axvspan(x0, x1, color="C1", alpha=0.10, lw=0, label="fit window")
    if slope is not None:
        xx = np.geomspace(xa, xb, 20)
        ax.plot(xx, anchor(slope) * (xx / xm) ** slope, color="k", lw=1.3, ls="--", zorder=5,
                label=rf"fitted slope ${slope:.3f}$ (summary)")
    xx = np.geomspace(xa / 4, min(xb * 6, 0.5), 20)
    ax.plot(xx, 2.5 * anchor(-2 / 3) * (xx / xm) ** (-2 / 3), color="C3", lw=2.0, alpha=0.8,
            label=r"reference $\propto |x - x_{\rm peak}|^{-2/3}$ (shifted)")
    ax.plot([], [], color="0.4", ls="-", label=r"$x > x_{\rm peak}$ (lines)")
    ax.plot([], [], color="0.4", ls="none", marker="o", mfc="none", ms=3, label=r"$x < x_{\rm peak}$ (circles)")
    ax.set_xlabel(r"$|x - x_{\rm peak}|$  [$L_x$]")
    ax.set_ylabel(N_UNIT)
    ax.set_title("Density profile near the singularity")
    ax.legend(loc="lower left", fontsize=8)
    name = save(fig, ctx.figdir, "fig4b_density_profile.png")
    measured = [
        (f"fitted log-log slope of n(|x|) at t = {fmt(t_fit)}", fmt(slope), None),
        ("paper", Markup("−2/3 ≈ −0.667"), None),
        ("difference slope − (−2/3)", fmt(slope + 2 / 3 if slope is not None else None, 2), None),
        ("fit range |x − x<sub>peak</sub>|", Markup(f"[{fmt(x0)}, {fmt(x1)}]"), None),
    ]
    return {
        "id": "density_profile", "title": "Density profile near the singularity (paper Fig. 4b)", "img": name,
        "paper": ("Fig. 4b (t = 3.209 and 3.225): very close to x = 0 the density grows as "
                  "n<sub>0</sub>(0)(1 − t/τ)<sup>−1</sup>; outside that core, but still close to x = 0, n(x, t) "
                  "approaches the universal profile n ∝ |x|<sup>−2/3</sup> (straight line, for reference)."),
        "measured": measured,
    }


def fig_haff(ctx):
    """Haff's law: mass-weighted T vs t on log-log axes, and the relative deviation."""
    ts = ctx.res["ts"]
    t, Tm, haff = arr(ts, "t", 2), arr(ts, "T_mean", 2), arr(ts, "haff_T", 2)
    if t is None or Tm is None or haff is None or not (t.size == Tm.size == haff.size):
        raise Skip("no T_mean / haff_T time series")
    Tmin = arr(ts, "T_min")
    t0 = num(ctx.res["theory"]["attrs"].get("t0")) if ctx.res["theory"] else None
    if t0 and t0 > 0:
        X = 1 + t / t0
        xlabel = r"$1 + t/t_0$" + rf"   ($t_0 = K/4q = {tex_num(t0)}$)"
        keep = np.ones_like(t, dtype=bool)
    else:
        X, xlabel, keep = t, T_UNIT, t > 0
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(7.4, 6.2), sharex=True, layout="constrained",
                                  gridspec_kw={"height_ratios": [2, 1]})
    Xk, Tk, Hk = thin(X[keep], Tm[keep], haff[keep])
    ax.plot(Xk, Hk, color="0.3", lw=3.0, alpha=0.35, label=r"Haff: $(1 + t/t_0)^{-2}$")
    ax.plot(Xk, Tk, color="C3", lw=1.3, label=r"$\langle T\rangle$ (mass-weighted)")
    if Tmin is not None and Tmin.size == t.size:
        Xk2, Tmk = thin(X[keep], Tmin[keep])
        ax.plot(Xk2, Tmk, color="C0", lw=1.0, ls=":", label=r"$T_{\min}$")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylabel(T_FIELD)
    ax.set_title("(a) cooling of the granular temperature")
    ax.legend(loc="lower left")
    with np.errstate(divide="ignore", invalid="ignore"):
        dev = Tm / haff - 1
    f, suffix = power_scale(dev[keep])
    Xd, dd = thin(X[keep], dev[keep] * f)
    ax2.plot(Xd, dd, color="C3", lw=1.2)
    ax2.axhline(0, color="0.5", lw=0.6)
    ax2.set_xlabel(xlabel)
    ax2.set_ylabel(r"$\langle T\rangle/T_{\rm Haff} - 1$" + suffix)
    ax2.set_title("(b) relative deviation from Haff's law")
    name = save(fig, ctx.figdir, "fig5_haff.png")
    K, q = hydro_physics(ctx)
    measured = [
        ("max |⟨T⟩/T<sub>Haff</sub> − 1| (summary)", fmt(get(ctx.s, "hydro", "haff_max_relative_error")), None),
        ("t<sub>0</sub> written by the code", fmt(t0), None),
        ("t<sub>0</sub> = K/(4q) from the configuration", fmt(K / (4 * q) if K and q else None), None),
    ]
    return {
        "id": "haff", "title": "Haff's cooling law", "img": name,
        "paper": ("The homogeneous cooling state obeys Haff's law T = (1 + t/t<sub>0</sub>)<sup>−2</sup>, "
                  "t<sub>0</sub> = K/(4q): a straight line of slope −2 against 1 + t/t<sub>0</sub> on log-log axes. "
                  "A uniform run must follow it to round-off; in a clustering run the mean temperature "
                  "departs from it once the density is no longer uniform."),
        "measured": measured,
    }


def fig_linear_theory(ctx):
    """Growth rates of the clustering and shear modes of the HCS vs mode number, with thresholds."""
    th = ctx.res["theory"]
    k = arr(th, "mode_k", 2)
    cr, sr = arr(th, "clustering_rate", 2), arr(th, "shear_rate", 2)
    if k is None or ((cr is None or cr.size != k.size) and (sr is None or sr.size != k.size)):
        raise Skip("no growth rates in /hydro/theory")
    K, q = hydro_physics(ctx)
    nu = th["attrs"].get("unstable_modes")
    nsu = th["attrs"].get("shear_unstable_modes")
    fig, ax = plt.subplots(figsize=(7.8, 4.6), layout="constrained")
    pos_max = 0.0
    curves = []
    if cr is not None and cr.size == k.size:
        curves.append((cr, "C3", "clustering (thermal) mode", "o"))
    if sr is not None and sr.size == k.size:
        curves.append((sr, "C0", "shear mode", "s"))
    few = k.max() <= 40
    for y, c, lab, mk in curves:
        ax.plot(k, y, color=c, lw=1.2 if few else 1.5, label=lab, marker=mk if few else None, ms=4)
        pos_max = max(pos_max, float(np.nanmax(y)))
    ax.axhline(0, color="0.3", lw=0.8)
    if not few:
        ax.set_xscale("log")
    if pos_max > 0:
        ax.set_ylim(-1.6 * pos_max, 1.25 * pos_max)
    if K and q:
        kc = math.sqrt(q) / (math.pi * K)
        ax.axvline(kc, color="C3", ls="--", lw=1.0,
                   label=rf"paper: $\pi k K = \sqrt{{q}}$, $k = {kc:.1f}$")
    for count, c, lab in ((nu, "C3", "clustering"), (nsu, "C0", "shear")):
        if count is not None and num(count) is not None and num(count) >= 1:
            if lab == "clustering":
                ax.axvspan(0.1 if not few else k.min() - 0.5, num(count) + 0.5, color=c, alpha=0.06, lw=0)
            ax.plot([num(count)], [0], marker="v", color=c, ms=8, ls="none",
                    label=f"last unstable {lab} mode (code): $k = {int(num(count))}$")
    # a linear-mode run: measured growth of one seeded mode against the theory curve
    lm = get(ctx.s, "hydro", "linear_mode")
    lm_note = None
    if isinstance(lm, dict):
        km, th_r, me_r = num(lm.get("k")), lm.get("rate_theory"), lm.get("rate_measured")
        th_re = num(th_r[0] if isinstance(th_r, list) and th_r else th_r)
        me_re = num(me_r[0] if isinstance(me_r, list) and me_r else me_r)
        on_curve = None
        if km is not None and cr is not None and th_re is not None:
            j = np.flatnonzero(k == km)
            if j.size and abs(cr[j[0]] - th_re) <= 1e-3 * max(1.0, abs(th_re)):
                on_curve = True
        if on_curve and me_re is not None:
            ax.plot([km], [me_re], marker="*", color="k", ms=13, ls="none", zorder=6,
                    label=rf"measured, seeded mode $k = {int(km)}$")
        elif km is not None:
            lm_note = ("The seeded-mode rate refers to a branch other than the plotted curve; "
                       "see the table.")
    ax.set_xlim((k.min() - 0.5, k.max() + 0.5) if few else (max(0.8, k.min() * 0.8), k.max() * 1.25))
    ax.set_xlabel(r"mode number $k$  ($k_x = 2\pi k$)")
    ax.set_ylabel("largest real growth rate  [collision-clock units]")
    ax.set_title("Linear stability of the homogeneous cooling state")
    ax.legend(loc="best")
    name = save(fig, ctx.figdir, "fig6_linear_theory.png")
    expected = (math.ceil(math.sqrt(q) / (math.pi * K)) - 1) if K and q else None
    got = get(ctx.s, "hydro", "unstable_modes")
    if got is None:
        got = nu
    measured = [
        ("unstable clustering modes (code)", fmt(got), verdict(int(got) == expected, "matches", "differs")
         if got is not None and expected is not None else None),
        ("number of k ≥ 1 with πkK &lt; √q (paper's criterion, from K, q)", fmt(expected), None),
        ("unstable shear modes (code)", fmt(get(ctx.s, "hydro", "shear_unstable_modes") or nsu), None),
    ]
    if isinstance(lm, dict):
        def cplx(v):
            if isinstance(v, list) and len(v) == 2 and all(num(c) is not None for c in v):
                return Markup(f"{fmt(num(v[0]))} {'+' if num(v[1]) >= 0 else '−'} {fmt(abs(num(v[1])))} i")
            return fmt(num(v))
        measured += [
            (f"seeded mode k = {fmt(lm.get('k'))}, branch {fmt(lm.get('branch'))}: rate, theory", cplx(lm.get("rate_theory")), None),
            ("… rate, measured from the run", cplx(lm.get("rate_measured")), None),
            ("… relative error", pct(num(lm.get("relative_error"))), None),
        ]
    return {
        "id": "linear", "title": "Linear theory: clustering and shear modes", "img": name,
        "paper": ("Linearising around the homogeneous cooling state gives a clustering mode and a shear mode. "
                  "Mode k (k<sub>x</sub> = 2πk) is clustering-unstable if πkK &lt; √q; for K = 4·10<sup>−4</sup>, "
                  "q = 10<sup>−2</sup> this gives 79 unstable modes. Growth is algebraic in t, i.e. exponential "
                  "in the collision clock used on the vertical axis."),
        "measured": measured,
        "note": Markup(escape(lm_note)) if lm_note else None,
    }


def fig_convergence(ctx):
    """Self-convergence: successive-refinement differences vs cells, slope-2 reference."""
    C = ctx.res["conv"]
    cells = arr(C, "cells", 2)
    if cells is None:
        raise Skip("no /hydro/convergence study in results.h5")
    orders_s = get(ctx.s, "hydro", "convergence") or {}
    fig, ax = plt.subplots(figsize=(6.8, 4.8), layout="constrained")
    drawn = []
    style = {"x": ("C0", "o", "position $x$"), "v": ("C3", "s", "velocity $v$"),
             "T": ("C1", "^", "temperature $T$"), "n": ("C2", "D", "density $n$")}
    words = {"x": "node position x", "v": "velocity v", "T": "temperature T", "n": "density n"}
    size = {"x": 10, "v": 5.5, "T": 6, "n": 6}   # x and v errors often coincide: nest the markers
    for key, (c, mk, lab) in style.items():
        e = arr(C, "error_" + key)
        if e is None or e.size != cells.size - 1:
            continue
        order = num(orders_s.get("order_" + key))
        if order is None:
            order = num(C["attrs"].get("order_" + key))
        ok = e > 0
        ax.plot(cells[:-1][ok], e[ok], color=c, marker=mk, ms=size[key], mfc="none", lw=1.2,
                label=f"{lab}: order {order:.2f}" if order is not None else lab)
        drawn.append((key, e, order))
    if not drawn:
        raise Skip("/hydro/convergence has cells but no error_* of length cells−1")
    top = max(float(np.nanmax(e)) for _, e, _ in drawn)
    xr = cells[:-1]
    ax.plot(xr, 1.8 * top * (xr / xr[0]) ** -2.0, color="k", ls="--", lw=1.0, label=r"reference $\propto N^{-2}$")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(r"cells $N$  (difference between $N$ and the next refinement)")
    ax.set_ylabel("self-convergence difference")
    tconv = num(orders_s.get("t")) or num(C["attrs"].get("t"))
    ax.set_title("Self-convergence" + (f" at $t = {tconv:.4g}$" if tconv is not None else ""))
    ax.legend(loc="lower left")
    ax.set_xticks(xr)
    ax.set_xticklabels([str(int(v)) for v in xr])
    ax.minorticks_off()
    name = save(fig, ctx.figdir, "fig7_convergence.png")
    measured = [(f"observed order, {words[k]}", fmt(o, 3), None) for k, _, o in drawn]
    measured.append(("cells", Markup(", ".join(str(int(c)) for c in cells)), None))
    return {
        "id": "convergence", "title": "Self-convergence of the Lagrangian scheme", "img": name,
        "paper": ("The paper uses a Lagrangian scheme (Richtmyer–Morton) that resolves steep gradients and high "
                  "peaks until close to the singularity; a second-order scheme shows differences between "
                  "successive refinements falling as N<sup>−2</sup> (dashed line)."),
        "measured": measured,
    }


# ------------------------------------------------------------ particle engine (MD)
# Particle units (DESIGN.md §4): sigma = m = T0 = 1. Lengths in sigma, times in sigma sqrt(m/T0),
# velocities in sqrt(T0/m), energies (whole box) in T0, number density in 1/sigma^2.

MD_HAFF_TOLERANCE = 0.03     # acceptance: fitted t0 within 3 % of kinetic theory with the Enskog chi(phi)
MD_T_UNIT = r"$t$  [$\sigma\sqrt{m/T_0}$]"
MD_X_UNIT = r"$x$  [$\sigma$]"
MD_N_UNIT = r"$n$  [$\sigma^{-2}$]"
MD_V_UNIT = r"[$\sqrt{T_0/m}$]"
MD_E_UNIT = r"energy of the box  [$T_0$]"
MD_MAX_MEMBERS = 40          # ensemble members drawn individually (thin lines)


def md_value(ctx, key):
    """A number of the particle engine: summary.json's md block first, else the /md attribute."""
    v = num(get(ctx.s, "md", key))
    if v is None and ctx.res.get("md"):
        v = num(ctx.res["md"]["attrs"].get(key))
    return v


def md_config(ctx, key):
    """A resolved md.* configuration value as a plain string/number (TOML quotes removed)."""
    v = config_value(ctx.res, ctx.cfg, "md." + key)
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


def md_timeseries(ctx):
    """(G, t) of /md/timeseries, or Skip with the reason (naming the MD error if the run failed)."""
    G = ctx.res.get("md_ts")
    t = arr(G, "t", 1)
    if t is None or t.ndim != 1:
        err = get(ctx.s, "md", "error")
        if err:
            raise Skip(f"the particle run failed before writing its time series: {err}")
        raise Skip("no /md/timeseries in results.h5 (no particle run in this scene)")
    return G, t


def nanmean_rows(a):
    """Mean over ensemble members, NaN (without a warning) where no member has a value."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return np.nanmean(a, axis=0)


def plain_log_ticks(axis, lo, hi, nbins=7):
    """Plain-number ticks (0.3, 0.4, …) on a log axis that spans less than about a decade."""
    if not (lo > 0 and hi > lo) or hi / lo > 300:
        return
    if hi / lo <= 12:
        ticks = matplotlib.ticker.MaxNLocator(nbins=nbins, steps=[1, 2, 2.5, 5, 10]).tick_values(lo, hi)
    else:   # one to two and a half decades: 1, 2, 5 × 10^k
        ticks = [m * 10.0 ** e for e in range(math.floor(math.log10(lo)), math.ceil(math.log10(hi)) + 1)
                 for m in (1, 2, 5)]
    ticks = [v for v in ticks if lo * (1 - 1e-9) <= v <= hi * (1 + 1e-9) and v > 0]
    if len(ticks) < 2:
        return
    axis.set_major_locator(matplotlib.ticker.FixedLocator(ticks))
    axis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(matplotlib.ticker.NullFormatter())


def band(ax, x, m, e, color, alpha=0.22, label=None, zorder=1):
    """Shade m ± e where e is finite; returns True if anything was drawn."""
    if e is None:
        return False
    ok = np.isfinite(m) & np.isfinite(e)
    if not ok.any():
        return False
    ax.fill_between(x, m - np.where(ok, e, 0), m + np.where(ok, e, 0), where=ok, color=color,
                    alpha=alpha, lw=0, label=label, zorder=zorder)
    return True


def legend_on_top(ax, entries, ncol, fontsize=7.8):
    """Legend across the top of the axes, with head room added so that it covers no data."""
    if entries <= 0:
        return
    rows = math.ceil(entries / ncol)
    f = min(0.5, 0.045 + 0.062 * rows * fontsize / 7.8 * (216 / max(ax.bbox.height * 72 / ax.figure.dpi, 60)))
    lo, hi = ax.get_ylim()
    if ax.get_yscale() == "log":
        L, H = math.log(lo), math.log(hi)
        ax.set_ylim(lo, math.exp(H + (H - L) * f / (1 - f)))
    else:
        ax.set_ylim(lo, hi + (hi - lo) * f / (1 - f))
    ax.legend(loc="upper center", ncol=ncol, fontsize=fontsize)


def fig_md_haff(ctx):
    """MD Haff: ensemble T(t) against Haff's law with the fitted, Enskog and dilute t0."""
    G, t = md_timeseries(ctx)
    S = t.size
    if S < 2:
        raise Skip("the particle time series has fewer than two samples")
    Tmem = md_members(G, "T", S)
    Tm = md_series(G, "T_mean", S)
    if Tm is None:
        if Tmem is None:
            raise Skip("/md/timeseries has neither T_mean nor T")
        Tm = nanmean_rows(Tmem)
    Ts = md_series(G, "T_stderr", S)
    M = Tmem.shape[0] if Tmem is not None else int(md_value(ctx, "ensemble") or 1)
    fit, chi, dil = (md_series(G, k, S) for k in ("haff_fit", "haff_theory", "haff_theory_dilute"))
    t0m, t0e = md_value(ctx, "haff_t0_measured"), md_value(ctx, "haff_t0_measured_error")
    T0m = md_value(ctx, "haff_T0_measured")
    t0c, t0d, t0p = (md_value(ctx, k) for k in ("haff_t0_theory", "haff_t0_theory_dilute", "haff_t0_paper"))
    T0 = T0m if T0m is not None else float(Tm[0])
    if chi is None and t0c:
        chi = T0 * (1 + t / t0c) ** -2.0
    if t0c and t0c > 0:
        X = 1 + t / t0c
        keep = np.ones(S, dtype=bool)
        xlabel = rf"$1 + t/t_0^{{\chi}}$,   $t_0^{{\chi}} = {t0c:.4g}\ \sigma\sqrt{{m/T_0}}$ (Enskog $\chi(\phi)$ theory)"
    else:
        X, keep, xlabel = t, t > 0, MD_T_UNIT
    if keep.sum() < 2:
        raise Skip("fewer than two samples at positive time")
    Xk = X[keep]
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(7.8, 7.0), sharex=True, layout="constrained",
                                  gridspec_kw={"height_ratios": [1.6, 1]})
    win = get(ctx.s, "md", "haff_fit_window")
    w0, w1 = (num(win[0]), num(win[1])) if isinstance(win, list) and len(win) == 2 else (None, None)
    if w0 is not None and w1 is not None and w1 > w0:
        xw = (1 + w0 / t0c, 1 + w1 / t0c) if t0c and t0c > 0 else (w0, w1)
        for a in (ax, ax2):
            for j, xv in enumerate(xw):
                if Xk.min() <= xv <= Xk.max() and (xv > Xk.min() or j == 1):
                    a.axvline(xv, color="C1", lw=1.0, ls=(0, (4, 3)),
                              label="fit window limits" if a is ax and j == 1 else None)
    # acceptance: t0 within ±3 % of the chi(phi) theory, shown as the band of Haff curves it allows
    if t0c and t0c > 0:
        lo_c = T0 * (1 + t / (t0c * (1 - MD_HAFF_TOLERANCE))) ** -2.0
        hi_c = T0 * (1 + t / (t0c * (1 + MD_HAFF_TOLERANCE))) ** -2.0
        ax.fill_between(Xk, lo_c[keep], hi_c[keep], color="C2", alpha=0.16, lw=0,
                        label=rf"acceptance: $t_0$ within $\pm{100 * MD_HAFF_TOLERANCE:.0f}$ % of $t_0^{{\chi}}$")
    if Tmem is not None and Tmem.shape[0] > 1:
        for j, row in enumerate(Tmem[:MD_MAX_MEMBERS]):
            ax.plot(Xk, row[keep], color="C3", lw=0.6, alpha=0.35,
                    label=f"{Tmem.shape[0]} ensemble members" if j == 0 else None)
    has_err = band(ax, Xk, Tm[keep], Ts[keep] if Ts is not None else None, "C3", label="± standard error")
    ax.plot(Xk, Tm[keep], color="C3", lw=1.4, marker="o", ms=2.8,
            label=r"$T$ ensemble mean" if M > 1 else r"$T$ (one run)")
    if chi is not None:
        ax.plot(Xk, chi[keep], color="k", lw=1.1,
                label=rf"Haff, Enskog $\chi(\phi)$: $t_0 = {tex_num(t0c, 4)}$")
    if dil is not None:
        ax.plot(Xk, dil[keep], color="C0", lw=1.1, ls="--", label=rf"Haff, dilute $\chi = 1$: $t_0 = {tex_num(t0d, 4)}$")
    if fit is not None:
        lab = rf"fit: $t_0 = {tex_num(t0m, 4)}" + (rf" \pm {tex_num(t0e, 2)}$" if t0e is not None else "$")
        ax.plot(Xk, fit[keep], color="C4", lw=1.1, ls="-.", label=lab)
    # the hydro of a side-by-side run (same K, q): its mass-weighted <T>, in MD time
    hyd = compare_hydro_T(ctx)
    hyd_note, t0_hyd = None, None
    if hyd is not None:
        th, Th = hyd
        sel = th <= t[-1] * (1 + 1e-9)
        th, Th = th[sel], Th[sel]
        Xh = 1 + th / t0c if t0c and t0c > 0 else th
        ok = (Xh > 0) & (Th > 0)
        Kq = hydro_physics(ctx)
        L = cmp_box(ctx)
        t0_hyd = Kq[0] / (4 * Kq[1]) * L if Kq[0] and Kq[1] and L else None
        if ok.sum() >= 2:
            ax.plot(Xh[ok], Th[ok], color="C5", lw=1.6, ls=(0, (6, 2)), zorder=5,
                    label=r"hydro $\langle T\rangle$ (same $K$, $q$)"
                    + (rf": $t_0 = K/4q = {tex_num(t0_hyd, 4)}$" if t0_hyd else ""))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylabel(r"$T$  [$T_0$]")
    ax.set_title(r"(a) granular temperature against Haff's law $T_0(1 + t/t_0)^{-2}$")
    ax.legend(loc="lower left", fontsize=8)
    ylo = float(np.nanmin([np.nanmin(Tm[keep])] + ([np.nanmin(chi[keep])] if chi is not None else [])))
    yhi = float(np.nanmax([np.nanmax(Tm[keep])] + ([np.nanmax(chi[keep])] if chi is not None else [])))
    if Tmem is not None:
        ylo, yhi = min(ylo, float(np.nanmin(Tmem[:, keep]))), max(yhi, float(np.nanmax(Tmem[:, keep])))
    ax.set_ylim(ylo / 1.04, yhi * 1.03)
    plain_log_ticks(ax.yaxis, ylo / 1.04, yhi * 1.03)
    if hyd is not None and ok.any():
        Tlast = float(Th[ok][-1])
        if Tlast < ylo / 1.04 or Tlast > yhi * 1.03 or np.nanmin(Th[ok]) < ylo / 1.04:
            hyd_note = (f"the hydro's ⟨T⟩ leaves the panel: {Tlast:.3g} T0 at t = {th[ok][-1]:.4g} "
                        "(its t0 = K/4q is not the particles' kinetic-theory t0)")
            ax.text(0.98, 0.97, "hydro leaves the panel:\n" + rf"$\langle T\rangle = {tex_num(Tlast)}$ at "
                    rf"$t = {th[ok][-1]:.4g}$", transform=ax.transAxes, ha="right", va="top", fontsize=8,
                    color="C5", bbox=dict(boxstyle="round,pad=0.3", fc="white", ec="C5", alpha=0.9))
    # (b) relative deviation, in per cent, from the two theories (both with the fitted T0)
    for ref, c, lab in ((chi, "k", r"$T/T_{\rm Haff}^{\chi} - 1$  (Enskog)"),
                        (dil, "C0", r"$T/T_{\rm Haff}^{\rm dilute} - 1$")):
        if ref is None:
            continue
        with np.errstate(divide="ignore", invalid="ignore"):
            d = 100 * (Tm / ref - 1)
            e = 100 * Ts / ref if Ts is not None else None
        band(ax2, Xk, d[keep], e[keep] if e is not None else None, c, alpha=0.13)
        ax2.plot(Xk, d[keep], color=c, lw=1.2, marker="o", ms=2.5, ls="-" if c == "k" else "--", label=lab)
    if hyd is not None and chi is not None and t0c and t0c > 0 and ok.sum() >= 2:
        ref_h = T0 * (1 + th[ok] / t0c) ** -2.0
        dh = 100 * (Th[ok] / ref_h - 1)
        if np.nanmax(np.abs(dh)) <= 30:   # a hydro far off (wrong t0) would flatten the particles' curves
            ax2.plot(Xh[ok], dh, color="C5", lw=1.4, ls=(0, (6, 2)), label=r"hydro $\langle T\rangle/T_{\rm Haff}^{\chi} - 1$")
    if t0c and t0c > 0:
        dev_band = [100 * (((1 + t / t0c) / (1 + t / (t0c * (1 + s * MD_HAFF_TOLERANCE)))) ** 2 - 1)
                    for s in (-1, 1)]
        ax2.fill_between(Xk, dev_band[0][keep], dev_band[1][keep], color="C2", alpha=0.16, lw=0, zorder=0,
                         label=rf"$t_0 = t_0^{{\chi}}(1 \pm {MD_HAFF_TOLERANCE:g})$")
    ax2.axhline(0, color="0.5", lw=0.6)
    ax2.set_xlabel(xlabel)
    ax2.set_ylabel(r"$T/T_{\rm Haff} - 1$  [%]")
    ax2.set_title("(b) relative deviation from the two theories" + (" (bands: ± standard error)" if has_err else ""))
    ax2.legend(loc="best", fontsize=8)
    if t0c and t0c > 0:
        plain_log_ticks(ax2.xaxis, float(Xk.min()), float(Xk.max()))
        # top axis in t (a twin with fixed ticks: secondary_xaxis on a log parent mislabels here)
        top = ax.twiny()
        top.set_xscale("log")
        top.set_xlim(ax.get_xlim())
        tt = matplotlib.ticker.MaxNLocator(nbins=8, steps=[1, 2, 2.5, 5, 10]).tick_values(0, float(t[keep].max()))
        tt = [v for v in tt if 0 <= v <= t[keep].max() * (1 + 1e-9)]
        top.xaxis.set_major_locator(matplotlib.ticker.FixedLocator([1 + v / t0c for v in tt]))
        top.xaxis.set_major_formatter(matplotlib.ticker.FixedFormatter([f"{v:g}" for v in tt]))
        top.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
        top.grid(False)
        top.set_xlabel(MD_T_UNIT, fontsize=9)
    name = save(fig, ctx.figdir, "md1_haff.png")

    dev_c = num(get(ctx.s, "md", "haff_t0_deviation"))
    if dev_c is None and t0m and t0c:
        dev_c = t0m / t0c - 1
    dev_d = num(get(ctx.s, "md", "haff_t0_deviation_dilute"))
    if dev_d is None and t0m and t0d:
        dev_d = t0m / t0d - 1
    unit = Markup(" σ(m/T<sub>0</sub>)<sup>1/2</sup>")
    measured = [
        ("t<sub>0</sub> fitted, T = T<sub>0</sub>(1 + t/t<sub>0</sub>)<sup>−2</sup> to the ensemble mean"
         + (f" in t ∈ [{fmt(w0)}, {fmt(w1)}]" if w0 is not None and w1 is not None else ""),
         Markup(f"{fmt(t0m)} ± {fmt(t0e, 2)}{unit}") if t0m is not None else fmt(None), None),
        ("T<sub>0</sub> fitted", fmt(T0m), None),
        ("t<sub>0</sub> kinetic theory with Enskog χ(φ) = (1 − 7φ/16)/(1 − φ)<sup>2</sup>",
         Markup(f"{fmt(t0c)}{unit}") if t0c is not None else fmt(None), None),
        ("… deviation t<sub>0</sub>/t<sub>0</sub><sup>χ</sup> − 1 (acceptance: within ±3 %)", pct(dev_c),
         verdict(abs(dev_c) <= MD_HAFF_TOLERANCE, "within 3 %", "outside 3 %") if dev_c is not None else None),
        ("… in units of the fit error, (t<sub>0</sub> − t<sub>0</sub><sup>χ</sup>)/δt<sub>0</sub> (computed here)",
         fmt((t0m - t0c) / t0e, 3) if t0m is not None and t0c is not None and t0e else fmt(None), None),
        ("t<sub>0</sub> dilute kinetic theory (χ = 1)", Markup(f"{fmt(t0d)}{unit}") if t0d is not None else fmt(None), None),
        ("… deviation t<sub>0</sub>/t<sub>0</sub><sup>dilute</sup> − 1", pct(dev_d), None),
        ("paper's t<sub>0</sub> = K/(4q) in MD units (1 − r<sup>2</sup> replaced by 4q, χ = 1)",
         Markup(f"{fmt(t0p)}{unit}") if t0p is not None else fmt(None), None),
        ("… deviation t<sub>0</sub>/t<sub>0</sub><sup>paper</sup> − 1 (computed here)",
         pct(t0m / t0p - 1) if t0m is not None and t0p else fmt(None), None),
        ("ensemble members (seeds)", fmt(M), None),
    ]
    if hyd is not None:
        measured.append(("hydro of the comparison: t<sub>0</sub> = K/(4q) in MD time (the K, q the hydro ran with; "
                         "computed here)", Markup(f"{fmt(t0_hyd)}{unit}") if t0_hyd else fmt(None), None))
        measured.append(("… deviation t<sub>0</sub><sup>hydro</sup>/t<sub>0</sub> − 1 from the fitted t<sub>0</sub>",
                         pct(t0_hyd / t0m - 1) if t0_hyd and t0m else fmt(None), None))
        if hyd_note:
            measured.append(("note", escape(hyd_note), None))
    phi, r = md_value(ctx, "area_fraction"), md_value(ctx, "restitution")
    return {
        "id": "md_haff", "title": "MD: Haff's cooling law for inelastic disks", "img": name,
        "paper": ("Haff's law: a homogeneous granular gas cools as T = T<sub>0</sub>(1 + t/t<sub>0</sub>)<sup>−2</sup>, "
                  "a straight line of slope −2 against 1 + t/t<sub>0</sub> on log-log axes. For 2D smooth disks "
                  "the cooling rate is ζ = √π (1 − r<sup>2</sup>) χ n σ (T/m)<sup>1/2</sup>, so t<sub>0</sub> = 2/ζ(T<sub>0</sub>); "
                  "with χ = 1 and 1 − r<sup>2</sup> ≈ 4q it is the paper's t<sub>0</sub> = K/(4q). At finite density the "
                  "Enskog factor χ(φ) = (1 − 7φ/16)/(1 − φ)<sup>2</sup> (Henderson) shortens t<sub>0</sub>"
                  + (f" by {fmt(100 * (1 - t0c / t0d), 2)} % at φ = {fmt(phi)}" if t0c and t0d and phi else "")
                  + (f", r = {fmt(r)}" if r is not None else "")
                  + ". Acceptance: the fitted t<sub>0</sub> lies within 3 % of the χ(φ) theory (green band). "
                  "All three Haff curves use the fitted T<sub>0</sub>, so panel (b) compares t<sub>0</sub> alone."),
        "measured": measured,
        "note": Markup("Times in σ(m/T<sub>0</sub>)<sup>1/2</sup> (top axis). T removes the local mean flow "
                       "(v<sub>x</sub> and v<sub>y</sub>) in each coarse-graining bin."
                       + ("" if M > 1 else " One run: no ensemble error band.")),
    }


def fig_md_energy(ctx):
    """MD energies: thermal and macroscopic kinetic (x, and y = shear), total; momentum drift."""
    G, t = md_timeseries(ctx)
    S = t.size
    if S < 2:
        raise Skip("the particle time series has fewer than two samples")
    keys = ("energy_total", "energy_thermal", "energy_kinetic_x", "energy_kinetic_y")
    E = {k: md_members(G, k, S) for k in keys}
    if all(v is None for v in E.values()):
        raise Skip("/md/timeseries has no energies")
    P = md_members(G, "momentum_x", S)
    Tm = md_series(G, "T_mean", S)
    Tmem = md_members(G, "T", S)
    if Tm is None and Tmem is not None:
        Tm = nanmean_rows(Tmem)
    N = md_value(ctx, "particles")
    has_p = P is not None and E["energy_total"] is not None and N
    fig, axes = plt.subplots(1, 2 if has_p else 1, figsize=(11.2 if has_p else 6.6, 4.5),
                             layout="constrained", squeeze=False,
                             gridspec_kw={"width_ratios": [1.45, 1]} if has_p else None)
    ax = axes[0, 0]
    style = {
        "energy_total": dict(color="k", lw=2.4, label=r"total kinetic $\Sigma_p\, m|c_p|^2/2$"),
        "energy_thermal": dict(color="C3", marker="o", label=r"thermal $\Sigma_b\, N_b T_b$"),
        "energy_kinetic_x": dict(color="C0", marker="s", label=r"flow along $x$: $\Sigma_b\, M_b v_{x,b}^2/2$"),
        "energy_kinetic_y": dict(color="C2", marker="^", label=r"transverse (shear) flow: $\Sigma_b\, M_b v_{y,b}^2/2$"),
    }
    me = max(1, S // 18)
    last = {}
    for k in keys:
        a = E[k]
        if a is None:
            continue
        st = dict(style[k])
        mean = nanmean_rows(a)
        last[k] = float(mean[-1])
        if a.shape[0] > 1:
            for row in a[:MD_MAX_MEMBERS]:
                ax.plot(t, row, color=st["color"], lw=0.5, alpha=0.3)
        mk = st.pop("marker", None)
        lab = st.pop("label") + (" (mean)" if a.shape[0] > 1 else "")
        ax.plot(t, mean, **{"lw": 1.2, **st}, marker=mk, ms=4, mfc="none", markevery=me, label=lab)
    bins = num(md_config(ctx, "bins"))
    kernel = md_config(ctx, "kernel")
    floor = None
    if Tm is not None and bins and kernel == "bin" and (E["energy_kinetic_x"] is not None or E["energy_kinetic_y"] is not None):
        floor = 0.5 * bins * Tm
        ax.plot(t, floor, color="0.45", lw=1.0, ls=":",
                label=rf"sampling-noise level per component $\approx B\,T/2$ ($B = {int(bins)}$ bins)")
    ax.set_yscale("log")
    ax.set_xlabel(MD_T_UNIT)
    ax.set_ylabel(MD_E_UNIT)
    ax.set_title("(a) energy split")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.15), fontsize=7.8, ncol=2)
    drift = None
    if has_p:
        ax2 = axes[0, 1]
        E0 = E["energy_total"][:, :1]
        with np.errstate(divide="ignore", invalid="ignore"):
            pm = (P - P[:, :1]) / np.sqrt(2 * N * E0)
        drift = float(np.nanmax(np.abs(pm))) if np.isfinite(pm).any() else None
        f, suffix = power_scale(pm)
        for j, row in enumerate(pm[:MD_MAX_MEMBERS]):
            ax2.plot(t, row * f, lw=0.9, color=plt.get_cmap("tab10")(j % 10),
                     label=f"member {j + 1}" if 1 < pm.shape[0] <= 6 else None)
        ax2.axhline(0, color="0.5", lw=0.6)
        ax2.set_xlabel(MD_T_UNIT)
        ax2.set_ylabel(r"$(P_x - P_x(0))\,/\,\sqrt{2 N m E(0)}$" + suffix)
        ax2.set_title("(b) momentum drift")
        if 1 < pm.shape[0] <= 6:
            ax2.legend(loc="best", fontsize=7.8)
    name = save(fig, ctx.figdir, "md2_energy.png")
    measured = [
        ("linearly unstable clustering modes in this box (πkK &lt; √q)", fmt(get(ctx.s, "md", "unstable_modes")), None),
        ("linearly unstable shear modes in this box", fmt(get(ctx.s, "md", "shear_unstable_modes")), None),
    ]
    Eth = last.get("energy_thermal")
    if Eth:
        for k, lab in (("energy_kinetic_x", "x"), ("energy_kinetic_y", "y")):
            if k in last:
                row = (f"at t = {fmt(t[-1])}: E<sub>kin,{lab}</sub>/E<sub>th</sub> (read off the time series)",
                       fmt(last[k] / Eth, 3), None)
                measured.append(row)
                if floor is not None and floor[-1] > 0:
                    measured.append((f"… E<sub>kin,{lab}</sub> / sampling-noise level B T/2 "
                                     "(≈ 1: no flow above noise; computed here)", fmt(last[k] / floor[-1], 3), None))
    if drift is not None:
        measured.append(("max |P<sub>x</sub> − P<sub>x</sub>(0)| / (2NmE(0))<sup>1/2</sup> over members (computed here)",
                         fmt(drift, 2), None))
    return {
        "id": "md_energy", "title": "MD: energy split and transverse flow", "img": name,
        "paper": ("Not in the paper, whose 1D model has no transverse velocity (DESIGN.md §6): in a periodic box the "
                  "shear mode (flow along y, wave vector along x) can go unstable before the clustering mode, so the "
                  "macroscopic kinetic energy of a particle run holds transverse flow. The granular temperature removes "
                  "the full local mean velocity (v<sub>x</sub> and v<sub>y</sub>) of each bin, and each component's flow "
                  "energy is counted on its own. In the homogeneous cooling state both stay at the sampling-noise level "
                  "(about T/2 per bin and component, dotted) while E<sub>th</sub> ≈ E follows Haff's law. Pair forces "
                  "conserve momentum: its drift is round-off."),
        "measured": measured,
        "note": Markup("Energies are whole-box sums in T<sub>0</sub> (m = 1). The thermal energy uses the unbiased bin "
                       "temperatures, so E<sub>th</sub> + E<sub>kin,x</sub> + E<sub>kin,y</sub> exceeds the total by the "
                       "noise energy of the bin means."),
    }


def fig_md_fields(ctx):
    """MD coarse-grained profiles n, v_x, v_y, T at the snapshot times, with ensemble error bands."""
    F = ctx.res.get("md_fields")
    t = arr(F, "t", 1)
    x = arr(F, "x", 1)
    if t is None or x is None or x.ndim != 1:
        if F is None:
            md_timeseries(ctx)   # Skip naming the failure, or the absence of a particle run
            raise Skip("no /md/fields in results.h5")
        raise Skip("no snapshots in /md/fields (md.output_times is empty)")
    ns, nb = t.size, x.size
    Q = {}
    for k in ("n", "v_x", "v_y", "T"):
        a = arr(F, k)
        if a is not None and a.shape == (ns, nb):
            e = arr(F, k + "_stderr")
            Q[k] = (a, e if e is not None and e.shape == (ns, nb) and np.isfinite(e).any() else None)
    if "n" not in Q:
        raise Skip("/md/fields lacks n of shape [snapshots x bins]")
    N, Lx, Ly = md_value(ctx, "particles"), md_value(ctx, "box_length"), md_value(ctx, "box_width")
    n0 = N / (Lx * Ly) if N and Lx and Ly else None
    M = int(md_value(ctx, "ensemble") or 1)
    t0c, T0m = md_value(ctx, "haff_t0_theory"), md_value(ctx, "haff_T0_measured")
    idx = pick(range(ns))
    cols = time_colors(t[idx])
    few = nb <= 60
    panels = [("n", "(a) number density", MD_N_UNIT), ("T", "(b) granular temperature", r"$T$  [$T_0$]"),
              ("v_x", "(c) longitudinal velocity $v_x$", r"$v_x$  " + MD_V_UNIT),
              ("v_y", "(d) transverse (shear) velocity $v_y$", r"$v_y$  " + MD_V_UNIT)]
    panels = [p for p in panels if p[0] in Q]
    ncols = 2 if len(panels) > 1 else 1
    nrows = math.ceil(len(panels) / ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(11 if ncols == 2 else 6.8, 3.4 * nrows + 0.5),
                             sharex=True, layout="constrained", squeeze=False)
    any_err = False
    Nb = n0 * Lx * Ly / nb if n0 else None
    for (key, title, ylabel), ax in zip(panels, axes.flat):
        a, e = Q[key]
        entries = 0
        for c, i in zip(cols, idx):
            any_err |= band(ax, x, a[i], e[i] if e is not None else None, c, alpha=0.18)
            ax.plot(x, a[i], color=c, lw=1.3, marker="o" if few else None, ms=3,
                    label=(f"$t = {t[i]:.4g}$" if key == "n" else None))
            entries += key == "n"
            if key == "T" and t0c and t0c > 0 and T0m:
                ax.axhline(T0m * (1 + t[i] / t0c) ** -2.0, color=c, lw=0.9, ls="--")
        if key in ("n", "T"):
            pos = a[idx][np.isfinite(a[idx]) & (a[idx] > 0)]
            if pos.size and pos.max() / pos.min() > 5:     # clusters: a log axis, as for the hydro
                ax.set_yscale("log")
        if key == "n" and n0:
            ax.axhline(n0, color="0.3", lw=0.9, ls="--", label=rf"$n_0 = N/(L_xL_y) = {n0:.4g}$")
            entries += 1
        if key == "T" and t0c and T0m:
            ax.plot([], [], color="0.3", lw=0.9, ls="--", label=r"Haff, Enskog $\chi(\phi)$, at each $t$")
            entries += 1
        if key in ("v_x", "v_y"):
            ax.axhline(0, color="0.5", lw=0.6)
            if "T" in Q and Nb and md_config(ctx, "kernel") in (None, "bin"):   # N_b is a bin's count
                Tl = float(np.nanmean(Q["T"][0][idx[-1]]))
                s = math.sqrt(Tl / (Nb * M)) if Tl > 0 else None
                if s:
                    for sgn in (-1, 1):
                        ax.axhline(sgn * s, color="0.35", lw=0.8, ls=":",
                                   label=(rf"$\pm\sqrt{{T/(N_b{' M' if M > 1 else ''})}}$ at the last $t$: "
                                          "bin sampling noise") if sgn > 0 else None)
                    entries += 1
        legend_on_top(ax, entries, min(entries, 4))
        ax.set_title(title)
        ax.set_ylabel(ylabel)
    for ax in axes.flat[len(panels):]:
        ax.set_visible(False)
    for ax in axes[-1, :]:
        ax.set_xlabel(MD_X_UNIT + "  (bin centres, box centred at 0)")
    if Lx:
        axes[0, 0].set_xlim(-Lx / 2, Lx / 2)
    name = save(fig, ctx.figdir, "md3_fields.png")
    il = idx[-1]
    measured = [
        ("snapshots (times)", Markup(", ".join(str(fmt(v)) for v in t)) if ns <= 12 else fmt(ns), None),
        ("bins, width", Markup(f"{nb}, {fmt(Lx / nb if Lx else None)} σ"), None),
        ("mean particles per bin N<sub>b</sub> = N/B", fmt(Nb, 4), None),
        ("ensemble members", fmt(M), None),
        ("unstable clustering modes in this box (πkK &lt; √q)", fmt(get(ctx.s, "md", "unstable_modes")), None),
    ]
    if n0:
        n_last = Q["n"][0][il]
        measured.append((f"rms of n/n<sub>0</sub> − 1 over bins at t = {fmt(t[il])} (computed here)",
                         fmt(float(np.sqrt(np.nanmean((n_last / n0 - 1) ** 2))), 3), None))
        if Nb:
            measured.append(("… ideal-gas (Poisson) level 1/(N<sub>b</sub>M)<sup>1/2</sup>", fmt(1 / math.sqrt(Nb * M), 3), None))
    for k in ("v_x", "v_y"):
        if k in Q:
            measured.append((f"max |{k.replace('_', '<sub>')}</sub>| over bins at t = {fmt(t[il])} (computed here)",
                             fmt(float(np.nanmax(np.abs(Q[k][0][il]))), 3), None))
    return {
        "id": "md_fields", "title": "MD: coarse-grained fields", "img": name,
        "paper": ("A homogeneous cooling state has n = n<sub>0</sub>, v = 0 and a uniform T that follows Haff's law, as "
                  "long as no mode is linearly unstable (clustering: πkK &lt; √q; DESIGN.md §4). In a particle run the "
                  "fields carry thermal noise: on a scale ℓ the velocity noise is about (n<sub>0</sub>L<sub>y</sub>ℓ)<sup>−1/2</sup> "
                  "(DESIGN.md §8), i.e. (T/N<sub>b</sub>)<sup>1/2</sup> per bin (dotted lines), reduced by √M with M seeds."),
        "measured": measured,
        "note": Markup(("Shaded: ± standard error of the ensemble mean over seeds. " if any_err else
                        "No error bands: one run (the standard error needs at least two seeds). ")
                       + "The density noise is not Poisson in general (static structure factor of the gas); "
                         "only an ensemble measures it."),
    }


def fig_md_contact(ctx):
    """Contact model: kn and dt vs t (adaptive stiffness), with the hard-disk scaling."""
    G, t = md_timeseries(ctx)
    S = t.size
    kn, dt = md_members(G, "kn", S), md_members(G, "dt", S)
    if kn is None and dt is None:
        raise Skip("/md/timeseries has no kn or dt")
    Tm = md_series(G, "T_mean", S)
    Tmem = md_members(G, "T", S)
    changes = get(ctx.s, "md", "stiffness_changes")
    rows = [(k, a) for k, a in (("kn", kn), ("dt", dt)) if a is not None]
    fig, axes = plt.subplots(len(rows), 1, figsize=(7.6, 2.9 * len(rows) + 0.4), sharex=True,
                             layout="constrained", squeeze=False)
    for (key, a), ax in zip(rows, axes[:, 0]):
        for j, row in enumerate(a[:MD_MAX_MEMBERS]):
            # sample i records the contact of the segment that ended at t[i]; it changes after a sample
            ax.plot(t, row, drawstyle="steps-pre", lw=1.3, color=plt.get_cmap("tab10")(j % 10),
                    label=f"member {j + 1}" if 1 < a.shape[0] <= 6 else
                    ("the run" if a.shape[0] == 1 else "each member" if j == 0 else None))
        Tref = Tmem[0] if Tmem is not None else Tm
        if Tref is not None and np.isfinite(Tref[0]) and Tref[0] > 0:
            p = 1.0 if key == "kn" else -0.5
            ax.plot(t, a[0, 0] * (Tref / Tref[0]) ** p, color="0.35", lw=0.9, ls=":",
                    label=(r"$k_n(0)\,T/T(0)$: hard-disk scaling $k_n \propto v^2$" if key == "kn" else
                           r"$\Delta t(0)\,(T/T(0))^{-1/2}$"))
        ax.set_yscale("log")
        lo, hi = float(np.nanmin(a)), float(np.nanmax(a))
        if Tref is not None and np.isfinite(Tref).all() and Tref[0] > 0:
            r_ = a[0, 0] * (Tref / Tref[0]) ** (1.0 if key == "kn" else -0.5)
            lo, hi = min(lo, float(np.nanmin(r_))), max(hi, float(np.nanmax(r_)))
        ax.set_ylim(lo / 1.25, hi * 1.25)
        if key == "kn":
            ax.set_ylabel(r"$k_n$  [$T_0/\sigma^2$]")
            ch = f"{int(num(changes))} stiffness change" + ("s" if num(changes) != 1 else "") if num(changes) is not None else ""
            ax.set_title(r"(a) normal stiffness $k_n$" + (f" — {ch} (all members)" if ch else ""))
        else:
            ax.set_ylabel(r"$\Delta t$  [$\sigma\sqrt{m/T_0}$]")
            ax.set_title(r"(b) time step $\Delta t = t_c/n_c$")
        ax.legend(loc="best", fontsize=7.8)
    axes[-1, 0].set_xlabel(MD_T_UNIT)
    name = save(fig, ctx.figdir, "md4_contact.png")
    ci, cf = get(ctx.s, "md", "contact_initial") or {}, get(ctx.s, "md", "contact_final") or {}
    nc = num(md_config(ctx, "steps_per_contact"))

    def tc(c):
        k, g = num(get(c, "kn")), num(get(c, "gamma_n"))
        if k is None or g is None or not 2 * k - g * g / 4 > 0:
            return None
        return math.pi / math.sqrt(2 * k - g * g / 4)   # m_eff = m/2 = 1/2

    def trio(c):
        return Markup(f"{fmt(num(get(c, 'kn')))}, {fmt(num(get(c, 'gamma_n')))}, {fmt(num(get(c, 'dt')))}")

    r, rm = md_value(ctx, "restitution"), md_value(ctx, "restitution_measured")
    measured = [
        ("restitution r: target / measured (binary collision in LAMMPS)", Markup(f"{fmt(r)} / {fmt(rm, 6)}"), None),
        ("… difference r<sub>measured</sub> − r", fmt(rm - r if rm is not None and r is not None else None, 2), None),
        ("initial k<sub>n</sub>, γ<sub>n</sub>, Δt (member 1)", trio(ci), None),
        ("final k<sub>n</sub>, γ<sub>n</sub>, Δt (member 1)", trio(cf), None),
        ("stiffness changes (all members)", fmt(changes), None),
    ]
    tci = tc(ci)
    if tci and num(get(ci, "dt")):
        measured.append(("t<sub>c</sub> = π/(k<sub>n</sub>/m<sub>eff</sub> − γ<sub>n</sub><sup>2</sup>/4)<sup>1/2</sup>, "
                         "steps per contact t<sub>c</sub>/Δt (computed here; md.steps_per_contact = "
                         f"{fmt(int(nc)) if nc else '—'})",
                         Markup(f"{fmt(tci)}, {fmt(tci / num(get(ci, 'dt')), 4)}"), None))
    measured += [
        ("steps (all members), atom-steps", Markup(f"{fmt(get(ctx.s, 'md', 'steps'))}, "
                                                   f"{fmt(md_value(ctx, 'atom_steps'), 3)}"), None),
        ("atom-steps / s", fmt(md_value(ctx, "atom_steps_per_second"), 3), None),
    ]
    ov = num(md_config(ctx, "max_overlap"))
    return {
        "id": "md_contact", "title": "MD: contact model and adaptive stiffness", "img": name,
        "paper": ("DESIGN.md §4: linear spring–dashpot (LAMMPS gran/hooke, friction off), m<sub>eff</sub> = m/2, "
                  "γ<sub>n</sub> = −2 ln r (k<sub>n</sub>/m<sub>eff</sub>)<sup>1/2</sup>/(π<sup>2</sup> + ln<sup>2</sup> r)<sup>1/2</sup>, "
                  "contact time t<sub>c</sub> = π/(k<sub>n</sub>/m<sub>eff</sub> − γ<sub>n</sub><sup>2</sup>/4)<sup>1/2</sup>. "
                  "Hard disks are approached by keeping the overlap at the fastest relative speed below "
                  + (f"{fmt(ov)} σ" if ov else "md.max_overlap")
                  + ", so k<sub>n</sub> ∝ v<sub>max</sub><sup>2</sup>; as the gas cools k<sub>n</sub> is lowered and "
                  "Δt = t<sub>c</sub>/n<sub>c</sub> raised at the same restitution (dotted: the continuous scaling "
                  "k<sub>n</sub> ∝ T, Δt ∝ T<sup>−1/2</sup>). r is checked by a binary collision inside LAMMPS."),
        "measured": measured,
        "note": Markup("Each member sets its own k<sub>n</sub> from the fastest speed of its own sample"
                       + ("; with md.adaptive_stiffness the stiffness is lowered whenever the fastest relative "
                          "speed has fallen below half its value at the last change."
                          if str(md_config(ctx, "adaptive_stiffness")).lower() != "false" else
                          "; md.adaptive_stiffness is off, so k<sub>n</sub> and Δt stay fixed.")),
    }


# ------------------------------------------------------ hydro and particles side by side
# /compare (app/compare_output.cpp), all in the hydro's scaled units: x in Lx on [-1/2, 1/2),
# t in Lx/sqrt(T0/m) (MD time = t * Lx/sigma), n in n0, v in sqrt(T0/m), T in T0.

CMP_FIELDS = [("n", "density", r"$n$  [$n_0$]", "C0"),
              ("v_x", "velocity $v_x$", r"$v_x$  [$\sqrt{T_0/m}$]", "C3"),
              ("v_y", "transverse velocity $v_y$", r"$v_y$  [$\sqrt{T_0/m}$]", "C2"),
              ("T", "temperature", r"$T$  [$T_0$]", "C1")]
CMP_FIELD_HTML = {"n": "n", "v_x": "v<sub>x</sub>", "v_y": "v<sub>y</sub>", "T": "T"}
CMP_FIELD_TEX = {"n": "$n$", "v_x": "$v_x$", "v_y": "$v_y$", "T": "$T$"}
CMP_HYDRO, CMP_MD, CMP_INERTIA = "C0", "C3", "0.15"
CMP_MAX_TIMES = 6            # columns of the profile figure


def cmp_data(ctx):
    """(C, t, x) of /compare, or Skip."""
    C = ctx.res.get("cmp")
    if C is None:
        raise Skip("no /compare group in results.h5 (the scene does not compare hydro and particles)")
    t, x = arr(C, "t", 1), arr(C, "x", 2)
    if t is None or x is None or t.ndim != 1 or x.ndim != 1:
        raise Skip("/compare has no common output time (t) or no bins (x)")
    return C, t, x


def cmp_box(ctx):
    """Lx in sigma (MD time = scaled t * Lx), or None."""
    C = ctx.res.get("cmp")
    v = num(C["attrs"].get("box_length")) if C else None
    return v if v is not None else md_value(ctx, "box_length")


def cmp_rows(g, name, shape):
    """A [times x bins] array of a /compare subgroup with the given shape, or None."""
    a = arr(g, name, 1)
    return a if a is not None and a.shape == shape else None


def cmp_vec(g, name, size):
    a = arr(g, name, 1)
    return a if a is not None and a.ndim == 1 and a.size == size and np.isfinite(a).any() else None


def cmp_fields(C, t, x):
    """[(key, title, ylabel, colour, hydro, md, md_error or None)] for the compared fields."""
    out = []
    for key, title, ylabel, colour in CMP_FIELDS:
        g = C["fields"].get(key)
        if g is None:
            continue
        h, m = cmp_rows(g, "hydro", (t.size, x.size)), cmp_rows(g, "md", (t.size, x.size))
        if h is None or m is None:
            continue
        e = cmp_rows(g, "md_error", (t.size, x.size))
        out.append((key, title, ylabel, colour, h, m, e if e is not None and np.isfinite(e).any() else None))
    return out


def cmp_window(C):
    """(window end or None, left_at or None, first field to leave or '')."""
    a = C["attrs"]
    first = a.get("first_field_to_leave")
    return num(a.get("agreement_window")), num(a.get("left_at")), first if isinstance(first, str) else ""


def mark_window(ax, C, t, label=True):
    """Shade the agreement window [t_first, window] and mark where the first field leaves it."""
    w, left, first = cmp_window(C)
    sig = num(C["attrs"].get("sigmas"))
    drawn = False
    if w is not None:
        if w > t[0]:
            ax.axvspan(t[0], w, color="C2", alpha=0.10, lw=0, zorder=0)
        ax.axvline(w, color="C2", lw=1.1, ls="-", zorder=1,
                   label=(rf"agreement window: all fields within {sig:g}$\sigma$ to $t = {w:.4g}$"
                          if sig else rf"agreement window to $t = {w:.4g}$") if label else None)
        drawn = True
    if left is not None:
        ax.axvline(left, color="C3", lw=1.0, ls=":", zorder=1,
                   label=(rf"first to leave: {CMP_FIELD_TEX.get(first, first)} at $t = {left:.4g}$" if first else
                          rf"a field leaves at $t = {left:.4g}$") if label else None)
        drawn = True
    return drawn


def md_time_axis(ax, L):
    """A top axis in MD time (sigma sqrt(m/T0)) for a linear axis in scaled time."""
    if not L:
        return
    top = ax.secondary_xaxis("top", functions=(lambda v: v * L, lambda v: v / L))
    top.set_xlabel(r"$t_{\rm MD}$  [$\sigma\sqrt{m/T_0}$]", fontsize=8.5)
    top.tick_params(labelsize=8)


def positive(a):
    """a with the non-positive entries as NaN (for log axes)."""
    a = np.asarray(a, dtype=float)
    return np.where(a > 0, a, np.nan)


def centred_slope_at_peak(n, v):
    """|dv/dx| at the bin of the largest n (centred difference on equal bins of the unit period),
    as the C++ comparison does for hydro and MD; NaN when the row is not finite."""
    if n is None or v is None or not (np.isfinite(n).all() and np.isfinite(v).all()):
        return np.nan
    b = int(np.argmax(n))
    nb = n.size
    return abs((v[(b + 1) % nb] - v[(b - 1) % nb]) * nb / 2.0)


def fig_cmp_profiles(ctx):
    """Side by side: n, v_x, (v_y), T of hydro and MD (± error) on the bins at up to 6 times."""
    C, t, x = cmp_data(ctx)
    rows = cmp_fields(C, t, x)
    if not rows:
        raise Skip("/compare/fields holds no hydro and md rows of [times x bins]")
    L = cmp_box(ctx)
    I = C.get("inertia")
    inertia = {"n": cmp_rows(I, "n", (t.size, x.size)), "v_x": cmp_rows(I, "v", (t.size, x.size))}
    idx = pick(range(t.size), CMP_MAX_TIMES)
    nr, nc = len(rows), len(idx)
    width = max(2.3 * nc + 1.3, 7.5)
    leg_cols = max(1, min(3, int(width // 3.0)))
    leg_rows = math.ceil(3 / leg_cols)
    fig = plt.figure(figsize=(width, 2.05 * nr + 1.0 + 0.25 * leg_rows), layout="constrained")
    gs = fig.add_gridspec(nr + 1, nc, height_ratios=[0.13 * leg_rows + 0.07] + [1.0] * nr)
    axes = np.empty((nr, nc), dtype=object)
    for r in range(nr):
        for c in range(nc):
            axes[r, c] = fig.add_subplot(gs[r + 1, c], sharex=axes[0, 0] if (r or c) else None)
    few = x.size <= 60
    has_inertia = False
    for r, (key, title, ylabel, colour, h, m, e) in enumerate(rows):
        lo, hi = np.inf, -np.inf
        for c, i in enumerate(idx):
            ax = axes[r, c]
            ax.plot(x, h[i], color=CMP_HYDRO, lw=1.5, zorder=3, label="hydro (binned like the particles)")
            ei = e[i] if e is not None else None
            if few:
                ax.errorbar(x, m[i], yerr=ei, fmt="o", ms=2.6, color=CMP_MD, elinewidth=0.8, capsize=0,
                            zorder=2, label="MD mean ± standard error" if e is not None else "MD mean")
            else:
                band(ax, x, m[i], ei, CMP_MD, alpha=0.22, zorder=1)
                ax.plot(x, m[i], color=CMP_MD, lw=0.9, zorder=2,
                        label="MD mean ± standard error" if e is not None else "MD mean")
            inr = inertia.get(key)
            if inr is not None and np.isfinite(inr[i]).any():
                ax.plot(x, inr[i], color=CMP_INERTIA, lw=1.1, ls="--", zorder=4,
                        label="flow by inertia (paper Eqs. 5–6)")
                has_inertia = True
            vals = [h[i], m[i]] + ([m[i] - ei, m[i] + ei] if ei is not None else []) \
                + ([inr[i]] if inr is not None else [])
            fin = np.concatenate([np.asarray(v)[np.isfinite(v)] for v in vals])
            if fin.size:
                lo, hi = min(lo, float(fin.min())), max(hi, float(fin.max()))
            if key in ("v_x", "v_y"):
                ax.axhline(0, color="0.5", lw=0.6)
            if key == "n":
                ax.axhline(1, color="0.5", lw=0.6)
            if r == 0:
                ax.set_title(f"$t = {t[i]:.4g}$" + (rf"  ($t_{{\rm MD}} = {t[i] * L:.4g}$)" if L else ""),
                             fontsize=8.8, loc="center")
            if c == 0:
                ax.set_ylabel(ylabel)
            else:
                ax.tick_params(labelleft=key == "T")
            if r == nr - 1:
                ax.set_xlabel(X_UNIT)
            else:
                plt.setp(ax.get_xticklabels(), visible=False)
        # a common scale along a row shows the evolution; T cools, so each time gets its own
        if key != "T" and np.isfinite(lo) and hi > lo:
            pad = 0.06 * (hi - lo)
            for c in range(nc):
                axes[r, c].set_ylim(lo - pad, hi + pad)
    axes[0, 0].set_xlim(-0.5, 0.5)
    handles, labels = [], []
    for ax in axes.flat:
        for hd, lb in zip(*ax.get_legend_handles_labels()):
            if lb not in labels:
                handles.append(hd)
                labels.append(lb)
    lax = fig.add_subplot(gs[0, :])
    lax.axis("off")
    lax.legend(handles, labels, loc="center", ncol=min(len(labels), leg_cols), fontsize=8.5, frameon=False)
    name = save(fig, ctx.figdir, "cmp1_profiles.png")
    nb = x.size
    measured = [
        ("compared times t (scaled), all", Markup(", ".join(str(fmt(v)) for v in t)) if t.size <= 14 else fmt(t.size), None),
        ("… in MD time (σ(m/T<sub>0</sub>)<sup>1/2</sup>), shown", Markup(", ".join(str(fmt(v * L)) for v in t[idx])) if L else fmt(None), None),
        ("bins (the particles' coarse-graining), width", Markup(f"{nb}, {fmt(1.0 / nb)} L<sub>x</sub>"
                                                              + (f" = {fmt(L / nb)} σ" if L else "")), None),
        ("hydro started from", fmt({"md": "the MD's coarse-grained t = 0 fields (ensemble mean)",
                                    "case": "the case's initial fields"}.get(C["attrs"].get("hydro_initial"),
                                                                            C["attrs"].get("hydro_initial"))), None),
    ]
    for key, *_rest in rows:
        src = C["fields"][key]["attrs"].get("error_source")
        measured.append((f"MD error of {CMP_FIELD_HTML.get(key, key)}", fmt(src), None))
    return {
        "id": "cmp_profiles", "title": "Side by side: fields at the compared times", "img": name,
        "paper": ("The hydro (Eqs. 1–2, same K and q) against the particles coarse-grained into the same n, v, T. "
                  "The hydro is binned exactly like the particles, so the two are compared bin by bin. "
                  + ("Flow by inertia (dashed), the paper's Eqs. (5)–(6), is the pressureless limit the single mode "
                     "approaches before its singularity. " if has_inertia else "")
                  + "A bin agrees when |hydro − MD| is below the chosen number of standard errors of the MD mean."),
        "measured": measured,
        "note": Markup("Rows: fields; columns: up to six compared times (first and last always). n and v share one "
                       "scale along a row; T has its own per time (it cools). Error bars: ± one standard error of the "
                       "MD mean (its source is listed above)."),
    }


def fig_cmp_time(ctx):
    """Side by side against time: peak density, |dv/dx| at the peak, E_th and E_kin per particle."""
    C, t, x = cmp_data(ctx)
    P, E = C.get("peak"), C.get("energy")
    K = t.size
    L = cmp_box(ctx)
    hn, mn, mne = (cmp_vec(P, k, K) for k in ("hydro_n", "md_n", "md_n_error"))
    hg, mg, inn = (cmp_vec(P, k, K) for k in ("hydro_dvdx", "md_dvdx", "inertia_n"))
    I = C.get("inertia")
    In, Iv = cmp_rows(I, "n", (K, x.size)), cmp_rows(I, "v", (K, x.size))
    ig = None
    if In is not None and Iv is not None:
        ig = np.array([centred_slope_at_peak(In[i], Iv[i]) for i in range(K)])
        if not np.isfinite(ig).any():
            ig = None
    if hn is None and mn is None and hg is None and E is None:
        raise Skip("/compare has neither peak nor energy data")
    fig = plt.figure(figsize=(11.2, 8.6), layout="constrained")
    gs = fig.add_gridspec(2, 2, height_ratios=[1, 1.15])
    ax_a, ax_b, ax_c = fig.add_subplot(gs[0, 0]), fig.add_subplot(gs[0, 1]), fig.add_subplot(gs[1, :])
    # (a) peak density
    if hn is not None:
        ax_a.plot(t, hn, color=CMP_HYDRO, marker="o", ms=4, lw=1.4, label="hydro (binned)")
    if mn is not None:
        ax_a.errorbar(t, mn, yerr=mne, fmt="s", ms=4.5, color=CMP_MD, capsize=2.5, lw=1.0,
                      label="MD ± standard error" if mne is not None else "MD")
    if inn is not None:
        ax_a.plot(t, inn, color=CMP_INERTIA, lw=1.1, ls="--", marker="^", ms=3.5, label="flow by inertia (binned)")
    ax_a.set_ylabel(r"peak density $n_{\max}$  [$n_0$] (on the bins)")
    ax_a.set_title("(a) peak density")
    # (b) |dv/dx| at the peak
    if hg is not None:
        ax_b.plot(t, hg, color=CMP_HYDRO, marker="o", ms=4, lw=1.4, label="hydro (binned)")
    if mg is not None:
        ax_b.plot(t, mg, color=CMP_MD, marker="s", ms=4.5, lw=1.0, ls="-", label="MD (no error estimate)")
    if ig is not None:
        ax_b.plot(t, ig, color=CMP_INERTIA, lw=1.1, ls="--", marker="^", ms=3.5, label="flow by inertia (binned)")
    ax_b.set_ylabel(r"$|\partial v_x/\partial x|$ at the peak  [$\sqrt{T_0/m}/L_x$]")
    ax_b.set_title(r"(b) velocity gradient at the density peak")
    for a in (ax_a, ax_b):
        mark_window(a, C, t, label=False)
        a.set_xlabel(T_UNIT)
        a.legend(loc="best", fontsize=7.8)
        md_time_axis(a, L)
    # (c) energies per particle: the full time series of both engines, and the binned values
    ts = ctx.res.get("ts")
    th = arr(ts, "t", 2)
    drawn = 0
    Kq = hydro_physics(ctx)
    t0h = Kq[0] / (4 * Kq[1]) if Kq[0] and Kq[1] else None
    if th is not None:
        eth, ek, eky = arr(ts, "energy_thermal"), arr(ts, "energy_kinetic"), arr(ts, "energy_kinetic_y")
        if eth is not None and eth.size == th.size:
            ax_c.plot(th, positive(eth), color="C3", lw=1.8, label=r"hydro $E_{\rm th}$")
            drawn += 1
            if t0h:
                ax_c.plot(th, eth[0] * (1 + th / t0h) ** -2.0, color="0.3", lw=1.0, ls=":",
                          label=rf"Haff $E_{{\rm th}}(0)(1+t/t_0)^{{-2}}$, hydro's $t_0 = K/4q = {tex_num(t0h)}$")
        if ek is not None and ek.size == th.size:
            tot = ek + (eky if eky is not None and eky.size == th.size else 0.0)
            ax_c.plot(th, positive(tot), color="C0", lw=1.8, label=r"hydro $E_{\rm kin}$ (flow)")
            drawn += 1
    G = ctx.res.get("md_ts")
    tm = arr(G, "t", 2)
    N = num(C["attrs"].get("particles")) or md_value(ctx, "particles")
    if tm is not None and L and N:
        S = tm.size
        ets = md_members(G, "energy_thermal", S)
        kx, ky = md_members(G, "energy_kinetic_x", S), md_members(G, "energy_kinetic_y", S)
        nx, ny = md_members(G, "kinetic_noise_x", S), md_members(G, "kinetic_noise_y", S)
        tt = tm / L
        series = []
        if ets is not None:
            series.append((ets / N, "#8c1010", r"MD $E_{\rm th}$"))
        if kx is not None:
            flow = kx + (ky if ky is not None else 0.0) - (nx if nx is not None else 0.0) - (ny if ny is not None else 0.0)
            series.append((flow / N, "#0b2e59", r"MD $E_{\rm kin}$ (flow, bin noise removed)"))
        for a, col, lab in series:
            M = a.shape[0]
            mean = nanmean_rows(a)
            if M > 1:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", RuntimeWarning)
                    se = np.nanstd(a, axis=0, ddof=1) / math.sqrt(M)
                # log axis: shade only where the whole band is positive (a noise-only flow energy is ~0 ± se)
                se = np.where(np.isfinite(se) & (mean - se > 0), se, np.nan)
                band(ax_c, tt, mean, se, col, alpha=0.2, label=None)
            ax_c.plot(tt, positive(mean), color=col, lw=1.3, ls=(0, (4, 2)), zorder=4,
                      label=lab + (f" (mean of {M} ± s.e.)" if M > 1 else ""))
            drawn += 1
    if E is not None:
        for k, col, mk, lab in (("hydro_thermal", "C3", "o", r"$E_{\rm th}$ hydro binned"),
                                ("md_thermal", "C3", "s", r"$E_{\rm th}$ MD binned"),
                                ("hydro_kinetic", "C0", "o", r"$E_{\rm kin}$ hydro binned"),
                                ("md_kinetic", "C0", "s", r"$E_{\rm kin}$ MD binned")):
            v = cmp_vec(E, k, K)
            if v is None:
                continue
            filled = k.startswith("md")
            ax_c.plot(t, positive(v), ls="none", marker=mk, ms=6 if filled else 8, color=col,
                      mfc=col if filled else "none", mew=1.2, label=lab + " (compared times)")
            drawn += 1
    if not drawn:
        ax_c.set_visible(False)
    else:
        ax_c.set_yscale("log")
        mark_window(ax_c, C, t, label=True)
        ax_c.set_xlabel(T_UNIT)
        ax_c.set_ylabel(r"energy per particle  [$T_0$]")
        ax_c.set_title("(c) thermal and flow kinetic energy per particle")
        ax_c.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize=7.8)
        md_time_axis(ax_c, L)
        tmax = max(float(t[-1]), float(th[-1]) if th is not None else 0.0)
        ax_c.set_xlim(0, tmax * 1.02 if tmax > 0 else 1)
    name = save(fig, ctx.figdir, "cmp2_time.png")
    last = K - 1
    measured = [
        (f"peak density at the last compared time t = {fmt(t[last])}: hydro, MD ± error, flow by inertia",
         Markup(f"{fmt(hn[last] if hn is not None else None)}, {fmt(mn[last] if mn is not None else None)} ± "
                f"{fmt(mne[last] if mne is not None else None, 2)}, {fmt(num(inn[last]) if inn is not None else None)}"), None),
        ("… |dv/dx| at the peak: hydro, MD",
         Markup(f"{fmt(hg[last] if hg is not None else None, 3)}, {fmt(mg[last] if mg is not None else None, 3)}"), None),
    ]
    if E is not None:
        vals = {k: cmp_vec(E, k, K) for k in ("hydro_thermal", "md_thermal", "hydro_kinetic", "md_kinetic")}
        if vals["hydro_thermal"] is not None and vals["md_thermal"] is not None:
            measured.append(("… E<sub>th</sub> per particle: hydro, MD (binned)",
                             Markup(f"{fmt(vals['hydro_thermal'][last])}, {fmt(vals['md_thermal'][last])}"), None))
        if vals["hydro_kinetic"] is not None and vals["md_kinetic"] is not None:
            measured.append(("… E<sub>kin</sub> per particle: hydro, MD (binned, noise removed)",
                             Markup(f"{fmt(vals['hydro_kinetic'][last])}, {fmt(vals['md_kinetic'][last])}"), None))
    measured.append(("hydro's Haff time t<sub>0</sub> = K/4q (scaled; MD units)",
                     Markup(f"{fmt(t0h)}; {fmt(t0h * L if t0h and L else None)}"), None))
    return {
        "id": "cmp_time", "title": "Side by side: peak, gradient and energies against time", "img": name,
        "paper": ("Fig. 4a: the density and |∂v/∂x| at the peak grow towards the singularity; flow by inertia "
                  "(dashed) predicts both. Fig. 2: the thermal energy follows Haff's law while the flow's kinetic "
                  "energy decays slowly and takes over. Here both engines are measured on the particles' bins; "
                  "the lines in (c) are the full time series of each engine (the MD's flow energy with the "
                  "sampling noise of the bin means removed, so it can dip below zero in a noise-only gas)."),
        # (the markers are the flow energy of the ensemble-mean bins; the MD line is the mean of each
        # member's own flow energy, which keeps the random-phase flows that the ensemble mean averages out)
        "measured": measured,
        "note": Markup("Green: the agreement window (every field within the chosen σ at every compared time up to "
                       "the green line); red dotted: where the first field leaves. Top axes: MD time "
                       "t<sub>MD</sub> = t L<sub>x</sub> in σ(m/T<sub>0</sub>)<sup>1/2</sup>. In (c) the markers are "
                       "the energies of the compared (ensemble-mean) bins; the dashed MD lines are the mean over "
                       "members of each member's own energies, so with several members the MD line keeps flows of "
                       "random phase (noise-born modes, shear) that the ensemble mean averages out."),
    }


def fig_cmp_metrics(ctx):
    """Per field against time: fraction of bins within sigmas, worst z, normalised L2 and L-infinity."""
    C, t, x = cmp_data(ctx)
    K = t.size
    frac_req, sig = num(C["attrs"].get("agreement_fraction")), num(C["attrs"].get("sigmas"))
    tracks = []
    for key, title, _ylabel, colour in CMP_FIELDS:
        g = C["fields"].get(key)
        if g is None:
            continue
        d = {k: cmp_vec(g, k, K) for k in ("fraction_within", "worst_z", "l1", "l2", "linf")}
        if all(v is None for v in d.values()):
            continue
        tracks.append((key, colour, d))
    if not tracks:
        raise Skip("/compare/fields holds no metrics")
    L = cmp_box(ctx)
    fig, axes = plt.subplots(1, 3, figsize=(13.5, 4.4), layout="constrained")
    ax_f, ax_z, ax_n = axes
    lab = {"n": "$n$", "v_x": "$v_x$", "v_y": "$v_y$", "T": "$T$"}
    ymin = 1.0
    for key, col, d in tracks:
        if d["fraction_within"] is not None:
            ax_f.plot(t, d["fraction_within"], color=col, marker="o", ms=4, lw=1.2, label=lab[key])
            ymin = min(ymin, float(np.nanmin(d["fraction_within"])))
        if d["worst_z"] is not None:
            ax_z.plot(t, positive(d["worst_z"]), color=col, marker="o", ms=4, lw=1.2, label=lab[key])
        if d["l2"] is not None:
            ax_n.plot(t, positive(d["l2"]), color=col, marker="o", ms=4, lw=1.3, label=lab[key] + r"  $L_2$")
        if d["linf"] is not None:
            ax_n.plot(t, positive(d["linf"]), color=col, marker="^", ms=3.5, lw=1.0, ls="--",
                      label=lab[key] + r"  $L_\infty$")
    if frac_req is not None:
        ax_f.axhline(frac_req, color="k", lw=1.0, ls="--", label=f"required fraction {frac_req:g}")
        ymin = min(ymin, frac_req)
    ax_f.set_ylim(max(-0.02, ymin - 0.08 * (1.02 - ymin) - 0.02), 1.02)
    ax_f.set_ylabel(rf"fraction of bins with $|d| < {sig:g}\,\sigma_{{\rm MD}}$" if sig else "fraction of bins within")
    ax_f.set_title("(a) bins that agree")
    if sig is not None:
        ax_z.axhline(sig, color="k", lw=1.0, ls="--", label=rf"{sig:g}$\sigma$")
    ax_z.set_yscale("log")
    ax_z.set_ylabel(r"worst $|{\rm hydro} - {\rm MD}|\,/\,\sigma_{\rm MD}$ over the bins")
    ax_z.set_title("(b) worst bin, in standard errors")
    ax_n.set_yscale("log")
    ax_n.set_ylabel(r"$\|{\rm hydro} - {\rm MD}\|\,/\,$scale")
    ax_n.set_title(r"(c) normalised $L_2$ (solid), $L_\infty$ (dashed)")
    for a in axes:
        mark_window(a, C, t, label=a is ax_f)
        a.set_xlabel(T_UNIT)
        md_time_axis(a, L)
    ax_f.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), fontsize=7.8, ncol=2)
    ax_z.legend(loc="best", fontsize=7.8)
    ax_n.legend(loc="best", fontsize=7.2, ncol=2)
    name = save(fig, ctx.figdir, "cmp3_metrics.png")
    measured = []
    for key, _col, d in tracks:
        fw = d["fraction_within"]
        worst = d["worst_z"]
        i_min = int(np.nanargmin(fw)) if fw is not None and np.isfinite(fw).any() else None
        measured.append((f"{CMP_FIELD_HTML.get(key, key)}: lowest fraction within (at t), largest worst z",
                         Markup(f"{fmt(fw[i_min], 3) if i_min is not None else fmt(None)} "
                                f"(t = {fmt(t[i_min]) if i_min is not None else fmt(None)}), "
                                f"{fmt(num(np.nanmax(worst)) if worst is not None else None, 3)}"),
                         verdict(bool(np.nanmin(fw) >= frac_req), "agrees throughout", "leaves")
                         if fw is not None and frac_req is not None and np.isfinite(fw).any() else None))
    return {
        "id": "cmp_metrics", "title": "Side by side: agreement metrics against time", "img": name,
        "paper": ("How far the hydro is from the particles, field by field: (a) the fraction of bins where "
                  "|hydro − MD| is within the chosen number of standard errors of the MD mean (for pure Gaussian "
                  "noise about 99.7 % at 3σ); a field agrees at a time when this fraction reaches the required one "
                  "(dashed). (b) The worst bin in standard errors. (c) The size of the difference relative to the "
                  "field's natural scale: n<sub>0</sub> for n, the thermal speed (mean T)<sup>1/2</sup> for v, the "
                  "mean T for T."),
        "measured": measured,
    }


def fig_cmp_modes(ctx):
    """Density Fourier modes |n_k| / |n_k(0)| against the collision clock: MD, hydro, linear theory."""
    C, t, x = cmp_data(ctx)
    Mo = C.get("modes")
    if Mo is None:
        raise Skip("no /compare/modes (compare.density_modes = 0)")
    k = arr(Mo, "k", 1)
    s = arr(C, "collision_clock", 1)
    if k is None or s is None or s.size != t.size:
        raise Skip("/compare/modes lacks k, or /compare lacks the collision clock")
    M, K = k.size, t.size
    hyd, md, mde, th = (cmp_rows(Mo, n, (K, M)) for n in ("hydro", "md", "md_error", "theory"))
    rate = cmp_vec(Mo, "theory_rate", M)
    if md is None and hyd is None:
        raise Skip("/compare/modes has no hydro or md amplitudes")

    def norm(a):
        if a is None:
            return None
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(a[:1] > 0, a / a[:1], np.nan)

    def slope(a):
        """Least-squares slope of ln a against s (all compared times with a > 0)."""
        out = np.full(M, np.nan)
        if a is None:
            return out
        for j in range(M):
            ok = np.isfinite(a[:, j]) & (a[:, j] > 0)
            if ok.sum() >= 2 and np.ptp(s[ok]) > 0:
                out[j] = np.polyfit(s[ok], np.log(a[ok, j]), 1)[0]
        return out

    hn, mn, tn = norm(hyd), norm(md), norm(th)
    me = mde / md[:1] if mde is not None and md is not None else None
    ncol = M + 1 if M + 1 <= 3 else min(4, math.ceil(math.sqrt(M + 1)))
    nrow = math.ceil((M + 1) / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(3.3 * ncol + 0.6, 2.9 * nrow + 0.6), layout="constrained",
                             squeeze=False)
    flat = list(axes.flat)
    for j in range(M):
        ax = flat[j]
        if mn is not None:
            ax.errorbar(s, positive(mn[:, j]), yerr=me[:, j] if me is not None and np.isfinite(me[:, j]).any() else None,
                        fmt="s", ms=4, color=CMP_MD, capsize=2, lw=0.9,
                        label="MD (rms over members)" + (" ± s.e." if me is not None and np.isfinite(me).any() else ""))
        if hn is not None:
            ax.plot(s, positive(hn[:, j]), color=CMP_HYDRO, marker="o", ms=3.5, lw=1.3, label="hydro")
        if tn is not None:
            ax.plot(s, positive(tn[:, j]), color="k", lw=1.1, ls="--", label="linear theory")
        if rate is not None and np.isfinite(rate[j]):
            ax.plot(s, np.exp(rate[j] * (s - s[0])), color="0.55", lw=0.8, ls=":",
                    label=r"$e^{\lambda_k s}$ (fastest branch)")
        ax.set_yscale("log")
        ax.set_title(rf"$k = {int(k[j])}$" + (rf",  $\lambda_k = {rate[j]:.3g}$" if rate is not None else ""),
                     fontsize=9)
        ax.set_xlabel(r"collision clock $s = t_0\ln(1+t/t_0)$  [$L_x/\sqrt{T_0/m}$]", fontsize=8.2)
        ax.set_ylabel(r"$|n_k(t)|\,/\,|n_k(0)|$")
        if j == 0:
            ax.legend(loc="best", fontsize=7.2)
    ax = flat[M]
    kk = k.astype(int)
    if rate is not None:
        ax.plot(kk, rate, color="k", marker="o", ms=5, lw=1.2, label=r"theory $\lambda_k$ (fastest branch)")
    gm, gh = slope(md), slope(hyd)
    # keep the theory readable: a mode born from almost nothing at t = 0 has a huge fitted exponent;
    # such points sit on the panel's edge as arrows with their value
    ref = rate[np.isfinite(rate)] if rate is not None else np.array([])
    allv = np.concatenate([ref, gm[np.isfinite(gm)], gh[np.isfinite(gh)]])
    if ref.size and allv.size:
        span = max(float(ref.max()) - min(0.0, float(ref.min())), 1e-12)
        lo_lim = min(0.0, float(ref.min())) - 0.6 * span
        hi_lim = float(ref.max()) + 0.6 * span
        lo = max(lo_lim, float(allv.min()) - 0.08 * span)
        hi = min(hi_lim, float(allv.max()) + 0.08 * span)
    else:
        lo = hi = None
    for g, col, mk, mfc, lab in ((gm, CMP_MD, "s", CMP_MD, "MD: fitted exponent"),
                                 (gh, CMP_HYDRO, "D", "none", "hydro: fitted exponent")):
        if not np.isfinite(g).any():
            continue
        inside = np.isfinite(g) if lo is None else np.isfinite(g) & (g >= lo) & (g <= hi)
        ax.plot(kk[inside], g[inside], color=col, marker=mk, ms=5, mfc=mfc, ls="none", label=lab)
        if lo is not None:
            for j in np.flatnonzero(np.isfinite(g) & ~inside):
                up = g[j] > hi
                ax.plot([kk[j]], [hi if up else lo], color=col, marker="^" if up else "v", ms=7, mfc=mfc,
                        ls="none", clip_on=False)
                ax.annotate(f"{g[j]:.3g}", (kk[j], hi if up else lo), textcoords="offset points",
                            xytext=(6 if col == CMP_MD else -6, -10 if up else 4),
                            ha="left" if col == CMP_MD else "right", fontsize=7, color=col)
    if lo is not None and hi > lo:
        ax.set_ylim(lo, hi)
    ax.axhline(0, color="0.5", lw=0.7)
    ax.set_xticks(kk)
    ax.set_xlabel("mode number $k$")
    ax.set_ylabel(r"growth exponent in $s$")
    ax.set_title("growth exponents")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), fontsize=7.2, ncol=2)
    for a in flat[M + 1:]:
        a.set_visible(False)
    name = save(fig, ctx.figdir, "cmp4_modes.png")
    measured = []
    for j in range(M):
        measured.append((f"k = {int(k[j])}: exponent in s — theory, MD fit, hydro fit (fits computed here)",
                         Markup(f"{fmt(num(rate[j]) if rate is not None else None, 3)}, {fmt(num(gm[j]), 3)}, "
                                f"{fmt(num(gh[j]), 3)}"), None))
    return {
        "id": "cmp_modes", "title": "Side by side: density Fourier modes against linear theory", "img": name,
        "paper": ("Linearised around the homogeneous cooling state, the equations have constant coefficients in the "
                  "collision clock s = t<sub>0</sub> ln(1 + t/t<sub>0</sub>): each mode grows or decays as "
                  "exp(λ s), and mode k is clustering-unstable when πkK &lt; √q. The theory (dashed) evolves each "
                  "member's own t = 0 perturbation (n, v, T of that k) and takes the rms over members; the MD's "
                  "|n<sub>k</sub>| is the rms over members too (the phases of noise-born modes differ between seeds)."),
        "measured": measured,
        "note": Markup("Each curve is divided by its own t = 0 value. The fitted exponents are least-squares slopes of "
                       "ln|n<sub>k</sub>| against s over all compared times, nonlinear growth included — a guide, not "
                       "a measurement of λ<sub>k</sub>."),
    }


def compare_hydro_T(ctx):
    """(t_MD, <T>) of the hydro of a comparison (its Haff curve in MD time), or None."""
    if ctx.res.get("cmp") is None:
        return None
    ts = ctx.res.get("ts")
    t, T = arr(ts, "t", 2), arr(ts, "T_mean", 2)
    L = cmp_box(ctx)
    if t is None or T is None or T.size != t.size or not L:
        return None
    return t * L, T


def compare_section(ctx):
    """The verdict box and the tables of the side-by-side section, or None without /compare."""
    C = ctx.res.get("cmp")
    c = get(ctx.s, "compare") or {}
    if C is None and not c:
        return None
    attrs = C["attrs"] if C else {}

    def pick_value(key, summary_key=None):
        v = attrs.get(key)
        if v is None or (isinstance(v, float) and not math.isfinite(v)):
            v = c.get(summary_key or key)
        return v

    verdict_text = pick_value("verdict") or ""
    kind = pick_value("disagreement") or ""
    sn = num(pick_value("signal_to_noise"))
    sn_txt = fmt(sn, 3)
    plain = {
        "none": Markup("The fields agree within the particles' statistical error"
                       + (f" (signal/noise = {sn_txt}: the imposed flow is not well above the particles' noise, "
                          "so this agreement tests the hydro only weakly)." if sn is not None and sn < 3 else
                          f" (signal/noise = {sn_txt}).")),
        "noise": Markup(f"The particles' own fluctuations compete with the imposed signal (signal/noise = {sn_txt}): "
                        "the difference is noise-driven, not a failure of the hydro."),
        "model": Markup(f"The signal is clear of the noise (signal/noise = {sn_txt}): the difference is the hydro's."),
    }.get(kind, Markup(f"Disagreement kind: {escape(kind) or '—'} (signal/noise = {sn_txt})."))
    L = cmp_box(ctx)
    w, left, first = (cmp_window(C) if C else
                      (num(c.get("agreement_window")), num(c.get("left_at")), c.get("first_field_to_leave") or ""))
    t = arr(C, "t", 1) if C else None
    sig, frac = num(pick_value("sigmas")), num(pick_value("agreement_fraction"))

    def t_both(v):
        if v is None:
            return fmt(None)
        return Markup(f"t = {fmt(v)}" + (f" (t<sub>MD</sub> = {fmt(v * L)} σ(m/T<sub>0</sub>)<sup>1/2</sup>)" if L else ""))

    rows = [
        ("agreement window (every field within "
         + (f"{fmt(sig)}σ in at least {pct(frac, 3)} of the bins" if sig and frac else "the tolerance") + ")",
         Markup("up to ") + t_both(w) if w is not None else Markup("none: the fields differ from the first compared time")),
        ("first field to leave (time)", Markup(f"{Markup(CMP_FIELD_HTML.get(first, escape(first))) if first else fmt(None)}"
                                              + (f" at {t_both(left)}" if left is not None else ""))),
        ("signal-to-noise (imposed flow against the thermal velocity noise on the bin scale, DESIGN.md §8)", sn_txt),
        ("disagreement kind", fmt(kind or None)),
        ("hydro started from", fmt({"md": "the MD's coarse-grained t = 0 fields", "case": "the case's initial fields"}
                                   .get(pick_value("hydro_initial"), pick_value("hydro_initial")))),
        ("compared times", Markup(f"{t.size}, from t = {fmt(t[0])} to {fmt(t[-1])}") if t is not None else fmt(None)),
    ]
    # metrics per field and time
    metrics = []
    if C and t is not None:
        for key, *_ in CMP_FIELDS:
            g = C["fields"].get(key)
            if g is None:
                continue
            cols = {k: cmp_vec(g, k, t.size) for k in ("l1", "l2", "linf", "fraction_within", "worst_z")}
            trs = []
            for i in range(t.size):
                fw = num(cols["fraction_within"][i]) if cols["fraction_within"] is not None else None
                trs.append({"bad": fw is not None and frac is not None and fw < frac,
                            "cells": [fmt(num(t[i])), fmt(num(t[i] * L) if L else None)]
                            + [fmt(num(cols[k][i]) if cols[k] is not None else None, 3)
                               for k in ("l1", "l2", "linf", "fraction_within", "worst_z")]})
            metrics.append({"field": Markup(CMP_FIELD_HTML.get(key, key)), "source": fmt(g["attrs"].get("error_source")),
                            "rows": trs})
    # Haff: the particles' measured t0 against kinetic theory and the hydro's K/4q
    h = c.get("haff") if isinstance(c.get("haff"), dict) else {}
    t0m = num(h.get("t0_measured")) if h else None
    t0m = t0m if t0m is not None else md_value(ctx, "haff_t0_measured")
    t0e = num(h.get("t0_measured_error")) if h else None
    t0e = t0e if t0e is not None else md_value(ctx, "haff_t0_measured_error")
    t0c = num(h.get("t0_theory_enskog")) if h else None
    t0c = t0c if t0c is not None else md_value(ctx, "haff_t0_theory")
    t0d = num(h.get("t0_theory_dilute")) if h else None
    t0d = t0d if t0d is not None else md_value(ctx, "haff_t0_theory_dilute")
    t0h = num(h.get("t0_hydro")) if h else None

    def dev(ref):
        if t0m is None or ref is None:
            return fmt(None), fmt(None)
        d = t0m / ref - 1
        sg = (t0m - ref) / t0e if t0e else None
        return pct(d), fmt(sg, 3)

    unit = Markup(" σ(m/T<sub>0</sub>)<sup>1/2</sup>")
    haff = [("measured (fit of the MD's T(t))", Markup(f"{fmt(t0m)} ± {fmt(t0e, 2)}{unit}") if t0m is not None else fmt(None),
             fmt(None), fmt(None))]
    for lab, ref in (("kinetic theory, Enskog χ(φ)", t0c), ("kinetic theory, dilute (χ = 1)", t0d),
                     ("the hydro's K/4q (in MD time)", t0h)):
        d, sg = dev(ref)
        haff.append((lab, Markup(f"{fmt(ref)}{unit}") if ref is not None else fmt(None), d, sg))
    cost = get(c, "cost") or {}
    ch, cm = cost.get("hydro") or {}, cost.get("md") or {}
    cost_rows = [
        ("hydro: wall time", Markup(f"{fmt(num(ch.get('wall_seconds')), 3)} s") if num(ch.get("wall_seconds")) is not None else fmt(None)),
        ("hydro: cells, steps", Markup(f"{fmt(ch.get('cells'))}, {fmt(ch.get('steps'))}")),
        ("hydro: cell-steps, cell-steps/s", Markup(f"{fmt(num(ch.get('cell_steps')), 3)}, {fmt(num(ch.get('cell_steps_per_second')), 3)}")),
        ("MD: wall time", Markup(f"{fmt(num(cm.get('wall_seconds')), 3)} s") if num(cm.get("wall_seconds")) is not None else fmt(None)),
        ("MD: particles, ensemble members", Markup(f"{fmt(cm.get('particles'))}, {fmt(cm.get('ensemble'))}")),
        ("MD: atom-steps, atom-steps/s", Markup(f"{fmt(num(cm.get('atom_steps')), 3)}, {fmt(num(cm.get('atom_steps_per_second')), 3)}")),
        ("MD / hydro wall-time ratio", fmt(num(cost.get("md_to_hydro_wall_ratio")), 3)),
    ]
    notes = []
    if t0h is not None and t0m is not None and t0e and abs(t0h / t0m - 1) > 0.1 and abs(t0h - t0m) > 3 * t0e:
        notes.append(Markup(
            f"The hydro's Haff time K/4q = {fmt(t0h)} σ(m/T<sub>0</sub>)<sup>1/2</sup> (the K, q the hydro ran with, in MD time) "
            f"differs from the particles' measured t<sub>0</sub> = {fmt(t0m)} by {pct(t0h / t0m - 1)}: the hydro does "
            "not cool like this particle box (its K, q do not describe the box, e.g. when md.particles or the box "
            "is set directly). Differences in T then come from the cooling rate, whatever the signal-to-noise "
            "classification above says."))
    return {"verdict": verdict_text, "kind": kind, "plain": plain, "rows": rows, "metrics": metrics,
            "sigmas": fmt(sig), "haff": haff, "cost": cost_rows, "notes": notes}


FIGURES = [
    ("fig1_profiles.png", fig_profiles),
    ("fig2_energy.png", fig_energy),
    ("fig3_inertia_collapse.png", fig_collapse),
    ("fig4a_singularity.png", fig_singularity),
    ("fig4b_density_profile.png", fig_density_profile),
    ("fig5_haff.png", fig_haff),
    ("fig6_linear_theory.png", fig_linear_theory),
    ("fig7_convergence.png", fig_convergence),
    ("md1_haff.png", fig_md_haff),
    ("md2_energy.png", fig_md_energy),
    ("md3_fields.png", fig_md_fields),
    ("md4_contact.png", fig_md_contact),
    ("cmp1_profiles.png", fig_cmp_profiles),
    ("cmp2_time.png", fig_cmp_time),
    ("cmp3_metrics.png", fig_cmp_metrics),
    ("cmp4_modes.png", fig_cmp_modes),
]


# ------------------------------------------------------------------ page pieces

def header_rows(res, s, cfg):
    h = get(s, "hydro") or {}
    ref = get(cfg, "case", "reference") or get(cfg, "reference") or res["attrs"].get("case.reference")
    desc = get(cfg, "case", "description") or get(cfg, "description") or res["attrs"].get("case.description")
    rows = [
        ("case", fmt(s.get("case") or res["attrs"].get("case"))),
        ("reference", fmt(ref)),
        ("description", fmt(desc)) if desc else None,
        ("status", Markup(f'<span class="status {escape(str(s.get("status")))}">{fmt(s.get("status"))}</span>')
         if s.get("status") else fmt(None)),
        ("hydro status", fmt(h.get("status"))),
        ("stop reason", fmt(h.get("stop_reason"))),
        ("final time", fmt(num(h.get("t_final")))) if num(h.get("t_final")) is not None else None,
        ("wall time (hydro)", Markup(f"{fmt(num(h.get('wall_seconds')), 3)} s") if num(h.get("wall_seconds")) is not None else fmt(None)),
        ("cells", fmt(h.get("cells"))),
        ("steps", fmt(h.get("steps"))),
        ("cell-steps / s", fmt(num(h.get("cell_steps_per_second")), 3)),
    ]
    md = get(s, "md")
    md_attrs = (res.get("md") or {}).get("attrs") or {}
    if isinstance(md, dict) or md_attrs:
        rows += md_header_rows(md if isinstance(md, dict) else {}, md_attrs, get(cfg, "md") or {})
    w = num(get(s, "compare", "wall_seconds"))
    if w is not None:
        rows.append(("wall time (compare)", Markup(f"{fmt(w, 3)} s")))
    rows.append(("granvv version", fmt(s.get("granvv_version") or res["attrs"].get("granvv_version"))))
    return [r for r in rows if r]


def md_header_rows(md, attrs, cfg_md):
    """Header rows of the particle engine: status, and one line with the scene and its cost
    (summary.json first, then the /md attributes, then the configuration, e.g. after a failure)."""
    def v(key):
        for src in (md, attrs, cfg_md):
            x = num(src.get(key)) if isinstance(src, dict) else None
            if x is not None and not (src is cfg_md and key in ("particles", "restitution") and x == 0):
                return x   # (in the configuration, 0 disks or r = 0 means "derive from K, q")
        return None

    st = md.get("status")
    status = Markup(f'<span class="status {escape(str(st))}">{fmt(st)}</span>') if st else fmt(None)
    if md.get("error"):
        status += Markup(" — ") + escape(str(md["error"]))
    N, Lx, Ly = v("particles"), v("box_length"), v("box_width")
    r, rm = v("restitution"), v("restitution_measured")
    parts = []
    if N is not None:
        parts.append(f"{fmt(int(N))} disks")
    if Lx is not None and Ly is not None:
        parts.append(f"L<sub>x</sub> × L<sub>y</sub> = {fmt(Lx)} × {fmt(Ly)} σ")
    if v("area_fraction") is not None:
        parts.append(f"φ = {fmt(v('area_fraction'))}")
    if r is not None:
        parts.append(f"r = {fmt(r)} (measured {fmt(rm, 6)})" if rm is not None else f"r = {fmt(r)}")
    ens = md.get("ensemble") if md.get("ensemble") is not None else cfg_md.get("ensemble")
    seed = md.get("seed") if md.get("seed") is not None else cfg_md.get("seed")
    if ens is not None:
        e = int(num(ens)) if num(ens) is not None else None
        s0 = int(num(seed)) if num(seed) is not None else None
        seeds = ("" if s0 is None else f" (seed {s0})" if e == 1 else
                 f" (seeds {s0}–{s0 + e - 1})" if e else "")
        parts.append(f"ensemble of {fmt(ens)}{seeds}")
    if v("t_end") is not None:
        parts.append(f"to t = {fmt(v('t_end'))} σ(m/T<sub>0</sub>)<sup>1/2</sup>")
    if v("wall_seconds") is not None:
        parts.append(f"{fmt(v('wall_seconds'), 3)} s wall")
    if v("atom_steps_per_second") is not None:
        parts.append(f"{fmt(v('atom_steps_per_second'), 3)} atom-steps/s")
    return [("MD status", status),
            ("particle engine (MD, LAMMPS)", Markup(", ".join(parts)) if parts else fmt(None))]


def flatten(d, prefix=""):
    out = []
    for k, v in d.items():
        key = f"{prefix}{k}"
        if isinstance(v, dict):
            out += flatten(v, key + ".")
        elif isinstance(v, list):
            if not v:
                out.append((key, Markup("none")))
            elif all(not isinstance(x, (dict, list)) for x in v) and len(v) <= 12:
                out.append((key, Markup(", ".join(str(fmt(x)) for x in v))))
            else:
                out.append((key, Markup(f"[{len(v)} entries]")))
        else:
            out.append((key, fmt(v)))
    return out


def engine_tables(s):
    tables = []
    for eng in ("hydro", "md", "compare"):
        block = s.get(eng)
        if isinstance(block, dict) and block:
            tables.append({"name": eng, "rows": flatten({k: v for k, v in block.items() if k != "snapshots"})})
    return tables


def snapshot_table(s):
    snaps = get(s, "hydro", "snapshots")
    if not isinstance(snaps, list) or not snaps:
        return None
    order = ["t", "n_max", "T_min", "energy", "energy_thermal", "energy_kinetic", "energy_kinetic_y",
             "collapse_error"]
    seen = []
    for rec in snaps:
        for k in (rec or {}):
            if k not in seen:
                seen.append(k)
    cols = [k for k in order if k in seen] + [k for k in seen if k not in order]
    return {"cols": cols, "rows": [[fmt(num(get(r, c)) if num(get(r, c)) is not None else get(r, c)) for c in cols]
                                   for r in snaps]}


# ------------------------------------------------------------------------- sweeps
# DIR/sweep.json (app/sweep_command.cpp): one run per value of one key, each in its own sub-folder,
# and the cooling analysis over the restitution coefficient r (compare/cooling_sweep.hpp). Times in
# MD units sigma sqrt(m/T0); cooling rates zeta = 2/t0 in sqrt(T0/m)/sigma.

SWEEP_TEMPLATE = "sweep_template.html"
SWEEP_T_UNIT = r"[$\sigma\sqrt{m/T_0}$]"
SWEEP_Z_UNIT = r"[$\sqrt{T_0/m}/\sigma$]"


def load_sweep(path):
    try:
        with open(path) as fh:
            sw = json.load(fh)
    except (OSError, ValueError) as e:
        raise ReportError(f"cannot read {path}: {e}")
    if not isinstance(sw, dict) or not isinstance(sw.get("points"), list):
        raise ReportError(f"{path} is not a granvv sweep (no points list)")
    return sw


def sweep_points(ctx):
    """One record per point: value, dir, status, md block, cooling row (or None), report link."""
    rows = {}
    cool = get(ctx.sw, "cooling", "points") or []
    for c in cool:
        i = c.get("point") if isinstance(c, dict) else None
        if isinstance(i, int):
            rows[i] = c
    out = []
    for i, p in enumerate(ctx.sw["points"]):
        p = p if isinstance(p, dict) else {}
        d = p.get("dir")
        link = None
        if isinstance(d, str) and d and (ctx.outdir / d / "report.html").is_file():
            link = urllib.parse.quote(f"{d}/report.html", safe="/=,.-_")
        out.append({"i": i, "value": num(p.get("value")), "dir": d, "status": p.get("status"),
                    "exit_code": p.get("exit_code"), "md": p.get("md") if isinstance(p.get("md"), dict) else {},
                    "cool": rows.get(i), "link": link, "hydro_wall": num(p.get("hydro_wall_seconds"))})
    return out


def sweep_cooling(ctx):
    """Arrays over the points with a cooling row, sorted by r; Skip if fewer than one."""
    pts = [p for p in sweep_points(ctx) if p["cool"]]
    if not pts:
        err = ctx.sw.get("cooling_error")
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


def theory_constant(y, r, power_of):
    """C with y = C / f(r) at every point (f = 1 - r^2 or 1 - r), or None when the points disagree
    (the sweep also changed something else, e.g. the area fraction)."""
    c = y * power_of(r)
    c = c[np.isfinite(c)]
    if c.size == 0:
        return None
    m = float(np.median(c))
    return m if np.all(np.abs(c / m - 1) < 1e-3) else None


def sweep_r_axis(d):
    """(x values, label, smooth) — r when it varies, else the swept value."""
    r = d["restitution"]
    if np.isfinite(r).sum() >= 2 and np.nanmax(r) > np.nanmin(r):
        return r, "restitution coefficient $r$", True
    return d["value"], "swept value", False


def fig_sweep_t0(ctx):
    """s1: measured Haff time against r with kinetic theory (chi, dilute) and the paper's small-q t0."""
    d = sweep_cooling(ctx)
    x, xlabel, smooth = sweep_r_axis(d)
    if not smooth:
        xlabel = ctx.sw.get("key") or xlabel
    r = d["restitution"]
    fig, ax = plt.subplots(figsize=(7.6, 5.0), layout="constrained")
    ax.errorbar(x, d["t0"], yerr=d["t0_error"], fmt="o", color="C3", ms=6, capsize=3, lw=1.2, zorder=5,
                label=r"measured $t_0$ ± standard error (fit of $T(t)$)")
    chi = d["haff_t0_theory_dilute"] / d["haff_t0_theory"]
    curves = [("haff_t0_theory", lambda rr: 1 - rr ** 2, "k", "-", r"kinetic theory, Enskog $\chi(\phi)$: $\propto 1/(1-r^2)$"),
              ("haff_t0_theory_dilute", lambda rr: 1 - rr ** 2, "C0", "--", r"kinetic theory, dilute $\chi = 1$"),
              ("haff_t0_paper", lambda rr: 1 - rr, "C2", "-.", r"paper's small-$q$ hydro $K/4q$: $\propto 1/(1-r)$")]
    rr = None
    if smooth:
        lo, hi = float(np.nanmin(r)), float(np.nanmax(r))
        rr = np.linspace(max(0.0, lo - 0.05), min(0.998, hi + 0.5 * (1 - hi)), 300)
    for key, f, c, ls, lab in curves:
        y = d[key]
        C = theory_constant(y, r, f) if smooth else None
        if C is not None:
            ax.plot(rr, C / f(rr), color=c, ls=ls, lw=1.2, label=lab)
        elif np.isfinite(y).any():
            ax.plot(x, y, color=c, ls=ls, lw=1.0, marker="x", ms=6, label=lab.split(":")[0] + " (per point)")
    # the paper's rate with chi(phi) put in: t0_paper / chi
    Cp = theory_constant(d["haff_t0_paper"] / chi, r, lambda q: 1 - q) if smooth else None
    if Cp is not None:
        ax.plot(rr, Cp / (1 - rr), color="C2", ls=":", lw=1.2, label=r"paper's small-$q$ hydro with $\chi(\phi)$")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(r"Haff time $t_0$  " + SWEEP_T_UNIT)
    ax.set_title(r"Haff time $t_0$ against the restitution coefficient")
    ax.legend(loc="upper left", fontsize=8)
    name = save(fig, ctx.figdir, "s1_t0.png")
    measured = []
    for p in d["points"]:
        c = p["cool"]
        measured.append((f"r = {fmt(num(c.get('restitution')))}: t<sub>0</sub> measured, Enskog theory, dilute",
                         Markup(f"{fmt(num(c.get('t0')))} ± {fmt(num(c.get('t0_error')), 2)}, "
                                f"{fmt(num(p['md'].get('haff_t0_theory')))}, {fmt(num(p['md'].get('haff_t0_theory_dilute')))}"),
                         None))
    phi = d["area_fraction"]
    return {
        "id": "sweep_t0", "title": "Haff time against r", "img": name,
        "paper": ("Kinetic theory of smooth inelastic disks: ζ = √π (1 − r<sup>2</sup>) χ(φ) n σ (T<sub>0</sub>/m)<sup>1/2</sup>, "
                  "t<sub>0</sub> = 2/ζ, so t<sub>0</sub> ∝ 1/(1 − r<sup>2</sup>); the Enskog factor χ(φ) = (1 − 7φ/16)/(1 − φ)<sup>2</sup> "
                  "shortens it at finite density"
                  + (f" (φ = {fmt(float(np.nanmedian(phi)))}: χ = {fmt(float(np.nanmedian(chi)), 4)})" if np.isfinite(phi).any() and np.isfinite(chi).any() else "")
                  + ". The paper's hydro keeps the small-q form 8q/K, i.e. 1 − r<sup>2</sup> ≈ 4q = 2(1 − r) and χ = 1: "
                  "t<sub>0</sub> = K/4q ∝ 1/(1 − r), too short by the factor (1 + r)/2 away from r = 1."),
        "measured": measured,
        "note": Markup("The theory curves are each point's own theory value carried along r by its r-dependence "
                       "(they coincide when the sweep changes nothing but r)." if smooth else
                       "The sweep does not vary r: the theory is drawn per point."),
    }


def fig_sweep_zeta(ctx):
    """s2: cooling rate against 1 - r^2 (log-log) with the fitted power law and kinetic theory."""
    d = sweep_cooling(ctx)
    r = d["restitution"]
    _x, _lab, smooth = sweep_r_axis(d)
    if not smooth:
        raise Skip("the sweep does not vary the restitution coefficient: no power of (1 − r²) to fit")
    u = 1 - r ** 2
    fit = get(ctx.sw, "cooling", "power_of_one_minus_r2")
    rmin = num(get(fit, "r_min")) if isinstance(fit, dict) else None
    used = r >= rmin - 1e-12 if rmin is not None else np.ones_like(r, dtype=bool)
    fig, ax = plt.subplots(figsize=(7.6, 5.0), layout="constrained")
    ax.errorbar(u[used], d["zeta"][used], yerr=d["zeta_error"][used], fmt="o", color="C3", ms=6, capsize=3,
                zorder=5, label=r"measured $\zeta = 2/t_0$" + (f" (fitted, $r \\geq {rmin:g}$)" if rmin is not None else ""))
    if (~used).any():
        ax.errorbar(u[~used], d["zeta"][~used], yerr=d["zeta_error"][~used], fmt="o", mfc="white", color="C3",
                    ms=6, capsize=3, zorder=5, label=r"measured, outside the fit range")
    uu = np.geomspace(float(np.nanmin(u)) / 1.5, min(1.0, float(np.nanmax(u)) * 1.15), 200)
    rr = np.sqrt(1 - uu)
    Ce = theory_constant(d["zeta_enskog"], r, lambda q: 1 / (1 - q ** 2))
    Cd = theory_constant(d["zeta_dilute"], r, lambda q: 1 / (1 - q ** 2))
    Cp = theory_constant(d["zeta_paper_enskog"], r, lambda q: 1 / (1 - q))
    if Ce is not None:
        ax.plot(uu, Ce * uu, color="k", lw=1.2, label=r"kinetic theory, Enskog $\chi(\phi)$: $\propto (1-r^2)^1$")
    if Cd is not None:
        ax.plot(uu, Cd * uu, color="C0", lw=1.1, ls="--", label=r"kinetic theory, dilute")
    if Cp is not None:
        ax.plot(uu, Cp * (1 - rr), color="C2", lw=1.2, ls=":", label=r"paper's small-$q$ $8q/K$ with $\chi(\phi)$: $\propto 1 - r$")
    p, pe = (num(get(fit, "power")), num(get(fit, "power_error"))) if isinstance(fit, dict) else (None, None)
    A = num(get(fit, "prefactor")) if isinstance(fit, dict) else None
    if p is not None and A is not None:
        uf = u[used]
        inside = np.geomspace(float(np.nanmin(uf)), float(np.nanmax(uf)), 100)
        ax.plot(inside, A * inside ** p, color="C3", lw=2.2, alpha=0.7,
                label=rf"fit $\zeta = C(1-r^2)^p$: $p = {p:.4g} \pm {tex_num(pe, 2)}$")
        ax.plot(uu, A * uu ** p, color="C3", lw=0.8, ls="--", alpha=0.6)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(r"$1 - r^2$")
    ax.set_ylabel(r"cooling rate $\zeta = 2/t_0$  " + SWEEP_Z_UNIT)
    ax.set_title(r"Cooling rate against $1 - r^2$")
    ax.legend(loc="upper left", fontsize=8)
    # top axis: r itself
    top = ax.secondary_xaxis("top", functions=(lambda v: np.sqrt(np.clip(1 - v, 0, 1)),
                                               lambda v: 1 - np.asarray(v) ** 2))
    top.set_xlabel("$r$", fontsize=9)
    top.xaxis.set_major_locator(matplotlib.ticker.FixedLocator([0.0, 0.3, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.98, 0.99,
                                                                0.995, 0.998, 0.999]))
    top.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    top.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
    plain_log_ticks(ax.xaxis, *ax.get_xlim())
    plain_log_ticks(ax.yaxis, *ax.get_ylim())
    name = save(fig, ctx.figdir, "s2_zeta.png")
    measured = [
        ("fitted power p of (1 − r<sup>2</sup>)", Markup(f"{fmt(p, 4)} ± {fmt(pe, 2)}") if p is not None else fmt(None),
         verdict(abs(p - 1) <= 3 * pe, "p = 1 within 3σ", "p ≠ 1 beyond 3σ") if p is not None and pe else None),
        ("… (p − 1)/δp (computed here)", fmt((p - 1) / pe, 3) if p is not None and pe else fmt(None), None),
        ("… prefactor C, χ<sup>2</sup> per degree of freedom, points, r ≥",
         Markup(f"{fmt(A, 4)}, {fmt(num(get(fit, 'chi2_per_dof')), 3)}, {fmt(get(fit, 'points'))}, {fmt(rmin)}")
         if isinstance(fit, dict) else fmt(None), None),
        ("kinetic theory", Markup("p = 1"), None),
    ]
    return {
        "id": "sweep_zeta", "title": "Cooling rate against 1 − r²", "img": name,
        "paper": ("Kinetic theory predicts ζ ∝ (1 − r<sup>2</sup>)<sup>1</sup> at fixed density and T<sub>0</sub>; "
                  "the paper's hydro uses 8q/K ∝ 1 − r, which agrees with it only as r → 1."),
        "measured": measured,
        "note": Markup("The fit (thick line, dashed outside its range) is the program's own (sweep.json)."
                       if p is not None else "No power fit: fewer than two points in the fit range."),
    }


def fig_sweep_deviation(ctx):
    """s3: relative deviation of kinetic theory (chi) and of the paper's small-q rate from the measured rate."""
    d = sweep_cooling(ctx)
    x, xlabel, smooth = sweep_r_axis(d)
    if not smooth:
        xlabel = ctx.sw.get("key") or xlabel
    sig = num(get(ctx.sw, "cooling", "sigmas")) or 3.0
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = d["zeta_error"] / d["zeta"]
    fig, ax = plt.subplots(figsize=(7.6, 4.8), layout="constrained")
    o = np.argsort(x)
    ax.fill_between(x[o], -100 * sig * rel[o], 100 * sig * rel[o], color="0.5", alpha=0.18, lw=0,
                    label=rf"$\pm{sig:g}\sigma$ of the measured rate")
    ax.axhline(0, color="0.4", lw=0.7)
    for key, c, mk, lab in (("deviation_enskog", "k", "o", r"kinetic theory, Enskog $\chi(\phi)$: $\zeta^{\chi}/\zeta - 1$"),
                            ("paper_deviation", "C2", "s", r"paper's small-$q$ $8q/K$ with $\chi$: $\zeta^{\rm paper}/\zeta - 1$")):
        y = d[key]
        if not np.isfinite(y).any():
            continue
        ax.errorbar(x[o], 100 * y[o], yerr=100 * (1 + y[o]) * rel[o], fmt=mk + "-", color=c, ms=5.5, capsize=3,
                    lw=1.1, label=lab)
    dep = num(get(ctx.sw, "cooling", "paper_departs_at_r"))
    if dep is not None and smooth:
        ax.axvline(dep, color="C2", lw=1.0, ls="--")
        ax.text(dep, 0.97, rf"  departs for $r \leq {dep:g}$  ", transform=ax.get_xaxis_transform(), color="C2",
                ha="right" if dep >= float(np.nanmax(x)) - 1e-9 else "left", va="top", fontsize=8)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("relative deviation from the measured rate  [%]")
    ax.set_title("Theory against the measured cooling rate")
    ax.legend(loc="best", fontsize=8)
    name = save(fig, ctx.figdir, "s3_deviation.png")
    measured = []
    for p in d["points"]:
        c = p["cool"]
        measured.append((f"r = {fmt(num(c.get('restitution')))}: Enskog theory, paper's small-q (with χ) — "
                         "relative deviation (in σ)",
                         Markup(f"{pct(num(c.get('deviation_enskog')))} ({fmt(num(c.get('deviation_enskog_sigmas')), 3)}σ), "
                                f"{pct(num(c.get('paper_deviation')))} ({fmt(num(c.get('paper_deviation_sigmas')), 3)}σ)"),
                         None))
    return {
        "id": "sweep_deviation", "title": "Deviation of theory from the measured rate", "img": name,
        "paper": ("The paper's small-q cooling 8q/K (with χ(φ) put in) overestimates the rate of kinetic theory by "
                  "2/(1 + r): 5 % at r = 0.9, 18 % at r = 0.7, 33 % at r = 0.5. Where it leaves the grey band "
                  "(the measurement's own error) the particles can tell the difference."),
        "measured": measured,
        "note": Markup("Error bars: the measured rate's standard error carried into the ratio. Both deviations are "
                       "theory/measured − 1, as written by the program (sweep.json)."),
    }


def fig_sweep_cost(ctx):
    """s4: cost per point: wall seconds of MD and hydro, atom-steps and their rate."""
    pts = sweep_points(ctx)
    x = np.array([p["value"] if p["value"] is not None else np.nan for p in pts])
    mdw = np.array([num(p["md"].get("wall_seconds")) or np.nan for p in pts])
    hw = np.array([p["hydro_wall"] if p["hydro_wall"] is not None else np.nan for p in pts])
    ast = np.array([num(p["md"].get("atom_steps")) or np.nan for p in pts])
    asr = np.array([num(p["md"].get("atom_steps_per_second")) or np.nan for p in pts])
    if not (np.isfinite(mdw).any() or np.isfinite(hw).any()):
        raise Skip("no point recorded a wall time")
    key = ctx.sw.get("key") or "swept value"
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
    if np.isfinite(mdw).any():
        ax.plot(x, positive(mdw), color="C3", marker="o", lw=1.2, label="MD (all members)")
    if np.isfinite(hw).any():
        ax.plot(x, positive(hw), color="C0", marker="s", lw=1.2, label="hydro")
    ax.set_yscale("log")
    ax.set_xlabel(key)
    ax.set_ylabel("wall time  [s]")
    ax.set_title("(a) wall time per point")
    ax.legend(loc="best", fontsize=8)
    if np.isfinite(ast).any():
        f1, suf1 = power_scale(ast)
        ax2.plot(x, ast * f1, color="C3", marker="o", lw=1.2, label="atom-steps")
        ax2.set_ylabel("atom-steps (all members)" + suf1)
        ax2.set_ylim(0, float(np.nanmax(ast)) * f1 * 1.15)
    ax2.set_xlabel(key)
    ax2.set_title("(b) particle work per point")
    if np.isfinite(asr).any():
        tw = ax2.twinx()
        f2, suf2 = power_scale(asr)
        tw.plot(x, asr * f2, color="C1", marker="^", lw=1.0, ls="--", label="atom-steps / s")
        tw.set_ylabel("atom-steps / s" + suf2, color="C1")
        tw.set_ylim(0, float(np.nanmax(asr)) * f2 * 1.15)
        tw.grid(False)
        h1, l1 = ax2.get_legend_handles_labels()
        h2, l2 = tw.get_legend_handles_labels()
        ax2.legend(h1 + h2, l1 + l2, loc="lower left", fontsize=8)
    name = save(fig, ctx.figdir, "s4_cost.png")
    total = np.nansum(mdw) + np.nansum(hw)
    measured = [
        ("sweep wall time (sweep.json), sum over points of MD + hydro",
         Markup(f"{fmt(num(ctx.sw.get('wall_seconds')), 3)} s, {fmt(total, 3)} s"), None),
        ("atom-steps / s: lowest, highest", Markup(f"{fmt(num(np.nanmin(asr)) if np.isfinite(asr).any() else None, 3)}, "
                                                   f"{fmt(num(np.nanmax(asr)) if np.isfinite(asr).any() else None, 3)}"), None),
    ]
    return {
        "id": "sweep_cost", "title": "Cost per point", "img": name,
        "paper": ("Each point runs to the same cooling depth when md.time_unit = \"haff\" (t<sub>end</sub> in units "
                  "of the kinetic-theory t<sub>0</sub> ∝ 1/(1 − r<sup>2</sup>)), so the particle work grows as r → 1 "
                  "while the rate per atom-step stays that of LAMMPS."),
        "measured": measured,
    }


SWEEP_FIGURES = [
    ("s1_t0.png", fig_sweep_t0),
    ("s2_zeta.png", fig_sweep_zeta),
    ("s3_deviation.png", fig_sweep_deviation),
    ("s4_cost.png", fig_sweep_cost),
]


def sweep_verdicts(sw):
    """Plain sentences: the power fit, where the paper's small-q rate departs, kinetic theory's misses."""
    c = sw.get("cooling") if isinstance(sw.get("cooling"), dict) else None
    if c is None:
        return [Markup("No cooling analysis: no point measured a Haff time with an error"
                       + (f" ({escape(sw['cooling_error'])})" if sw.get("cooling_error") else "") + ".")]
    sig = num(c.get("sigmas")) or 3.0
    out = []
    fit = c.get("power_of_one_minus_r2")
    if isinstance(fit, dict) and num(fit.get("power")) is not None:
        p, pe = num(fit.get("power")), num(fit.get("power_error"))
        z = (p - 1) / pe if pe else None
        out.append(Markup(f"The measured cooling rate scales as (1 − r<sup>2</sup>)<sup>p</sup> with p = {fmt(p, 4)} ± "
                          f"{fmt(pe, 2)} over r ≥ {fmt(num(fit.get('r_min')))} ({fmt(fit.get('points'))} points"
                          + (f"; {fmt(abs(z), 2)}σ from kinetic theory's p = 1" if z is not None else "") + ")."))
    else:
        out.append(Markup("No power fit: fewer than two points in its range of r."))
    rs = [num(q.get("restitution")) for q in c.get("points") or [] if isinstance(q, dict)]
    rs = [v for v in rs if v is not None]
    dep = num(c.get("paper_departs_at_r"))
    if dep is None:
        out.append(Markup(f"The paper's small-q rate (8q/K, with χ(φ)) departs from the measured one by more than "
                          f"{fmt(sig)}σ nowhere in the sweep."))
    else:
        everywhere = rs and dep >= max(rs) - 1e-12 and all(
            abs(num(q.get("paper_deviation_sigmas")) or 0) > sig for q in c.get("points") or [])
        out.append(Markup(f"The paper's small-q rate (8q/K, with χ(φ)) departs from the measured one by more than "
                          f"{fmt(sig)}σ for r ≤ {fmt(dep)}" + (" — at every r of the sweep." if everywhere else ".")))
    miss = [q for q in c.get("points") or [] if isinstance(q, dict)
            and num(q.get("deviation_enskog_sigmas")) is not None and abs(num(q["deviation_enskog_sigmas"])) > sig]
    if miss:
        out.append(Markup(f"Kinetic theory with χ(φ) itself misses the measured t<sub>0</sub> by more than {fmt(sig)}σ at r = "
                          + ", ".join(str(fmt(num(q.get("restitution")))) for q in miss)
                          + " (" + ", ".join(f"{pct(num(q.get('deviation_enskog')))}" for q in miss)
                          + "): there the statistical error understates the systematic one, and a departure of "
                          "the small-q rate means something only where it is larger than kinetic theory's own miss."))
    elif rs:
        out.append(Markup(f"Kinetic theory with χ(φ) agrees with every measured t<sub>0</sub> within {fmt(sig)}σ."))
    return out


def sweep_tables(ctx):
    pts = sweep_points(ctx)
    rows = []
    for p in pts:
        md, c = p["md"], p["cool"] or {}
        t0, t0e = num(md.get("haff_t0_measured")), num(md.get("haff_t0_measured_error"))
        th = num(md.get("haff_t0_theory"))
        dev = num(c.get("deviation_enskog")) if c else (t0 / th - 1 if t0 is not None and th else None)
        sg = num(c.get("deviation_enskog_sigmas")) if c else ((t0 - th) / t0e if t0 is not None and th and t0e else None)
        st = p["status"]
        rows.append({
            "cells": [fmt(p["value"]),
                      Markup(f'<span class="status {escape(str(st))}">{fmt(st)}</span>') if st else
                      Markup(f"— (exit {fmt(p['exit_code'])})"),
                      fmt(num(md.get("restitution"))), fmt(num(md.get("restitution_measured")), 6),
                      Markup(f"{fmt(t0)} ± {fmt(t0e, 2)}") if t0 is not None else fmt(None),
                      fmt(th), fmt(num(md.get("haff_t0_theory_dilute"))), fmt(num(md.get("haff_t0_paper"))),
                      pct(dev), fmt(sg, 3),
                      Markup(f"{fmt(num(md.get('wall_seconds')), 3)} s") if num(md.get("wall_seconds")) is not None else fmt(None)],
            "link": p["link"], "dir": p["dir"],
            "bad": sg is not None and abs(sg) > (num(get(ctx.sw, "cooling", "sigmas")) or 3.0)})
    fit = get(ctx.sw, "cooling", "power_of_one_minus_r2")
    fit_rows = None
    if isinstance(fit, dict):
        p, pe = num(fit.get("power")), num(fit.get("power_error"))
        fit_rows = [("power p of (1 − r<sup>2</sup>)", Markup(f"{fmt(p, 4)} ± {fmt(pe, 2)}")),
                    ("(p − 1)/δp (computed here)", fmt((p - 1) / pe if p is not None and pe else None, 3)),
                    ("prefactor C (ζ = C (1 − r<sup>2</sup>)<sup>p</sup>, in (T<sub>0</sub>/m)<sup>1/2</sup>/σ)", fmt(num(fit.get("prefactor")), 4)),
                    ("χ<sup>2</sup> per degree of freedom", fmt(num(fit.get("chi2_per_dof")), 3)),
                    ("points in the fit, r ≥", Markup(f"{fmt(fit.get('points'))}, {fmt(num(fit.get('r_min')))}"))]
    sw = ctx.sw
    run = [
        ("case", fmt(sw.get("case"))),
        ("swept key", Markup(f"<code>{escape(str(sw.get('key')))}</code>")),
        ("values", Markup(", ".join(str(fmt(v)) for v in sw.get("values") or [])) if sw.get("values") else fmt(None)),
        ("fixed settings (every point)", Markup(", ".join(f"<code>{escape(str(v))}</code>" for v in sw.get("fixed_sets") or []))
         if sw.get("fixed_sets") else Markup("none (the case file as it is)")),
        ("status", Markup(f'<span class="status {escape(str(sw.get("status")))}">{fmt(sw.get("status"))}</span>')
         if sw.get("status") else fmt(None)),
        ("points finished", Markup(f"{len(pts)} of {len(sw.get('values') or [])}")),
        ("wall time", Markup(f"{fmt(num(sw.get('wall_seconds')), 3)} s") if num(sw.get("wall_seconds")) is not None else fmt(None)),
        ("granvv version", fmt(sw.get("granvv_version"))),
    ]
    seeds = {(p["md"].get("seed"), p["md"].get("ensemble")) for p in pts if p["md"]}
    if seeds:
        run.insert(4, ("seeds, ensemble members", Markup("; ".join(
            f"seed {fmt(s)}, ensemble of {fmt(e)}" for s, e in sorted(seeds, key=str)))))
    return rows, fit_rows, run


class SweepCtx:
    pass


def figure_folder(outdir):
    """DIR/figures, created, with DIR and it writable (else ReportError)."""
    figdir = outdir / "figures"
    try:
        figdir.mkdir(exist_ok=True)
    except OSError as e:
        raise ReportError(f"cannot create {figdir}: {e.strerror or e}")
    if not os.access(outdir, os.W_OK) or not os.access(figdir, os.W_OK):
        raise ReportError(f"{outdir} or {figdir} is not writable")
    return figdir


def draw_figures(specs, ctx, figdir, strict, list_skip=lambda fname: True):
    """Each (file name, function) of specs drawn: (figures, skipped, failed). A skipped or failed
    figure's stale PNG of an earlier run is removed; list_skip(fname) says whether a skip is worth
    listing on the page."""
    figures, skipped, failed = [], [], []
    for fname, fn in specs:
        try:
            figures.append(fn(ctx))
        except Skip as e:
            if list_skip(fname):
                skipped.append((fname, str(e)))
            if (figdir / fname).exists():
                (figdir / fname).unlink()   # a stale figure of an earlier run must not linger
        except Exception as e:  # noqa: BLE001 - one broken figure must not sink the page
            plt.close("all")
            failed.append((fname, f"{type(e).__name__}: {e}"))
            print(f"{PROG}: warning: {fname} failed: {type(e).__name__}: {e}", file=sys.stderr)
            if strict:
                traceback.print_exc()
            if (figdir / fname).exists():
                (figdir / fname).unlink()
    return figures, skipped, failed


def write_page(outdir, template, **fields):
    """Render template (beside this script) into DIR/report.html: a temporary file, renamed."""
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(Path(__file__).resolve().parent),
                             autoescape=jinja2.select_autoescape(["html"]), undefined=jinja2.StrictUndefined)
    html = env.get_template(template).render(**fields)
    fd, tmp = tempfile.mkstemp(prefix=".report.", suffix=".html.tmp", dir=outdir)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(html)
        os.chmod(tmp, 0o644)
        os.replace(tmp, outdir / "report.html")
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def build_sweep(outdir, strict=False):
    outdir = Path(outdir)
    sw = load_sweep(outdir / "sweep.json")
    figdir = figure_folder(outdir)
    ctx = SweepCtx()
    ctx.sw, ctx.outdir, ctx.figdir = sw, outdir, figdir
    figures, skipped, failed = draw_figures(SWEEP_FIGURES, ctx, figdir, strict)
    warn = []
    if sw.get("status") not in ("ok", None):
        warn.append(f"sweep status is '{sw.get('status')}': "
                    + ("it is still running or was stopped; the page shows the points finished so far."
                       if sw.get("status") == "running" else "at least one point failed (see its exit code)."))
    rows, fit_rows, run = sweep_tables(ctx)
    write_page(
        outdir, SWEEP_TEMPLATE,
        case=sw.get("case") or outdir.name, key=sw.get("key") or "", status=sw.get("status"),
        run=run, verdicts=sweep_verdicts(sw), points=rows, fit=fit_rows,
        figures=[{**f, "paper": Markup(f["paper"]), "note": f.get("note")} for f in figures],
        skipped=skipped, failed=failed, warnings=warn,
        raw=json.dumps({k: v for k, v in sw.items() if k != "points"}, indent=2),
        generated=datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z"),
        source=str(outdir / "sweep.json"),
    )
    return figures, skipped, failed


class Ctx:
    pass


def build(outdir, strict=False):
    outdir = Path(outdir)
    h5 = outdir / "results.h5"
    if not h5.exists() and (outdir / "sweep.json").is_file():
        return build_sweep(outdir, strict)
    if not h5.is_file():
        raise ReportError(f"{h5} not found" if not h5.exists() else f"{h5} is not a file")
    res = load_results(h5)
    warnings = []
    s = load_summary(outdir / "summary.json", warnings)
    cfg_text = res["attrs"].get("config_toml")
    cfg = {}
    if isinstance(cfg_text, str) and cfg_text.strip():
        try:
            import tomllib
            cfg = tomllib.loads(cfg_text)
        except Exception as e:  # noqa: BLE001 - any parse problem is only a warning here
            warnings.append(f"config_toml in results.h5 does not parse as TOML ({e}).")
    figdir = figure_folder(outdir)

    ctx = Ctx()
    ctx.res, ctx.s, ctx.cfg, ctx.figdir = res, s, cfg, figdir
    has_md = bool(res.get("md") or res.get("md_ts") or res.get("md_fields") or s.get("md"))
    has_cmp = bool(res.get("cmp") or s.get("compare"))
    # no particle run: no MD entries at all; no comparison: no side-by-side entries
    figures, skipped, failed = draw_figures(
        FIGURES, ctx, figdir, strict,
        list_skip=lambda f: not ((f.startswith("md") and not has_md) or (f.startswith("cmp") and not has_cmp)))

    if isinstance(cfg_text, str) and cfg_text.strip():
        config_block = cfg_text.rstrip()
    else:
        config_block = "\n".join(f"{k} = {v}" for k, v in sorted(res["attrs"].items())
                                 if k not in ("config_toml",)) or "(no configuration stored in results.h5)"

    write_page(
        outdir, TEMPLATE,
        case=s.get("case") or res["attrs"].get("case") or outdir.name,
        status=s.get("status"),
        header=header_rows(res, s, cfg),
        figures=[{**f, "paper": Markup(f["paper"]), "note": f.get("note")} for f in figures
                 if not str(f.get("id", "")).startswith("cmp_")],
        cmp_figures=[{**f, "paper": Markup(f["paper"]), "note": f.get("note")} for f in figures
                     if str(f.get("id", "")).startswith("cmp_")],
        compare=compare_section(ctx),
        skipped=skipped, failed=failed, warnings=warnings,
        engines=engine_tables(s), snapshots=snapshot_table(s),
        md_units=any(str(f.get("id", "")).startswith("md_") for f in figures),
        config=config_block, groups=res["groups"], paper=Markup(PAPER),
        generated=datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z"),
        source=str(h5),
    )
    return figures, skipped, failed


def main(argv=None):
    p = argparse.ArgumentParser(prog=PROG, description="Write DIR/report.html and DIR/figures/*.png "
                                "from DIR/results.h5 and DIR/summary.json.")
    p.add_argument("dir", help="output folder of a granvv run")
    p.add_argument("--strict", action="store_true", help="exit 2 if any figure fails (for CI)")
    args = p.parse_args(argv)
    try:
        figures, skipped, failed = build(args.dir, strict=args.strict)
    except ReportError as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        return 1
    out = Path(args.dir) / "report.html"
    print(f"{PROG}: wrote {out} ({len(figures)} figures, {len(skipped)} not applicable"
          + (f", {len(failed)} FAILED" if failed else "") + ")")
    return 2 if (failed and args.strict) else 0


if __name__ == "__main__":
    sys.exit(main())
