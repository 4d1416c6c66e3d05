"""The particle frames of a run (H5MD, docs/outputs.md "particles.h5"), and the density profiles drawn
beside them: the reader shared by the report's strip figure and `granvv movie` (scripts/particle_movie.py).

Frames are read one at a time (a frame of 2.8·10⁶ disks is 45 MB). Positions are in σ, wrapped into
[−Lx/2, Lx/2) × [−Ly/2, Ly/2); the hydro's x is scaled by Lx, so a disk's scaled x is x_σ / Lx."""
from dataclasses import dataclass
from pathlib import Path

import h5py
import numpy as np

from .data import Skip, arr, cmp_box

# The member whose frames are drawn: particles.h5 of a one-member run, else member 1's file.
FRAME_FILES = ("particles.h5", "particles_m0.h5")


@dataclass
class Frames:
    path: Path
    times: np.ndarray      # MD time of each frame
    box: tuple             # (Lx, Ly) in σ
    count: int             # disks

    def positions(self, i):
        with h5py.File(self.path, "r") as f:
            return np.asarray(f["particles/all/position/value"][i], dtype=float)

    def velocities(self, i):
        with h5py.File(self.path, "r") as f:
            return np.asarray(f["particles/all/velocity/value"][i], dtype=float)

    def nearest(self, t_md):
        """Index of the frame nearest to t_md, or None when none is within half a frame spacing."""
        if self.times.size == 0:
            return None
        i = int(np.argmin(np.abs(self.times - t_md)))
        spacing = float(np.min(np.diff(self.times))) if self.times.size > 1 else 0.0
        return i if abs(self.times[i] - t_md) <= max(0.5 * spacing, 1e-9 * max(1.0, abs(t_md))) else None


def read_frames(outdir):
    """The frames of the run in outdir, or Skip saying why there are none."""
    outdir = Path(outdir)
    path = next((outdir / n for n in FRAME_FILES if (outdir / n).is_file()), None)
    if path is None:
        raise Skip("no particle frames (particles.h5 or particles_m0.h5): a particle run writes them "
                   "with md.snapshot_interval > 0, e.g. --set md.snapshot_interval=…")
    try:
        with h5py.File(path, "r") as f:
            pos = f.get("particles/all/position/value")
            t = f.get("particles/all/position/time")
            step = f.get("particles/all/position/step")
            edges = f.get("particles/all/box/edges")
            if pos is None or t is None or edges is None or pos.ndim != 3 or pos.shape[2] != 2:
                raise Skip(f"{path.name} has no [frames × N × 2] positions")
            # A frame counts once its step is written (a killed run may leave a partial last row).
            frames = min(pos.shape[0], t.shape[0], step.shape[0] if step is not None else t.shape[0])
            times = np.asarray(t[:frames], dtype=float)
            box = tuple(float(v) for v in np.asarray(edges[...], dtype=float).ravel()[:2])
            count = int(pos.shape[1])
    except OSError as e:
        raise Skip(f"{path.name} cannot be read ({e})") from e
    if frames == 0:
        raise Skip(f"{path.name} holds no particle frames: the run was made with md.snapshot_interval = 0 "
                   "(set it, e.g. --set md.snapshot_interval=…, to draw the particles)")
    if len(box) != 2 or not all(np.isfinite(box)) or min(box) <= 0:
        raise Skip(f"{path.name} has no valid box edges")
    return Frames(path, times, box, count)


def local_density(x, Lx, bins):
    """n/n0 of each disk's bin along x (bins of equal width over [−Lx/2, Lx/2)), and the bin centres
    (scaled by Lx) with the binned n/n0."""
    idx = np.clip(((x / Lx + 0.5) * bins).astype(int), 0, bins - 1)
    counts = np.bincount(idx, minlength=bins).astype(float)
    n = counts / (counts.mean() if counts.mean() > 0 else 1.0)
    centres = (np.arange(bins) + 0.5) / bins - 0.5
    return n[idx], centres, n


@dataclass
class Profiles:
    """The compared density profiles (scaled x, n in n0) at scaled times t; md_error may be None."""
    t: np.ndarray
    x: np.ndarray
    hydro: np.ndarray
    md: np.ndarray
    md_error: object
    box_length: float


def compared_density(run):
    """The hydro's and the particles' n at the compared times (/compare/fields/n), or None."""
    C = run.compare
    if C is None:
        return None
    t, x = arr(C, "t", 1), arr(C, "x", 1)
    g = (C.get("fields") or {}).get("n")
    L = cmp_box(run)
    if t is None or x is None or g is None or not L:
        return None
    hydro, md, err = arr(g, "hydro", 1), arr(g, "md", 1), arr(g, "md_error", 1)
    shape = (t.size, x.size)
    if hydro is None or md is None or hydro.shape != shape or md.shape != shape:
        return None
    return Profiles(t, x, hydro, md, err if err is not None and err.shape == shape else None, float(L))
