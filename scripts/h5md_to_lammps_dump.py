#!/usr/bin/python3
"""Write the frames of an H5MD file (granvv's particles.h5) as a LAMMPS text dump.

    scripts/h5md_to_lammps_dump.py particles.h5 frames.dump --timestep 0.001

One frame per H5MD frame, as `dump custom ... id x y vx vy` writes it: ITEM: TIMESTEP (the
frame's time over --timestep, rounded; the times must be multiples of it), ITEM: NUMBER OF
ATOMS, ITEM: BOX BOUNDS pp pp pp (the box [-L/2, L/2) of granvv's frames, z from -0.5 to
0.5), ITEM: ATOMS id x y vx vy with every value in full precision (%.17g), so that the dump
holds the same numbers as the H5MD file. Used by the round-trip test of the recorded engine
(docs/recorded.md).
"""
import argparse
import sys

import h5py
import numpy as np


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("h5md")
    parser.add_argument("dump")
    parser.add_argument("--timestep", type=float, required=True,
                        help="time per dump step; every frame time must be a multiple of it")
    parser.add_argument("--group", default="all", help="the /particles group (default all)")
    args = parser.parse_args()
    with h5py.File(args.h5md, "r") as f:
        g = f["particles"][args.group]
        edges = np.asarray(g["box"]["edges"], dtype=float)
        ids = np.asarray(g["id"]) if "id" in g else None
        x = g["position"]["value"]
        v = g["velocity"]["value"]
        times = np.asarray(g["position"]["time"], dtype=float)
        with open(args.dump, "w") as out:
            for k, t in enumerate(times):
                step = int(round(t / args.timestep))
                if abs(step * args.timestep - t) > 1e-9 * max(1.0, abs(t)):
                    print(f"{args.h5md}: frame {k} at t = {t!r} is not a multiple of "
                          f"--timestep {args.timestep!r}", file=sys.stderr)
                    return 2
                pos, vel = np.asarray(x[k]), np.asarray(v[k])
                n = pos.shape[0]
                out.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n{n}\n")
                out.write("ITEM: BOX BOUNDS pp pp pp\n")
                out.write(f"{-0.5 * edges[0]!r} {0.5 * edges[0]!r}\n")
                out.write(f"{-0.5 * edges[1]!r} {0.5 * edges[1]!r}\n-0.5 0.5\n")
                out.write("ITEM: ATOMS id x y vx vy\n")
                atom_ids = ids if ids is not None else np.arange(1, n + 1)
                for i in range(n):
                    out.write(f"{int(atom_ids[i])} {pos[i, 0]:.17g} {pos[i, 1]:.17g} "
                              f"{vel[i, 0]:.17g} {vel[i, 1]:.17g}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
