"""scripts/granvv_report/data.py: the report's only reader of results.h5, summary.json, sweep.json
and atlas.json. Its accessors against output folders of the real binary (a hydro-only run of
`haff`, and `md_haff` shrunk to 400 hard disks with its comparison: about 1 s together), read
again here with h5py and json; its helpers at known values; and the refusals of folders it
cannot read (a missing or damaged results.h5, files of two runs, a sweep or atlas file without
its list)."""
import json
import math
import unittest
import warnings

import h5py
import numpy as np

from report_fixtures import TINY_MD, copy_of, granvv_run, scratch
from granvv_report import data
from granvv_report.data import ReportError, Skip


def group(**arrays):
    """A group as data.py holds it."""
    return {"data": {k: np.asarray(v) for k, v in arrays.items()}, "attrs": {}}


class Helpers(unittest.TestCase):
    def test_num_is_a_finite_float_or_none(self):
        self.assertEqual(data.num(3), 3.0)
        self.assertEqual(data.num("2.5"), 2.5)
        self.assertEqual(data.num(np.float32(0.5)), 0.5)
        for x in (None, "abc", float("nan"), math.inf, -math.inf, [1.0], {}):
            self.assertIsNone(data.num(x), x)

    def test_get_tolerates_absent_levels(self):
        s = {"hydro": {"fit": {"t_min": 0.1}, "none": None}, "list": [1]}
        self.assertEqual(data.get(s, "hydro", "fit", "t_min"), 0.1)
        self.assertEqual(data.get(s, "hydro", "fit"), {"t_min": 0.1})
        self.assertIsNone(data.get(s, "hydro", "none", "t_min"))
        self.assertIsNone(data.get(s, "md", "t0"))
        self.assertIsNone(data.get(s, "list", "x"))
        self.assertIsNone(data.get(None, "hydro"))
        self.assertIs(data.get(s), s)

    def test_arr_gives_float_arrays_or_none(self):
        g = group(t=[0, 1, 2], label=np.array(["a", "b"], dtype=object), one=[7.0])
        a = data.arr(g, "t")
        self.assertEqual(a.dtype, float)
        np.testing.assert_array_equal(a, [0.0, 1.0, 2.0])
        self.assertIsNone(data.arr(g, "label"))  # text
        self.assertIsNone(data.arr(g, "absent"))
        self.assertIsNone(data.arr(None, "t"))
        self.assertIsNone(data.arr(g, "one", min_len=2))

    def test_member_rows_and_series(self):
        g = group(one=[1.0, 2.0, 3.0], two=[[1.0, 2.0, 3.0], [3.0, 4.0, 5.0]], nan=[math.nan] * 3)
        self.assertEqual(data.md_members(g, "one", 3).shape, (1, 3))  # one member
        self.assertEqual(data.md_members(g, "two", 3).shape, (2, 3))
        self.assertIsNone(data.md_members(g, "two", 4))  # another length
        np.testing.assert_array_equal(data.md_series(g, "one", 3), [1.0, 2.0, 3.0])
        self.assertIsNone(data.md_series(g, "nan", 3))  # nothing measured
        self.assertIsNone(data.md_series(g, "two", 3))  # not 1-D

    def test_nanmean_rows_is_nan_where_no_member_has_a_value_without_a_warning(self):
        a = np.array([[1.0, math.nan, math.nan], [3.0, 4.0, math.nan]])
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            m = data.nanmean_rows(a)
        np.testing.assert_array_equal(m[:2], [2.0, 4.0])
        self.assertTrue(math.isnan(m[2]))

    def test_compare_rows_and_vectors_of_their_shape(self):
        g = group(rows=np.ones((2, 5)), vec=[1.0, math.nan], allnan=[math.nan, math.nan])
        self.assertIsNotNone(data.cmp_rows(g, "rows", (2, 5)))
        self.assertIsNone(data.cmp_rows(g, "rows", (5, 2)))
        self.assertIsNotNone(data.cmp_vec(g, "vec", 2))
        self.assertIsNone(data.cmp_vec(g, "allnan", 2))
        self.assertIsNone(data.cmp_vec(g, "vec", 3))

    def test_snapshot_labels_fall_back_to_output(self):
        self.assertEqual(data.snapshot_labels(None, 2), ["output", "output"])
        g = group(label=np.array(["initial", "output"], dtype=object))
        self.assertEqual(data.snapshot_labels(g, 2), ["initial", "output"])
        self.assertEqual(data.snapshot_labels(g, 3), ["output"] * 3)  # labels of another count


