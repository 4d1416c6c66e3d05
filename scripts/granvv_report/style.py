"""Style of the report's figures: matplotlib settings, axis labels and units, colours, and the
drawing helpers shared by the figure modules (snapshot choice, periodic sorting, error bands,
legends, log ticks, the atomic PNG writer)."""
import math
import os
import tempfile

import matplotlib
import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np

plt.rcParams.update({
    "figure.dpi": 110, "savefig.dpi": 130, "font.size": 9.5, "axes.titlesize": 10,
    "axes.labelsize": 10, "legend.fontsize": 8.5, "legend.framealpha": 0.85,
    "axes.grid": True, "grid.alpha": 0.25, "grid.linewidth": 0.6,
    "lines.linewidth": 1.4, "axes.titleweight": "bold", "axes.titlelocation": "left",
    "mathtext.fontset": "dejavusans",
})

MAX_CURVES = 7               # snapshots per panel

# Axis labels of the hydro figures: the paper's scaled variables.
T_UNIT = r"$t$  [$L_x/\sqrt{T_0/m}$]"
X_UNIT = r"$x$  [$L_x$]"
N_UNIT = r"$n$  [$n_0$]"
V_UNIT = r"$v$  [$\sqrt{T_0/m}$]"
T_FIELD = r"$T$  [$T_0$]"

# Particle units (docs/physics.md §4): sigma = m = T0 = 1. Lengths in sigma, times in sigma sqrt(m/T0),
# velocities in sqrt(T0/m), energies (whole box) in T0, number density in 1/sigma^2.
MD_T_UNIT = r"$t$  [$\sigma\sqrt{m/T_0}$]"
MD_X_UNIT = r"$x$  [$\sigma$]"
MD_N_UNIT = r"$n$  [$\sigma^{-2}$]"
MD_V_UNIT = r"[$\sqrt{T_0/m}$]"
MD_E_UNIT = r"energy of the box  [$T_0$]"
MD_MAX_MEMBERS = 40          # ensemble members drawn individually (thin lines)

# Hydro and particles side by side (/compare), in the hydro's scaled units: x in Lx on [-1/2, 1/2),
# t in Lx/sqrt(T0/m) (MD time = t * Lx/sigma), n in n0, v in sqrt(T0/m), T in T0.
# How each compared field is drawn: title, axis label, colour; and its name in a label. Which fields a
# comparison holds, and their order, come from data.compared_fields.
CMP_FIELD_STYLE = {"n": ("density", r"$n$  [$n_0$]", "C0"),
                   "v_x": ("velocity $v_x$", r"$v_x$  [$\sqrt{T_0/m}$]", "C3"),
                   "v_y": ("transverse velocity $v_y$", r"$v_y$  [$\sqrt{T_0/m}$]", "C2"),
                   "T": ("temperature", r"$T$  [$T_0$]", "C1")}
CMP_FIELD_TEX = {"n": "$n$", "v_x": "$v_x$", "v_y": "$v_y$", "T": "$T$"}
CMP_HYDRO, CMP_MD, CMP_INERTIA = "C0", "C3", "0.15"
CMP_MAX_TIMES = 6            # columns of the profile figure

# Sweeps: times in sigma sqrt(m/T0), cooling rates zeta = 2/t0 in sqrt(T0/m)/sigma.
SWEEP_T_UNIT = r"[$\sigma\sqrt{m/T_0}$]"
SWEEP_Z_UNIT = r"[$\sqrt{T_0/m}/\sigma$]"


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
