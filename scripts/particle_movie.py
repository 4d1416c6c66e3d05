#!/usr/bin/python3
"""An animation of a particle run's frames: the box as a strip, the disks coloured by the local density,
above the particles' binned density of the frame and the hydro's and the particles' compared profiles
at the nearest compared time. `granvv movie DIR` runs this script.

Usage: /usr/bin/python3 scripts/particle_movie.py DIR [--out FILE.gif] [--fps F] [--max-frames M]

Exit codes: 0 written; 2 bad input (no run folder, no frames, an output it cannot write)."""
import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import granvv_report  # noqa: E402,F401 - sets the matplotlib backend and config folder
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.animation import FuncAnimation, PillowWriter  # noqa: E402

from granvv_report.data import ReportError, Run, Skip  # noqa: E402
from granvv_report.figures_particles import STRIP_BINS, STRIP_MAX_DISKS, disk_marker_size  # noqa: E402
from granvv_report.formatting import fmt  # noqa: E402
from granvv_report.frames import compared_density, local_density, read_frames  # noqa: E402
from granvv_report.style import CMP_HYDRO, CMP_MD, pick  # noqa: E402

PROG = "granvv movie"
WIDTH_IN = 7.6


def fail(message):
    print(f"{PROG}: error: {message}", file=sys.stderr)
    return 2


def make_movie(outdir, out, fps, max_frames):
    frames = read_frames(outdir)
    try:
        profiles = compared_density(Run(outdir))
    except ReportError:
        profiles = None  # frames without results.h5 (a run still going): the particles alone
    Lx, Ly = frames.box
    bins = profiles.x.size if profiles is not None else STRIP_BINS
    order = pick(list(range(frames.times.size)), max_frames)
    rng = np.random.default_rng(0)
    shown = np.arange(frames.count)
    if shown.size > STRIP_MAX_DISKS:
        shown = np.sort(rng.choice(shown, STRIP_MAX_DISKS, replace=False))

    fig = plt.figure(figsize=(WIDTH_IN, 4.2), layout="constrained")
    grid = fig.add_gridspec(2, 1, height_ratios=[1.0, 1.4])
    ax_s = fig.add_subplot(grid[0])
    ax_p = fig.add_subplot(grid[1], sharex=ax_s)
    pos = frames.positions(order[0])[shown]
    sc = ax_s.scatter(pos[:, 0] / Lx, pos[:, 1], c=np.ones(shown.size), s=disk_marker_size(Lx, WIDTH_IN * 0.85),
                      cmap="viridis", vmin=0.0, vmax=3.0, linewidths=0)
    fig.colorbar(sc, ax=ax_s, label=r"$n/n_0$", aspect=8, pad=0.01)
    ax_s.set_ylim(-Ly / 2, Ly / 2)
    ax_s.set_yticks([])
    ax_s.set_ylabel(f"{fmt(Ly, 3)} σ", fontsize=8)
    plt.setp(ax_s.get_xticklabels(), visible=False)
    centres = (np.arange(bins) + 0.5) / bins - 0.5
    (frame_line,) = ax_p.step(centres, np.ones(bins), where="mid", color="0.45", lw=1.0, label="this frame")
    hydro_line = md_line = None
    if profiles is not None:
        (hydro_line,) = ax_p.plot(profiles.x, profiles.hydro[0], color=CMP_HYDRO, lw=1.5, label="hydro (binned)")
        (md_line,) = ax_p.plot(profiles.x, profiles.md[0], "o", ms=3, color=CMP_MD, label="particles (ensemble mean)")
        top = float(np.nanmax([np.nanmax(profiles.hydro), np.nanmax(profiles.md)]))
    else:
        top = 2.0
    ax_p.set_xlim(-0.5, 0.5)
    ax_p.set_xlabel(r"$x$  [$L_x$]")
    ax_p.set_ylabel(r"$n$  [$n_0$]")
    ax_p.legend(loc="upper right", fontsize=7)
    title = fig.suptitle("", fontsize=9)
    peak = [top]

    def draw(k):
        p = frames.positions(k)
        colour, _, n_bins = local_density(np.nan_to_num(p[:, 0]), Lx, bins)
        sc.set_offsets(np.column_stack([p[shown, 0] / Lx, p[shown, 1]]))
        sc.set_array(colour[shown])
        frame_line.set_ydata(n_bins)
        text = r"$t_\mathrm{MD}$" + f" = {fmt(frames.times[k], 4)}"
        if profiles is not None:
            i = int(np.argmin(np.abs(profiles.t * profiles.box_length - frames.times[k])))
            hydro_line.set_ydata(profiles.hydro[i])
            md_line.set_ydata(profiles.md[i])
            text += "; profiles at the nearest compared time, " + r"$t_\mathrm{MD}$" + \
                f" = {fmt(profiles.t[i] * profiles.box_length, 4)}"
        peak[0] = max(peak[0], float(np.max(n_bins)))
        ax_p.set_ylim(0, 1.1 * peak[0])
        title.set_text(text)
        return sc, frame_line

    anim = FuncAnimation(fig, draw, frames=order, blit=False)
    anim.save(out, writer=PillowWriter(fps=fps))
    plt.close(fig)
    return len(order)


def main(argv):
    ap = argparse.ArgumentParser(prog=PROG, description=__doc__.splitlines()[0])
    ap.add_argument("dir", help="output folder of a particle run that wrote frames (md.snapshot_interval > 0)")
    ap.add_argument("--out", help="the animation (a .gif; default DIR/movie.gif)")
    ap.add_argument("--fps", type=float, default=8.0, help="frames per second (default 8)")
    ap.add_argument("--max-frames", type=int, default=200, help="at most this many frames, evenly spread (default 200)")
    args = ap.parse_args(argv)
    outdir = Path(args.dir)
    if not outdir.is_dir():
        return fail(f"{outdir} is not a folder; `granvv movie DIR` needs the output folder of a particle run")
    out = Path(args.out) if args.out else outdir / "movie.gif"
    if out.suffix.lower() != ".gif":
        return fail(f"--out {out}: the movie is written as a GIF (Pillow); give a name ending in .gif")
    if not 0 < args.fps <= 60:
        return fail(f"--fps {args.fps:g}: allowed is 0 < fps <= 60")
    if args.max_frames < 1:
        return fail(f"--max-frames {args.max_frames}: allowed is at least 1")
    try:
        n = make_movie(outdir, out, args.fps, args.max_frames)
    except Skip as e:
        return fail(f"{outdir}: {e}")
    except OSError as e:
        return fail(f"{out} could not be written ({e})")
    print(f"{PROG}: wrote {out} ({n} frames)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