class HydroRun(unittest.TestCase):
    """`granvv run haff`: the hydro alone."""

    @classmethod
    def setUpClass(cls):
        cls.dir = granvv_run("haff")
        cls.out = data.Run(cls.dir)
        with open(cls.dir / "summary.json") as fh:
            cls.summary = json.load(fh)

    def test_groups_are_the_files_datasets(self):
        with h5py.File(self.dir / "results.h5", "r") as f:
            for name in ("t", "T_mean", "energy"):
                np.testing.assert_array_equal(data.arr(self.out.hydro_ts, name), f["hydro/timeseries"][name][()])
            self.assertEqual(self.out.attrs["run_id"], f.attrs["run_id"])
            groups = []
            f.visit(lambda name: groups.append(name) if isinstance(f[name], h5py.Group) else None)
            self.assertEqual(self.out.groups, groups)
            labels = [x.decode() for x in f["hydro/fields/label"][()]]
        self.assertIn("hydro/timeseries", self.out.groups)
        self.assertEqual(data.snapshot_labels(self.out.hydro_fields, len(labels)), labels)

    def test_summary_blocks_are_summary_json(self):
        self.assertEqual(self.out.top_summary("run_id"), self.summary["run_id"])
        self.assertEqual(self.out.hydro_summary("energy_drift"), self.summary["hydro"]["energy_drift"])
        self.assertIsNone(self.out.md_summary("haff_t0_measured"))  # md is null
        self.assertEqual([name for name, _ in self.out.engine_blocks()], ["hydro"])
        self.assertTrue(self.out.has_hydro())
        self.assertFalse(self.out.has_md())
        self.assertFalse(self.out.has_compare())
        self.assertEqual(self.out.warnings, [])

    def test_configuration_from_the_attributes_and_the_stored_case(self):
        self.assertEqual(self.out.config("case.name"), '"haff"')  # the attribute: a TOML literal
        self.assertEqual(self.out.config_table("case", "name"), "haff")  # the parsed case
        self.assertEqual(self.out.cfg["case"]["name"], "haff")
        self.assertIsNone(self.out.config("no.such_key"))

    def test_snapshot_record_at_the_same_time(self):
        # The same time is data.SAME_TIME relative (as the C++ pairs snapshots): a time written
        # to results.h5 and to summary.json is the same double, so round-off is all it allows.
        first = self.summary["hydro"]["snapshots"][0]
        scale = max(1.0, abs(first["t"]))
        self.assertEqual(data.find_snapshot_summary(self.out, first["t"] + 0.5 * data.SAME_TIME * scale), first)
        self.assertIsNone(data.find_snapshot_summary(self.out, first["t"] + 2 * data.SAME_TIME * scale))
        self.assertIsNone(data.find_snapshot_summary(self.out, first["t"] + 0.5))

    def test_particle_and_comparison_accessors_skip_with_the_reason(self):
        with self.assertRaisesRegex(Skip, "no /md/timeseries"):
            data.md_timeseries(self.out)
        with self.assertRaisesRegex(Skip, "no /compare group"):
            data.cmp_data(self.out)
        with self.assertRaisesRegex(Skip, "no /compare/pressure"):
            data.cmp_pressure(self.out)
        self.assertIsNone(data.compare_hydro_T(self.out))
        self.assertIsNone(data.md_value(self.out, "particles"))
        self.assertFalse(data.is_sweep_folder(self.dir))
        self.assertFalse(data.is_atlas_folder(self.dir))


