#!/usr/bin/python3
"""Build the granvv report of one output folder.

    /usr/bin/python3 scripts/report.py DIR [--strict]

Reads DIR/results.h5 (required, unless DIR holds a sweep or an atlas) and DIR/summary.json (optional), writes the
figures to DIR/figures/*.png and the page to DIR/report.html. A sweep folder (DIR/sweep.json from
`granvv sweep`, no results.h5) gets a sweep page instead, and an atlas folder (DIR/atlas.json of
`granvv atlas`) the page DIR/atlas.html. The work is done by the package
granvv_report beside this script (see its __init__ for the modules).

Exit status: 0 report written; 1 results.h5 missing or unreadable (one line on
stderr); 2 a figure failed and --strict was given (the report is still written).
Needs only Debian's python3-numpy, -matplotlib, -h5py, -jinja2.
"""
import argparse
import sys
from pathlib import Path

# The package lives beside this script, wherever the scripts folder is installed.
sys.path.insert(0, str(Path(__file__).resolve().parent))

from granvv_report import PROG  # noqa: E402
from granvv_report.data import ReportError, is_atlas_folder  # noqa: E402
from granvv_report.page import build  # noqa: E402


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
    out = Path(args.dir) / ("atlas.html" if is_atlas_folder(args.dir) else "report.html")
    print(f"{PROG}: wrote {out} ({len(figures)} figures, {len(skipped)} not applicable"
          + (f", {len(failed)} FAILED" if failed else "") + ")")
    return 2 if (failed and args.strict) else 0


if __name__ == "__main__":
    sys.exit(main())
