#!/usr/bin/env python3
"""The Sonine coefficient a2 of the velocity distribution in the particle frames of a run.

In d = 2, a2 = <c^4> / (2 <c^2>^2) - 1 for the peculiar velocity c (here the velocity less the
box mean; the homogeneous cooling state has no flow). Reads every particles_m*.h5 (H5MD) of an
output folder and prints, per frame time, the mean of a2 over the members and its standard
error, with the van Noije & Ernst first-Sonine value for the restitution given
(docs/physics.md, Haff's t0 at r = 0.9 and 0.98).

Usage: sonine_a2.py OUT_DIR --restitution R [--from T] [--to T]
"""
import argparse
import pathlib

import h5py
import numpy as np


def van_noije_ernst_a2(r):
    """2D first Sonine coefficient of the HCS (van Noije & Ernst 1998)."""
    return 16 * (1 - r) * (1 - 2 * r * r) / (57 - 25 * r + 30 * r * r * (1 - r))


def a2_of(v):
    c = v - v.mean(axis=0)
    c2 = (c * c).sum(axis=1)
    return (c2 * c2).mean() / (2 * c2.mean() ** 2) - 1


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out_dir", type=pathlib.Path)
    p.add_argument("--restitution", type=float, required=True)
    p.add_argument("--from", dest="t_from", type=float, default=0.0)
    p.add_argument("--to", dest="t_to", type=float, default=float("inf"))
    a = p.parse_args()
    members = sorted(a.out_dir.glob("particles_m*.h5"))
    members = [m for m in members if ".rank" not in m.name]
    if not members:
        raise SystemExit(f"no particles_m*.h5 in {a.out_dir}")
    per_member = []
    for m in members:
        with h5py.File(m, "r") as f:
            t = f["particles/all/velocity/time"][()]
            v = f["particles/all/velocity/value"]
            per_member.append((t, np.array([a2_of(v[k]) for k in range(len(t))])))
    t = per_member[0][0]
    values = np.array([x for _, x in per_member])
    mean, err = values.mean(axis=0), values.std(axis=0, ddof=1) / np.sqrt(len(members))
    theory = van_noije_ernst_a2(a.restitution)
    print(f"# {len(members)} members; van Noije & Ernst a2 = {theory:.5f}")
    print("| t | a2 | error |\n|---|---|---|")
    window = []
    for k in range(len(t)):
        print(f"| {t[k]:.1f} | {mean[k]:+.5f} | {err[k]:.5f} |")
        if a.t_from <= t[k] <= a.t_to:
            window.append(values[:, k])
    if window:
        w = np.array(window).mean(axis=0)  # per member, the mean over the window
        print(f"# mean over [{a.t_from}, {a.t_to}]: a2 = {w.mean():+.5f} ± "
              f"{w.std(ddof=1) / np.sqrt(len(w)):.5f} (theory {theory:+.5f})")


if __name__ == "__main__":
    main()