class ParticleRunWithComparison(unittest.TestCase):
    """`granvv run md_haff`, 400 hard disks, two members, with its comparison."""

    @classmethod
    def setUpClass(cls):
        cls.dir = granvv_run("md_haff", *TINY_MD)
        cls.out = data.Run(cls.dir)
        with open(cls.dir / "summary.json") as fh:
            cls.summary = json.load(fh)

    def test_particle_time_series_and_members(self):
        G, t = data.md_timeseries(self.out, at_least_two=True)
        with h5py.File(self.dir / "results.h5", "r") as f:
            np.testing.assert_array_equal(t, f["md/timeseries/t"][()])
            T = f["md/timeseries/T"][()]
        self.assertEqual(T.shape, (2, t.size))  # members x samples
        np.testing.assert_array_equal(data.md_members(G, "T", t.size), T)
        np.testing.assert_allclose(data.nanmean_rows(data.md_members(G, "T", t.size)), T.mean(axis=0),
                                   rtol=1e-15)
        self.assertEqual(t[0], 0.0)
        self.assertTrue(np.all(np.diff(t) > 0))

    def test_engine_values_from_the_summary_then_the_md_group(self):
        self.assertEqual(data.md_value(self.out, "particles"), 400.0)
        self.assertEqual(data.md_value(self.out, "haff_t0_measured"), self.summary["md"]["haff_t0_measured"])
        self.assertEqual(data.md_config(self.out, "engine"), "event_driven")  # TOML quotes removed
        self.assertEqual(data.md_config(self.out, "particles"), "400")
        # Without summary.json (docs/outputs.md: a results.h5 is reported only with the summary of
        # its run; a folder from before run ids has neither id and is read with a warning).
        no_summary = copy_of(self.dir, self)
        (no_summary / "summary.json").unlink()
        with self.assertRaisesRegex(ReportError, "from different runs"):
            data.Run(no_summary)
        with h5py.File(no_summary / "results.h5", "a") as f:
            del f.attrs["run_id"]
        run = data.Run(no_summary)
        self.assertEqual(run.summary, {})
        self.assertEqual(len(run.warnings), 1)
        self.assertIn("summary.json not found", run.warnings[0])
        self.assertEqual(data.md_value(run, "box_length"), self.out.md_group["attrs"]["box_length"])

    def test_comparison(self):
        C, t, x = data.cmp_data(self.out)
        with h5py.File(self.dir / "results.h5", "r") as f:
            np.testing.assert_array_equal(t, f["compare/t"][()])
            np.testing.assert_array_equal(x, f["compare/x"][()])
            self.assertEqual(set(C["fields"]), set(f["compare/fields"]))
        L = data.cmp_box(self.out)
        self.assertEqual(L, self.summary["md"]["box_length"])
        tm, T = data.compare_hydro_T(self.out)
        np.testing.assert_array_equal(tm, data.arr(self.out.hydro_ts, "t") * L)  # MD time
        self.assertEqual(T.size, tm.size)
        self.assertIsNotNone(data.cmp_pressure(self.out))  # hard disks give a collision virial
        window = data.cmp_window(C)
        self.assertEqual(len(window), 3)
        self.assertIsInstance(window[2], str)
        self.assertEqual([name for name, _ in self.out.engine_blocks()], ["hydro", "md", "compare"])
        self.assertTrue(self.out.has_md() and self.out.has_compare())
        self.assertEqual(self.out.transport, {})  # compare.transport = "none": no /transport
        self.assertIsNone(self.out.transport_summary("shear_viscosity"))


