"""The sweep page's transport figure (figures_sweep.fig_sweep_transport) and its accessor
(data.sweep_transport) on a synthetic sweep.json: the coefficients the points measured, with every
closure's value, drawn against r; absent (skipped, no error) when no point has a transport block.
And through the real binary: `granvv sweep` copies a point's summary.json transport block into
sweep.json (a tiny md_haff sweep, its points' summaries given a block, then reused by the sweep
run again)."""
import json
import math
import subprocess
import unittest

import matplotlib
import numpy as np

matplotlib.use("Agg")

from report_fixtures import BINARY, TINY_MD, scratch  # noqa: E402
from granvv_report import data, figures_sweep, page  # noqa: E402
from granvv_report.data import Skip  # noqa: E402


def coefficient(measured, error, **closures):
    return {"measured": measured, "error": error, "closures": closures}


def point(r, transport=None):
    p = {"value": r, "dir": f"md.restitution={r}", "status": "ok", "exit_code": 0, "reused": False,
         "md": {"restitution": r, "restitution_measured": r}, "hydro_wall_seconds": 1.0, "compare": None}
    if transport is not None:
        p["transport"] = transport
    return p


# Three points given out of order; r = 0.8 lacks the effective conductivity and has no enskog value.
POINTS = [
    point(0.9, {"shear_viscosity": coefficient(1.02, 0.02, dilute=1.0, enskog=1.01),
                "effective_conductivity": coefficient(0.86, 0.015, dilute=1.0, enskog=1.01)}),
    point(0.8, {"shear_viscosity": coefficient(1.05, 0.03, dilute=1.0)}),
    point(0.99, {"shear_viscosity": coefficient(1.0, 0.02, dilute=1.0, enskog=1.01),
                 "effective_conductivity": coefficient(0.98, 0.01, dilute=1.0, enskog=None)}),
]


def sweep_folder(test, points):
    folder = scratch(test)
    (folder / "sweep.json").write_text(json.dumps({"case": "shear_wave", "key": "md.restitution",
                                                   "status": "ok", "points": points, "cooling": None}))
    return folder


class SweepTransport(unittest.TestCase):
    def test_coefficients_sorted_by_r_with_every_closure(self):
        d = data.sweep_transport(data.SweepRun(sweep_folder(self, POINTS)))
        np.testing.assert_array_equal(d["restitution"], [0.8, 0.9, 0.99])
        self.assertEqual(list(d["coefficients"]), ["shear_viscosity", "effective_conductivity"])  # page order
        eta = d["coefficients"]["shear_viscosity"]
        np.testing.assert_array_equal(eta["measured"], [1.05, 1.02, 1.0])
        np.testing.assert_array_equal(eta["error"], [0.03, 0.02, 0.02])
        self.assertEqual(sorted(eta["closures"]), ["dilute", "enskog"])
        self.assertTrue(math.isnan(eta["closures"]["enskog"][0]))  # absent at r = 0.8: NaN
        kappa = d["coefficients"]["effective_conductivity"]
        self.assertTrue(math.isnan(kappa["measured"][0]))
        self.assertTrue(math.isnan(kappa["closures"]["enskog"][2]))  # null in the file: NaN

    def test_figure_draws_one_panel_per_coefficient_with_the_distances_in_sigma(self):
        run = data.SweepRun(sweep_folder(self, POINTS))
        drawn = figures_sweep.fig_sweep_transport(run)
        self.assertEqual(len(drawn.fig.axes), 2)
        rows = [str(label) + " " + str(value) for label, value, _ in drawn.measured]
        self.assertEqual(len(rows), 6)  # two coefficients at three points
        # r = 0.9, eta: dilute 1.0 is (1.0 - 1.02)/0.02 = -1 sigma from the particles.
        self.assertTrue(any("r = 0.9:" in row and "dilute 1 (−1σ)" in row for row in rows), rows)
        matplotlib.pyplot.close(drawn.fig)

    def test_absent_without_a_transport_block(self):
        run = data.SweepRun(sweep_folder(self, [point(0.9), point(0.8)]))
        with self.assertRaisesRegex(Skip, "transport"):
            data.sweep_transport(run)

    def test_the_sweep_page_shows_it_or_lists_it_as_skipped(self):
        for points, shown in ((POINTS, True), ([point(0.9), point(0.8)], False)):
            folder = sweep_folder(self, points)
            figures, skipped, failed = page.build_sweep(folder)
            self.assertNotIn("s5_transport.png", [f for f, _ in failed])
            self.assertEqual("sweep_transport" in [f["id"] for f in figures], shown)
            self.assertEqual((folder / "figures" / "s5_transport.png").is_file(), shown)
            self.assertTrue((folder / "report.html").is_file())
            if not shown:
                self.assertIn("s5_transport.png", [f for f, _ in skipped])


class SweepCopiesTheTransportBlock(unittest.TestCase):
    def test_a_point_summary_transport_block_reaches_sweep_json_and_the_page(self):
        if not BINARY.is_file():
            self.skipTest(f"{BINARY} not built (set GRANVV_BINARY)")
        out = scratch(self) / "sweep"
        command = [str(BINARY), "sweep", "md_haff", "--out", str(out), "--quiet", "--no-report",
                   "--set", "md.restitution=0.9,0.95", *TINY_MD]

        def sweep():
            done = subprocess.run(command, capture_output=True, text=True, timeout=120)
            self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
            return json.loads((out / "sweep.json").read_text())

        first = sweep()["points"]
        self.assertFalse(any("transport" in p for p in first))  # no block: no key
        for p in first:
            summary_file = out / p["dir"] / "summary.json"
            summary = json.loads(summary_file.read_text())
            summary["transport"] = {"shear_viscosity": coefficient(1.02, 0.02, dilute=1.0, enskog=1.01)}
            summary_file.write_text(json.dumps(summary))
        points = sweep()["points"]  # the finished points are reused, their summaries read again
        self.assertTrue(all(p["reused"] for p in points))
        self.assertEqual([p["transport"]["shear_viscosity"]["measured"] for p in points], [1.02, 1.02])
        figures, _skipped, failed = page.build_sweep(out)
        self.assertEqual(failed, [])
        self.assertIn("sweep_transport", [f["id"] for f in figures])


if __name__ == "__main__":
    unittest.main()
