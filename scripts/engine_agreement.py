#!/usr/bin/python3
"""Do two particle runs of one scene agree within their ensemble errors?

Reads /md/fields of two results.h5 (for example the same case with md.engine = "lammps" and
"event_driven", the same seeds) and, for every field the coarse-grainer writes, compares the
ensemble means bin by bin at the snapshot times both runs hold:

    z = (a - b) / sqrt(sa^2 + sb^2)

with sa, sb the ensemble standard errors of the two runs. Two independent estimates of one
mean give |z| < 3 in 99.7 % of the bins when the errors are right, so the table prints the
fraction of bins within 3, the largest |z| and where it is. The first snapshot (t = 0) is the
same sample for both engines and is left out (z = 0/0 there).

Usage: scripts/engine_agreement.py RUN_A RUN_B [--fields n,v_x,T,P_xx,P_yy] [--json OUT]
"""
import argparse
import json
import sys

import h5py
import numpy as np

Z_AGREE = 3.0  # |z| below this counts as agreeing (Gaussian 99.7 %)
# Relative difference of two runs' snapshot times taken as the same snapshot: each engine lands on a
# requested time within its own time step (a soft-contact engine's is ~1e-5 of the time here), so this
# is a step resolution, not the round-off tolerance of one time written twice (granvv_report SAME_TIME).
STEP_MATCH = 1e-5


def fields_of(path):
    with h5py.File(path, "r") as f:
        g = f["md/fields"]
        out = {"t": g["t"][()], "x": g["x"][()]}
        for name in g:
            if name + "_stderr" in g:
                out[name] = (g[name][()], g[name + "_stderr"][()])
        return out


def agreement(a, b, names):
    common = [t for t in a["t"] if np.any(np.isclose(b["t"], t, rtol=STEP_MATCH)) and t > 0]
    if not common:
        sys.exit("engine_agreement: the two runs share no snapshot time after t = 0")
    ia = [int(np.argmin(abs(a["t"] - t))) for t in common]
    ib = [int(np.argmin(abs(b["t"] - t))) for t in common]
    rows = []
    for name in names:
        if name not in a or name not in b:
            continue
        (ma, ea), (mb, eb) = a[name], b[name]
        ma, ea, mb, eb = ma[ia], ea[ia], mb[ib], eb[ib]
        if ma.shape != mb.shape:
            sys.exit(f"engine_agreement: {name} has shape {ma.shape} in one run and {mb.shape} in the other")
        z = (ma - mb) / np.sqrt(ea**2 + eb**2)
        ok = np.isfinite(z)
        if not ok.any():
            continue
        k = np.unravel_index(np.nanargmax(np.where(ok, abs(z), -1)), z.shape)
        rows.append({"field": name, "bins": int(ok.sum()),
                     "fraction_within_3": float(np.mean(abs(z[ok]) < Z_AGREE)),
                     "largest_abs_z": float(abs(z[k])), "at_t": float(common[k[0]]),
                     "at_x": float(a["x"][ia[k[0]], k[1]] if a["x"].ndim == 2 else a["x"][k[1]]),
                     "mean_z": float(np.mean(z[ok]))})
    return common, rows


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("run_a")
    p.add_argument("run_b")
    p.add_argument("--fields", default="n,v_x,T,P_xx,P_yy")
    p.add_argument("--json")
    args = p.parse_args()
    a, b = (fields_of(f"{d}/results.h5") for d in (args.run_a, args.run_b))
    common, rows = agreement(a, b, args.fields.split(","))
    print(f"{len(common)} common snapshot times after t = 0: {', '.join(f'{t:g}' for t in common)}")
    print(f"{'field':6} {'bins':>5} {'|z|<3':>7} {'max |z|':>8} {'at t':>8} {'at x':>8} {'mean z':>7}")
    for r in rows:
        print(f"{r['field']:6} {r['bins']:5d} {r['fraction_within_3']:7.3f} {r['largest_abs_z']:8.2f} "
              f"{r['at_t']:8.4g} {r['at_x']:8.3g} {r['mean_z']:7.2f}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"runs": [args.run_a, args.run_b], "times": common, "fields": rows}, f, indent=1)


if __name__ == "__main__":
    main()