class RefusedFolders(unittest.TestCase):
    def test_missing_or_damaged_results(self):
        folder = scratch(self)
        with self.assertRaisesRegex(ReportError, "results.h5 not found"):
            data.Run(folder)
        (folder / "results.h5").mkdir()
        with self.assertRaisesRegex(ReportError, "is not a file"):
            data.Run(folder)
        (folder / "results.h5").rmdir()
        (folder / "results.h5").write_bytes(b"\x89HDF\r\n\x1a\n" + bytes(200))
        with self.assertRaisesRegex(ReportError, "the file is damaged"):
            data.Run(folder)
        # The damage message is one line.
        try:
            data.Run(folder)
        except ReportError as e:
            self.assertNotIn("\n", str(e))

    def test_results_and_summary_of_two_runs(self):
        folder = copy_of(granvv_run("haff"), self)
        summary = json.loads((folder / "summary.json").read_text())
        summary["run_id"] = "another-run"
        (folder / "summary.json").write_text(json.dumps(summary))
        with self.assertRaisesRegex(ReportError, "from different runs"):
            data.Run(folder)

    def test_unreadable_summary_is_a_warning(self):
        folder = scratch(self)
        kept = []
        (folder / "summary.json").write_text("{not json")
        self.assertEqual(data.load_summary(folder / "summary.json", kept), {})
        (folder / "summary.json").write_text("[1, 2]")
        self.assertEqual(data.load_summary(folder / "summary.json", kept), {})
        self.assertEqual(len(kept), 2)
        self.assertTrue(all("summary.json unreadable" in w for w in kept), kept)

    def test_sweep_and_atlas_files_need_their_lists(self):
        folder = scratch(self)
        (folder / "sweep.json").write_text(json.dumps({"key": "md.restitution"}))
        self.assertTrue(data.is_sweep_folder(folder))
        with self.assertRaisesRegex(ReportError, "no points list"):
            data.SweepRun(folder)
        (folder / "atlas.json").write_text("[]")
        self.assertTrue(data.is_atlas_folder(folder))
        with self.assertRaisesRegex(ReportError, "no runs list"):
            data.AtlasRun(folder)
        (folder / "results.h5").write_bytes(b"")  # a run folder is neither
        self.assertFalse(data.is_sweep_folder(folder))
        self.assertFalse(data.is_atlas_folder(folder))


class Sweep(unittest.TestCase):
    """sweep.json's points with their cooling rows and report links (docs/outputs.md)."""

    def test_points_joined_to_their_cooling_rows(self):
        folder = scratch(self)
        (folder / "r=0.8 a").mkdir()
        (folder / "r=0.8 a" / "report.html").write_text("<html></html>")
        sweep = {"key": "md.restitution",
                 "points": [{"value": 0.8, "dir": "r=0.8 a", "status": "ok", "exit_code": 0,
                             "md": {"restitution_measured": 0.8}, "hydro_wall_seconds": 1.5},
                            {"value": 0.9, "dir": "r=0.9", "status": "failed", "exit_code": 1, "md": None},
                            "not a point"],
                 "cooling": {"points": [{"point": 0, "restitution": 0.8, "t0": 12.0}]}}
        (folder / "sweep.json").write_text(json.dumps(sweep))
        run = data.SweepRun(folder)
        self.assertEqual(run.sweep("key"), "md.restitution")
        self.assertEqual(run.without_points(), {"key": "md.restitution", "cooling": sweep["cooling"]})
        points = data.sweep_points(run)
        self.assertEqual([p["i"] for p in points], [0, 1, 2])
        self.assertEqual(points[0]["link"], "r=0.8%20a/report.html")  # quoted, only where it exists
        self.assertIsNone(points[1]["link"])
        self.assertEqual(points[0]["cool"]["t0"], 12.0)
        self.assertIsNone(points[1]["cool"])
        self.assertEqual(points[1]["md"], {})
        self.assertEqual(points[0]["hydro_wall"], 1.5)
        self.assertIsNone(points[2]["value"])
        cooling = data.sweep_cooling(run)
        np.testing.assert_array_equal(cooling["t0"], [12.0])
        self.assertTrue(math.isnan(cooling["zeta"][0]))  # absent: NaN, not an error
        np.testing.assert_array_equal(cooling["restitution_measured"], [0.8])

    def test_no_cooling_rows_skip_with_the_reason(self):
        folder = scratch(self)
        (folder / "sweep.json").write_text(json.dumps({"points": [], "cooling_error": "too few points"}))
        with self.assertRaisesRegex(Skip, "too few points"):
            data.sweep_cooling(data.SweepRun(folder))


if __name__ == "__main__":
    unittest.main()
