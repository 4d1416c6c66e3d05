#!/usr/bin/python3
"""Fault injection against the real granvv binary: the output protocol of docs/outputs.md.

    /usr/bin/python3 tests/fault_injection.py BUILD/granvv [unittest args, e.g. -k sigterm]

Every test breaks a real run (signals at several phases, a full disk, read-only folders, two
runs into one folder, MPI failure paths, a damaged results.h5, an interrupted sweep) and then
asserts the state of the folder: an honest status, readable files, and the previous good result
either intact or superseded by a complete, honestly labelled one. The full-disk and read-only
tests mount a small tmpfs and run only as root; otherwise they are skipped. Runs are tiny (a
64-cell hydro, 400 disks), so the whole file takes well under a minute on an idle core.
"""
import json
import math
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path

import h5py
import numpy as np

GRANVV = None  # set from argv

# A hydro run of a fraction of a second, and one of many seconds (to be interrupted).
QUICK = ["single_mode", "--set", "hydro.cells=64", "--set", "convergence.cells=[]",
         "--set", "hydro.t_end=0.5", "--set", "hydro.output_times=[0.25]", "--quiet", "--no-report"]
SLOW = ["single_mode", "--set", "hydro.cells=20000", "--set", "convergence.cells=[]",
        "--set", "hydro.output_times=[0.25]", "--quiet", "--no-report"]
# 20000 cells for a few steps: the HDF5 write is a large part of its second.
BIG = ["single_mode", "--set", "hydro.cells=20000", "--set", "convergence.cells=[]",
       "--set", "hydro.output_times=[]", "--set", "hydro.t_end=0.002", "--quiet", "--no-report"]
# A particle run of 400 disks: about a second, and one that lasts long enough to be interrupted.
MD = ["md_haff", "--set", "md.particles=400", "--set", "md.box_width=80", "--set", "md.ensemble=1",
      "--set", "md.sample_interval=1.0", "--set", "md.snapshot_interval=1.0", "--quiet", "--no-report"]
MD_QUICK = MD + ["--set", "md.t_end=4", "--set", "md.output_times=[0.0,4.0]"]
MD_SLOW = MD + ["--set", "md.t_end=4000", "--set", "md.output_times=[0.0,4000.0]"]
# Two members of a few seconds each, checkpointed every 0.3 s of wall time.
MD_RESUMABLE = MD + ["--set", "md.ensemble=2", "--set", "md.t_end=30",
                     "--set", "md.output_times=[0.0,15.0,30.0]", "--set", "md.checkpoint_interval=0.3"]
# The same four times longer, for runs stopped under mpirun once their members have checkpoints:
# on an idle machine the 30-unit run is over within a second of its first checkpoint, and may end
# before mpirun has passed the signal on to its ranks.
MPI_T_END = 120
MD_RESUMABLE_MPI = MD + ["--set", "md.ensemble=2", "--set", f"md.t_end={MPI_T_END}",
                         "--set", f"md.output_times=[0.0,{MPI_T_END / 2},{MPI_T_END}.0]",
                         "--set", "md.checkpoint_interval=0.3"]
# Long enough for any run of this file on a loaded machine; a hang fails the test instead.
TIMEOUT = 300


def run(args, **kw):
    return subprocess.run([GRANVV, "run"] + args, capture_output=True, text=True, timeout=TIMEOUT, **kw)


def start(args):
    return subprocess.Popen([GRANVV, "run"] + args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            text=True)


def summary(d):
    with open(Path(d) / "summary.json") as f:
        return json.load(f)


def results_run_id(d):
    with h5py.File(Path(d) / "results.h5", "r") as f:
        return f.attrs["run_id"].decode() if isinstance(f.attrs["run_id"], bytes) else f.attrs["run_id"]


def wait_for(predicate, seconds=60.0):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if predicate():
            return True
        time.sleep(0.05)
    return False


def frames_started(d):
    """The particle run in d has written its first H5MD frame (beside its checkpoints)."""
    folder = Path(d) / ".granvv-checkpoint"
    return folder.is_dir() and any(folder.glob("particles*.h5"))


def is_root():
    return os.geteuid() == 0


class Mount:
    """A small tmpfs (options e.g. "size=400k" or "ro"), unmounted at exit."""

    def __init__(self, where, options):
        self.where = Path(where)
        self.where.mkdir(parents=True, exist_ok=True)
        r = subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", str(self.where)],
                           capture_output=True, text=True)
        self.ok = r.returncode == 0

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self.ok:
            subprocess.run(["umount", str(self.where)], check=False)


class FolderState(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="granvv-fault-"))

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def good_run(self, d, args=QUICK):
        r = run(args + ["--out", str(d)])
        self.assertEqual(r.returncode, 0, r.stderr)
        return summary(d)["run_id"]

    def assert_consistent(self, d, status=None):
        """summary.json and results.h5 in d belong to one run, and nothing is half-written."""
        s = summary(d)
        if status:
            self.assertEqual(s["status"], status)
        if (Path(d) / "results.h5").exists():
            self.assertEqual(results_run_id(d), s["run_id"])
        leftovers = [p.name for p in Path(d).iterdir() if p.name.endswith(".partial")]
        self.assertEqual(leftovers, [])
        return s

    def stop_particle_run(self, args, d, sig, after):
        """Starts a particle run into d and stops it with sig `after` seconds into its frames."""
        p = start(args + ["--out", str(d)])
        self.assertTrue(wait_for(lambda: frames_started(d)))
        time.sleep(after)
        p.send_signal(sig)
        _, err = p.communicate(timeout=TIMEOUT)
        self.assertEqual(p.returncode, 128 + sig, err)

    def assert_one_error_line(self, stderr):
        lines = [l for l in stderr.splitlines() if l.strip()]
        self.assertEqual(len(lines), 1, stderr)
        self.assertTrue(lines[0].startswith("granvv: error: "), stderr)


class Signals(FolderState):
    def interrupt(self, args, sig, after):
        d = self.tmp / "out"
        previous = self.good_run(d)
        p = start(args + ["--out", str(d)])
        time.sleep(after)
        p.send_signal(sig)
        _, err = p.communicate(timeout=TIMEOUT)
        return d, previous, p.returncode, err

    def test_sigint_and_sigterm_during_the_hydro_keep_the_previous_result(self):
        for sig in (signal.SIGINT, signal.SIGTERM):
            with self.subTest(sig=sig.name):
                d, previous, code, err = self.interrupt(SLOW, sig, 1.5)
                self.assertEqual(code, 128 + sig, err)
                s = self.assert_consistent(d, "ok")
                self.assertEqual(s["run_id"], previous)
                stopped = summary(d / "interrupted-run")
                self.assertEqual(stopped["status"], "interrupted")
                self.assertIn(sig.name, stopped["error"])
                self.assertFalse(any(p.name.startswith(".granvv-staging") for p in d.iterdir()))
                shutil.rmtree(d)

    def test_sigkill_during_the_hydro_keeps_the_previous_result_and_is_cleaned_up(self):
        d, previous, code, _ = self.interrupt(SLOW, signal.SIGKILL, 1.5)
        self.assertEqual(code, -signal.SIGKILL)
        self.assertEqual(self.assert_consistent(d, "ok")["run_id"], previous)
        self.assertTrue(any(p.name.startswith(".granvv-staging") for p in d.iterdir()))
        r = run(QUICK + ["--out", str(d)])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("killed before it completed", r.stderr)
        self.assertFalse(any(p.name.startswith(".granvv-staging") for p in d.iterdir()))
        self.assert_consistent(d, "ok")

    def test_kills_at_every_phase_never_leave_a_mixed_folder(self):
        # A run of ~1 s whose last part is the HDF5 write of 20000 cells: kills spread over it
        # hit the hydro, the write, and the replacement of the outputs.
        args = BIG
        d = self.tmp / "out"
        previous = self.good_run(d)
        t0 = time.monotonic()
        self.good_run(self.tmp / "timing", args)
        duration = time.monotonic() - t0
        for i, sig in enumerate([signal.SIGKILL, signal.SIGTERM] * 4):
            after = duration * (0.2 + 0.2 * (i // 2))
            with self.subTest(sig=sig.name, after=round(after, 3)):
                p = start(args + ["--out", str(d)])
                time.sleep(after)
                p.send_signal(sig)
                p.communicate(timeout=TIMEOUT)
                if not (d / "summary.json").exists():
                    # Killed while it replaced the outputs: its commit marker lets a reader
                    # finish the replacement.
                    self.assertTrue(any((q / ".commit").exists() for q in d.iterdir()
                                        if q.name.startswith(".granvv-staging")))
                    r = subprocess.run([GRANVV, "report", str(d)], capture_output=True, text=True,
                                       timeout=TIMEOUT)
                    self.assertIn("finished replacing the outputs", r.stderr)
                s = self.assert_consistent(d)
                # Either the previous result, or a complete new one: never a mixture.
                if s["run_id"] != previous:
                    self.assertEqual(s["status"], "ok")
                    self.assertEqual(s["hydro"]["cells"], 20000)
                    previous = s["run_id"]

    def test_sigterm_during_a_particle_run_keeps_the_previous_result(self):
        d = self.tmp / "out"
        previous = self.good_run(d, MD_QUICK)
        self.stop_particle_run(MD_SLOW, d, signal.SIGTERM, 1.0)
        s = self.assert_consistent(d, "ok")
        self.assertEqual(s["run_id"], previous)
        stopped = summary(d / "interrupted-run")
        self.assertEqual(stopped["status"], "interrupted")
        self.assertEqual(stopped["md"]["error"], "interrupted by SIGTERM")
        with h5py.File(d / "interrupted-run" / "particles.h5", "r") as f:  # frames so far, readable
            self.assertGreater(f["particles/all/position/value"].shape[0], 0)

    def test_sigkill_during_a_particle_run_presents_only_the_previous_run(self):
        d = self.tmp / "out"
        previous = self.good_run(d, MD_QUICK)
        p = start(MD_SLOW + ["--out", str(d)])
        self.assertTrue(wait_for(lambda: frames_started(d)))
        p.kill()
        p.communicate(timeout=TIMEOUT)
        s = self.assert_consistent(d, "ok")
        self.assertEqual(s["run_id"], previous)
        r = subprocess.run([GRANVV, "report", str(d)], capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(r.returncode, 0, r.stderr)


class Concurrency(FolderState):
    def test_a_second_run_into_a_busy_folder_refuses_and_mixes_nothing(self):
        d = self.tmp / "out"
        p = start(SLOW + ["--out", str(d)])
        self.assertTrue(wait_for(lambda: (d / ".granvv.lock").exists()))
        time.sleep(0.5)
        r = run(QUICK + ["--out", str(d)])
        self.assertEqual(r.returncode, 2)
        self.assert_one_error_line(r.stderr)
        self.assertIn(f"pid {p.pid}", r.stderr)
        p.send_signal(signal.SIGTERM)
        p.communicate(timeout=TIMEOUT)
        self.assertFalse((d / "summary.json").exists())  # the first run was interrupted: nothing
        self.assertEqual(summary(d / "interrupted-run")["status"], "interrupted")


class UnusableFolders(FolderState):
    def test_proc_self_and_a_file_exit_2_with_one_line(self):
        (self.tmp / "file").write_text("x")
        for out in ["/proc/self", "/proc/self/x", str(self.tmp / "file")]:
            with self.subTest(out=out):
                r = run(QUICK + ["--out", out])
                self.assertEqual(r.returncode, 2)
                self.assert_one_error_line(r.stderr)

    @unittest.skipUnless(is_root(), "mounts a read-only tmpfs (root only)")
    def test_read_only_folder_exits_2_with_one_line(self):
        with Mount(self.tmp / "ro", "ro,size=64k") as m:
            self.assertTrue(m.ok)
            for out in [m.where, m.where / "sub"]:
                r = run(QUICK + ["--out", str(out)])
                self.assertEqual(r.returncode, 2)
                self.assert_one_error_line(r.stderr)
            self.assertEqual(list(m.where.iterdir()), [])

    @unittest.skipIf(is_root(), "root writes into a chmod 555 folder anyway")
    def test_read_only_folder_exits_2_with_one_line_unprivileged(self):
        d = self.tmp / "ro"
        d.mkdir()
        d.chmod(0o555)
        r = run(QUICK + ["--out", str(d)])
        self.assertEqual(r.returncode, 2)
        self.assert_one_error_line(r.stderr)


@unittest.skipUnless(is_root(), "mounts a small tmpfs (root only)")
class FullDisk(FolderState):
    def test_full_disk_during_results_h5_fails_honestly_over_a_good_run(self):
        with Mount(self.tmp / "disk", "size=400k") as m:
            self.assertTrue(m.ok)
            d = m.where / "out"
            self.good_run(d)
            r = run(BIG + ["--out", str(d)])
            self.assertEqual(r.returncode, 1, r.stderr)
            s = self.assert_consistent(d, "failed")
            self.assertIn("No space left on device", s["error"])
            self.assertFalse((d / "results.h5").exists())  # the half-written file is not kept
            self.assertEqual((d / "case.toml").read_text().count("cells = 20000"), 1)

    def test_a_disk_full_at_any_point_of_the_write_is_a_failure_not_a_crash(self):
        # Depending on the room left, HDF5 fails in a dataset write (an exception) or only in
        # the close of the file, which it reports from a destructor on stderr; either must give
        # exit 1 and an honest summary, never a crash at exit.
        for size in ("24k", "40k", "64k", "100k", "200k"):
            with self.subTest(size=size), Mount(self.tmp / f"disk{size}", f"size={size}") as m:
                self.assertTrue(m.ok)
                d = m.where / "out"
                r = run(QUICK + ["--set", "hydro.cells=4000", "--out", str(d)])
                self.assertEqual(r.returncode, 1, r.stderr)
                if not (d / "summary.json").exists():  # not even the summary fits: nothing kept
                    self.assertIn("keeps what it held before this run", r.stderr)
                    self.assertEqual([p.name for p in d.iterdir()], [".granvv.lock"])
                    continue
                s = self.assert_consistent(d, "failed")
                self.assertIn("No space left on device", s["error"])

    def test_full_disk_during_particle_frames_never_leaves_an_empty_summary(self):
        with Mount(self.tmp / "disk", "size=300k") as m:
            self.assertTrue(m.ok)
            d = m.where / "out"
            r = run(MD + ["--set", "md.t_end=200", "--set", "md.output_times=[0.0,200.0]",
                          "--out", str(d)])
            self.assertEqual(r.returncode, 1, r.stderr)
            s = self.assert_consistent(d, "failed")
            self.assertIn("particle frame", s["error"])
            self.assertIn("removed to make room", s["error"])
            self.assertGreater((d / "summary.json").stat().st_size, 0)


    def test_a_comparison_failing_after_its_particle_run_keeps_the_particle_results(self):
        # The particles run first; the hydro's results.h5 then does not fit on the disk.
        with Mount(self.tmp / "disk", "size=600k") as m:
            self.assertTrue(m.ok)
            d = m.where / "out"
            r = run(MD_QUICK + ["--set", "hydro.cells=5000", "--out", str(d)])
            self.assertEqual(r.returncode, 1, r.stderr)
            s = self.assert_consistent(d, "failed")
            self.assertIn("No space left on device", s["error"])
            self.assertEqual(s["md"]["status"], "ok")
            self.assertEqual(s["md"]["particles"], 400)
            with h5py.File(d / "results.h5", "r") as f:
                self.assertEqual(f["md/timeseries/T"].shape[0], 1)


class Mpi(FolderState):
    def mpirun(self, args):
        return subprocess.run(["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", "2", GRANVV, "run"]
                              + args, capture_output=True, text=True, timeout=120)

    def test_hydro_only_under_mpirun_has_one_writer(self):
        d = self.tmp / "out"
        r = self.mpirun(QUICK + ["--out", str(d)])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assert_consistent(d, "ok")
        log = (d / "run.log").read_text()
        self.assertEqual(log.count("running case"), 1)

    def test_an_out_that_cannot_be_made_ends_every_rank(self):
        r = self.mpirun(MD_QUICK + ["--out", "/proc/self/x"])  # timeout: a spinning rank fails
        self.assertNotEqual(r.returncode, 0)
        self.assertEqual(r.stderr.count("granvv: error: "), 1, r.stderr)

    def stopped_under_mpirun(self, d, members=2):
        """A particle run of two members (or one) into d under mpirun -np 2, stopped once its
        last member has a checkpoint; the mpirun command that ran it."""
        mpirun = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", "2", GRANVV]
        p = subprocess.Popen(mpirun + ["run"] + MD_RESUMABLE_MPI +
                             ["--set", f"md.ensemble={members}", "--out", str(d)],
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        last = d / ".granvv-checkpoint" / f"member_{members - 1}.h5"
        self.assertTrue(wait_for(last.exists, TIMEOUT))  # member 0 first: minutes on a loaded machine
        p.terminate()  # mpirun passes SIGTERM on; under several ranks it ends them
        p.communicate(timeout=TIMEOUT)
        return mpirun

    def test_a_particle_run_stopped_under_mpirun_resumes_its_block_files(self):
        # Two ranks write their ID blocks of the H5MD frames to particles_mK.rank000k.h5, joined
        # by particles_mK.h5, and of their checkpoints to member_m.stepS.rankk.h5
        # (docs/outputs.md); a resume continues each rank's own files.
        d = self.tmp / "stopped"
        mpirun = self.stopped_under_mpirun(d)
        self.assertFalse((d / "summary.json").exists())
        # The checkpoint holds each rank's block of the particles in a file of its own, not all
        # of them in member_1.h5 (scene/md_checkpoint.hpp).
        c = d / ".granvv-checkpoint"
        with h5py.File(c / "member_1.h5", "r") as f:
            self.assertEqual(f["engine"].attrs["particle_blocks"], 2)
            self.assertEqual(f["engine/x"].shape, (0,))
            step = int(f.attrs["steps"])
        for k in (0, 1):
            with h5py.File(c / f"member_1.step{step}.rank{k}.h5", "r") as f:
                self.assertEqual(f["x"].shape, (3 * 200,))
                self.assertEqual(f.attrs["first_row"], 200 * k)
        # Earlier steps' blocks are removed once member_1.h5 names the new step; a stop that
        # lands between writing a step's blocks and that removal leaves at most one superseded
        # pair, which the next save removes.
        others = [b for b in c.glob("member_1.step*.rank*.h5")
                  if not b.name.startswith(f"member_1.step{step}.")]
        self.assertLessEqual(len(others), 2, others)
        # One rank cannot continue a state saved in two blocks, and says how to.
        r = subprocess.run([GRANVV, "resume", str(d), "--quiet", "--no-report"],
                           capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assert_one_error_line(r.stderr)
        self.assertIn("mpirun -np 2", r.stderr)
        r = subprocess.run(mpirun + ["resume", str(d), "--quiet", "--no-report"],
                           capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(r.returncode, 0, r.stderr)
        s = self.assert_consistent(d, "ok")
        self.assertTrue(s["md"]["checkpoints"]["resumed"])
        for m in (0, 1):
            with h5py.File(d / f"particles_m{m}.h5", "r") as f:
                steps = f["particles/all/position/step"][()]
                x = f["particles/all/position/value"]
                self.assertTrue(x.is_virtual)
                self.assertEqual(len(steps), MPI_T_END + 1)  # t = 0, 1, ..., MPI_T_END
                self.assertTrue((steps[1:] > steps[:-1]).all())
                self.assertEqual(x.shape, (MPI_T_END + 1, 400, 2))
                self.assertTrue(np.isfinite(x[()]).all())  # every row of every frame
            for k in (0, 1):
                with h5py.File(d / f"particles_m{m}.rank000{k}.h5", "r") as f:
                    self.assertEqual(f["particles/all/position/value"].shape, (MPI_T_END + 1, 200, 2))

    def test_lammps_members_on_one_rank_each_resume_on_their_ranks(self):
        # md.ranks_per_member = 1 under two ranks: member m runs on rank m (a group of one), which
        # writes its checkpoints whole (no blocks) and its frames; a resume continues each member
        # on its rank from them.
        mpirun = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", "2", GRANVV]
        d = self.tmp / "groups"
        args = MD_RESUMABLE_MPI + ["--set", "md.ranks_per_member=1"]
        p = subprocess.Popen(mpirun + ["run"] + args + ["--out", str(d)],
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        c = d / ".granvv-checkpoint"
        self.assertTrue(wait_for(lambda: all((c / f"member_{m}.h5").exists() for m in (0, 1)), 120))
        p.terminate()
        p.communicate(timeout=TIMEOUT)
        self.assertFalse((d / "summary.json").exists())
        for m in (0, 1):
            with h5py.File(c / f"member_{m}.h5", "r") as f:
                self.assertNotIn("particle_blocks", f["engine"].attrs)
                if not f.attrs["finished"]:
                    self.assertEqual(f["engine/x"].shape, (3 * 400,))
        self.assertEqual(list(c.glob("member_*.rank*.h5")), [])
        r = subprocess.run(mpirun + ["resume", str(d), "--quiet", "--no-report"],
                           capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(r.returncode, 0, r.stderr)
        s = self.assert_consistent(d, "ok")
        self.assertTrue(s["md"]["checkpoints"]["resumed"])
        self.assertIn("2 groups of 1 MPI rank", (d / "run.log").read_text())
        for m in (0, 1):
            with h5py.File(d / f"particles_m{m}.h5", "r") as f:
                steps = f["particles/all/position/step"][()]
                x = f["particles/all/position/value"]
                self.assertFalse(x.is_virtual)  # one rank wrote all of it
                self.assertEqual(x.shape, (MPI_T_END + 1, 400, 2))  # t = 0, 1, ..., MPI_T_END
                self.assertTrue((steps[1:] > steps[:-1]).all())
                self.assertTrue(np.isfinite(x[()]).all())

    def test_a_non_finite_particle_on_one_rank_stops_every_rank(self):
        # Rank 1's block of a checkpoint saved by two ranks gets a NaN velocity: rank 1 alone
        # sees it, and every rank must stop with its reason (exit 2, one line), none waiting.
        d = self.tmp / "stopped"
        mpirun = self.stopped_under_mpirun(d)
        c = d / ".granvv-checkpoint"
        with h5py.File(c / "member_1.h5", "r") as f:
            step = int(f.attrs["steps"])
        with h5py.File(c / f"member_1.step{step}.rank1.h5", "r+") as f:
            v = f["v"][()]
            v[3 * 17] = float("nan")
            f["v"][...] = v
        begin = time.monotonic()
        r = subprocess.run(mpirun + ["resume", str(d), "--quiet", "--no-report"],
                           capture_output=True, text=True, timeout=TIMEOUT)
        self.assertLess(time.monotonic() - begin, 60)
        self.assertEqual(r.returncode, 2, r.stderr)
        lines = [l for l in r.stderr.splitlines() if l.startswith("granvv: error: ")]
        self.assertEqual(len(lines), 1, r.stderr)
        self.assertIn("non-finite", lines[0])
        self.assertIn("(on rank 1)", lines[0])
        self.assertTrue((c / "member_1.h5").exists())  # the checkpoint stays

    def test_disks_pressed_onto_one_spot_are_refused_before_the_resume(self):
        # Two disks of a LAMMPS checkpoint saved in blocks by two ranks put on one spot, first
        # within one rank's block, then one from each block. Their gran/hooke force would be
        # 0 * inf, a NaN inside LAMMPS on the rank holding them, which Debian's LAMMPS ends
        # through MPI_Abort. The resume must refuse the state before the run: exit 2 on every
        # rank, one line naming the member, the disks and the overlap, the checkpoint and the
        # folder's listing as before.
        for case, (k, i) in (("one block", (0, 1)), ("two blocks", (1, 0))):
            with self.subTest(case):
                d = self.tmp / case.replace(" ", "_")
                c = d / ".granvv-checkpoint"
                mpirun = self.stopped_under_mpirun(d, members=1)
                with h5py.File(c / "member_0.h5", "r") as f:
                    step = int(f.attrs["steps"])
                blocks = [c / f"member_0.step{step}.rank{b}.h5" for b in (0, 1)]
                xs = []
                for b in blocks:
                    with h5py.File(b, "r") as f:
                        xs.append(f["x"][()].reshape(-1, 3))
                xs[k][i] = xs[0][0]  # disk i of block k onto the first disk of block 0
                for b, x in zip(blocks, xs):
                    with h5py.File(b, "r+") as f:
                        f["x"][...] = x.reshape(-1)
                kept = lambda: {f.name: f.read_bytes() for f in c.iterdir()}
                saved = kept()
                listing = sorted(f.name for f in d.iterdir() if not f.name.startswith(".granvv-staging"))
                begin = time.monotonic()
                r = subprocess.run(mpirun + ["resume", str(d), "--quiet", "--no-report"],
                                   capture_output=True, text=True, timeout=TIMEOUT)
                self.assertLess(time.monotonic() - begin, 60)  # no rank waits for the other
                self.assertEqual(r.returncode, 2, r.stderr)
                lines = [l for l in r.stderr.splitlines() if l.startswith("granvv: error: ")]
                self.assertEqual(len(lines), 1, r.stderr)
                self.assertRegex(lines[0], r"member 0 .*disks \d+ and \d+ overlap by 1 sigma")
                self.assertIn("md.max_overlap", lines[0])
                self.assertEqual(kept(), saved)
                self.assertEqual(sorted(f.name for f in d.iterdir()
                                        if not f.name.startswith(".granvv-staging")), listing)

    @unittest.skipUnless(is_root(), "mounts a small tmpfs (root only)")
    def test_a_write_failure_on_rank_0_ends_every_rank(self):
        # Without a comparison the hydro runs first and results.h5 is written before the
        # collective particle run: rank 1 must not enter it alone.
        # 64 kB: room for case.toml and run.log (13 kB each with every resolved key) and the
        # failure's summary, not for the 4000-cell results.h5.
        with Mount(self.tmp / "disk", "size=64k") as m:
            self.assertTrue(m.ok)
            d = m.where / "out"
            r = self.mpirun(MD_QUICK + ["--set", "compare.enabled=false", "--set", "hydro.cells=4000",
                                        "--out", str(d)])
            self.assertEqual(r.returncode, 1, r.stderr)
            self.assertNotIn("Process received signal", r.stderr)  # no rank crashed at exit
            self.assertIn("No space left on device", self.assert_consistent(d, "failed")["error"])


class Report(FolderState):
    def test_a_damaged_results_h5_gives_one_line(self):
        d = self.tmp / "out"
        self.good_run(d)
        with open(d / "results.h5", "r+b") as f:
            size = f.seek(0, 2)
            f.seek(2048)
            f.write(b"\0" * (size - 4096))
        r = subprocess.run([GRANVV, "report", str(d)], capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(r.returncode, 1)
        self.assertNotIn("Traceback", r.stderr)
        lines = [l for l in r.stderr.splitlines() if l.strip()]
        self.assertEqual(len(lines), 1, r.stderr)
        self.assertIn("damaged", lines[0])

    def test_a_replacement_cut_short_is_finished_by_report(self):
        # The state of a run killed inside its commit: the old summary removed, the new outputs
        # still in a staging folder with the commit marker (docs/outputs.md).
        d, new = self.tmp / "out", self.tmp / "new"
        self.good_run(d)
        new_id = self.good_run(new, QUICK + ["--set", "hydro.cells=128"])
        staging = d / ".granvv-staging-99999"
        shutil.copytree(new, staging, ignore=shutil.ignore_patterns(".granvv.lock"))
        (staging / ".commit").write_text("".join(p.name + "\n" for p in staging.iterdir()))
        (d / "summary.json").unlink()
        r = subprocess.run([GRANVV, "report", str(d)], capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("finished replacing the outputs", r.stderr)
        self.assertEqual(self.assert_consistent(d, "ok")["run_id"], new_id)
        self.assertFalse(staging.exists())

    def test_results_of_another_run_are_refused(self):
        a, b = self.tmp / "a", self.tmp / "b"
        self.good_run(a)
        self.good_run(b)
        shutil.copy(b / "results.h5", a / "results.h5")
        r = subprocess.run([GRANVV, "report", str(a)], capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(r.returncode, 1)
        self.assertIn("from different runs", r.stderr)


class Sweeps(FolderState):
    def sweep(self, d, values, **kw):
        return subprocess.Popen([GRANVV, "sweep"] + QUICK[:1] + QUICK[1:] +
                                ["--set", f"hydro.cells={values}", "--out", str(d)],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, **kw)

    def test_equal_values_are_refused(self):
        r = subprocess.run([GRANVV, "sweep"] + QUICK + ["--set", "hydro.cells=32,64,32", "--out",
                                                         str(self.tmp / "s")],
                           capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(r.returncode, 2)
        self.assert_one_error_line(r.stderr)
        self.assertFalse((self.tmp / "s").exists())

    def test_an_interrupted_sweep_says_so_and_resumes(self):
        d = self.tmp / "s"
        # QUICK's hydro.cells is overridden by the swept one; the last point lasts minutes.
        p = self.sweep(d, "32,48,20000")
        point = d / "hydro.cells=20000"
        self.assertTrue(wait_for(lambda: point.exists()))
        time.sleep(1.0)
        p.send_signal(signal.SIGINT)
        p.communicate(timeout=TIMEOUT)
        self.assertEqual(p.returncode, 128 + signal.SIGINT)
        sw = json.loads((d / "sweep.json").read_text())
        self.assertEqual(sw["status"], "interrupted")
        self.assertEqual([q["status"] for q in sw["points"]], ["ok", "ok", "interrupted"])
        ids = [summary(d / f"hydro.cells={v}")["run_id"] for v in (32, 48)]
        r = self.sweep(d, "32,48,64")
        r.communicate(timeout=TIMEOUT)
        self.assertEqual(r.returncode, 0)
        sw = json.loads((d / "sweep.json").read_text())
        self.assertEqual(sw["status"], "ok")
        self.assertEqual([q["reused"] for q in sw["points"]], [True, True, False])
        self.assertEqual([summary(d / f"hydro.cells={v}")["run_id"] for v in (32, 48)], ids)

    def test_a_particle_point_stopped_midway_continues_its_checkpoint(self):
        d = self.tmp / "s"
        args = [GRANVV, "sweep"] + MD_RESUMABLE + ["--set", "md.checkpoint_interval=1000",
                                                   "--set", "md.seed=1,2", "--out", str(d)]
        p = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        self.assertTrue(wait_for(lambda: frames_started(d / "md.seed=1")))
        time.sleep(0.5)
        p.send_signal(signal.SIGINT)
        p.communicate(timeout=TIMEOUT)
        self.assertEqual(p.returncode, 128 + signal.SIGINT)
        r = subprocess.run(args, capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("continues its checkpoint", r.stderr)
        self.assertTrue(summary(d / "md.seed=1")["md"]["checkpoints"]["resumed"])
        self.assertFalse(summary(d / "md.seed=2")["md"]["checkpoints"]["resumed"])

    def test_a_killed_sweep_is_not_left_running(self):
        d = self.tmp / "s"
        p = self.sweep(d, "32,20000")
        self.assertTrue(wait_for(lambda: (d / "hydro.cells=20000").exists()))
        p.kill()
        p.communicate(timeout=TIMEOUT)
        sw = json.loads((d / "sweep.json").read_text())
        self.assertEqual(sw["status"], "incomplete")


class Resume(FolderState):
    """Checkpoints of particle runs and `granvv resume` (docs/outputs.md, "Checkpoints and resume")."""

    def members(self, d, name):
        with h5py.File(Path(d) / "results.h5", "r") as f:
            return f["md/timeseries/" + name][()]

    def resume(self, d):
        return subprocess.run([GRANVV, "resume", str(d), "--quiet", "--no-report"],
                              capture_output=True, text=True, timeout=TIMEOUT)

    def test_a_particle_run_killed_midway_resumes_with_the_statistics_of_an_uninterrupted_one(self):
        whole = self.tmp / "whole"
        r = run(MD_RESUMABLE + ["--out", str(whole)])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertFalse((whole / ".granvv-checkpoint").exists())  # removed once complete
        d = self.tmp / "killed"
        p = start(MD_RESUMABLE + ["--out", str(d)])
        # Member 0 finished and member 1 has saved a state of its own.
        self.assertTrue(wait_for(lambda: (d / ".granvv-checkpoint" / "member_1.h5").exists(), 120))
        p.kill()
        p.communicate(timeout=TIMEOUT)
        self.assertFalse((d / "summary.json").exists())
        r = self.resume(d)
        self.assertEqual(r.returncode, 0, r.stderr)
        s = self.assert_consistent(d, "ok")
        c = s["md"]["checkpoints"]
        self.assertTrue(c["resumed"])
        self.assertEqual(c["members_restored"], 1)
        self.assertEqual(c["resumed_member"], 1)
        self.assertGreater(c["resumed_t"], 0.0)
        self.assertNotIn("checkpoint", s)
        self.assertFalse((d / ".granvv-checkpoint").exists())
        # Member 0 is the saved result, bit for bit. Member 1 continued from its state: the
        # samples before it are the saved ones, bit for bit; after it the restart changes the
        # contacts open at that moment by O(dt) (tests/test_md_run.cpp,
        # ARunContinuedFromItsCheckpoint...), and the chaotic collisions amplify that, the more
        # the earlier the checkpoint fell (measured 1e-5 to 7e-3 here). What must hold is the
        # statistics: the continued member stays within the thermal noise of one member's box
        # temperature, sqrt(2/N) = 7 % for these 400 disks, and the Haff fit within 3 standard
        # errors of the uninterrupted one.
        with h5py.File(whole / "results.h5", "r") as f:
            times = f["md/timeseries/t"][()]
        before = times < c["resumed_t"] + 1e-9
        for name in ("T", "energy_total"):
            a, b = self.members(whole, name), self.members(d, name)
            self.assertEqual(a.shape, b.shape)
            self.assertTrue((a[0] == b[0]).all(), name)
            self.assertTrue((a[1][before] == b[1][before]).all(), name)
        a, b = self.members(whole, "T"), self.members(d, "T")
        self.assertLess(abs(b[1] / a[1] - 1).max(), math.sqrt(2 / 400))
        mw, md = summary(whole)["md"], s["md"]
        self.assertLess(abs(md["haff_t0_measured"] - mw["haff_t0_measured"]),
                        3 * math.hypot(md["haff_t0_measured_error"], mw["haff_t0_measured_error"]))
        # The particle frames of the resumed member: the same steps as the uninterrupted ones.
        for f in ("particles_m0.h5", "particles_m1.h5"):
            with h5py.File(whole / f, "r") as a, h5py.File(d / f, "r") as b:
                self.assertEqual(list(a["particles/all/position/step"][()]),
                                 list(b["particles/all/position/step"][()]), f)
                self.assertEqual(list(a["observables/thermal_energy/step"][()]),
                                 list(b["observables/thermal_energy/step"][()]), f)

    def test_sigint_saves_a_checkpoint_and_resume_continues_from_it(self):
        d = self.tmp / "out"
        # No timed checkpoint in this run: the one it leaves is the signal's.
        args = MD_RESUMABLE + ["--set", "md.checkpoint_interval=1000"]
        self.stop_particle_run(args, d, signal.SIGINT, 0.5)
        stopped = summary(d / "interrupted-run")
        self.assertEqual(stopped["status"], "interrupted")
        self.assertIn("granvv resume", stopped["checkpoint"]["resume"])
        self.assertTrue((d / ".granvv-checkpoint" / "member_0.h5").exists())
        # A resume of another case is refused, and the checkpoint stays.
        r = run(args + ["--set", "md.seed=5", "--resume", "--out", str(d)])
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assert_one_error_line(r.stderr)
        self.assertIn("md.seed", r.stderr)
        self.assertTrue((d / ".granvv-checkpoint" / "member_0.h5").exists())
        r = self.resume(d)
        self.assertEqual(r.returncode, 0, r.stderr)
        s = self.assert_consistent(d, "ok")
        self.assertEqual(s["md"]["checkpoints"]["resumed_member"], 0)
        self.assertGreater(s["md"]["checkpoints"]["resumed_t"], 0.0)
        self.assertEqual(self.members(d, "T").shape[0], 2)

    def test_a_checkpoint_saved_before_its_own_last_sample_is_refused(self):
        # A damaged checkpoint whose time lies before the member's last sample would sample those
        # times again and write a NaN-padded series (found by the fuzzer): refused in one line.
        d = self.tmp / "out"
        c = d / ".granvv-checkpoint"

        def unfinished_with_samples():
            for m in (0, 1):
                try:
                    with h5py.File(c / f"member_{m}.h5", "r") as f:
                        if not f.attrs["finished"] and len(f["series/t"]) >= 2:
                            return m
                except (OSError, KeyError):
                    pass
            return None
        p = start(MD_RESUMABLE + ["--out", str(d)])
        self.assertTrue(wait_for(lambda: unfinished_with_samples() is not None, 120))
        p.send_signal(signal.SIGINT)
        p.communicate(timeout=TIMEOUT)
        m = unfinished_with_samples()
        self.assertIsNotNone(m)
        with h5py.File(c / f"member_{m}.h5", "r+") as f:
            f.attrs["t"] = 0.5 * f["series/t"][-1]
        r = self.resume(d)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assert_one_error_line(r.stderr)
        self.assertIn(f"member {m} holds t = ", r.stderr)
        self.assertIn("before its last sample", r.stderr)
        self.assertTrue((c / f"member_{m}.h5").exists())  # the checkpoint stays

    def test_resume_without_a_checkpoint(self):
        r = self.resume(self.tmp / "nothing")
        self.assertEqual(r.returncode, 2)
        self.assert_one_error_line(r.stderr)
        self.assertIn("no checkpoint", r.stderr)
        d = self.tmp / "fresh"  # `run --resume` with nothing to resume starts from t = 0
        r = run(MD_QUICK + ["--resume", "--out", str(d)])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertFalse(summary(d)["md"]["checkpoints"]["resumed"])


def write_table(path, temperature):
    """A four-row CSV table of uniform density and temperature `temperature` (mean density 1)."""
    rows = "".join(f"{x}, 1, 0, {temperature}\n" for x in (-0.375, -0.125, 0.125, 0.375))
    Path(path).write_text("x, n, v_x, T\n" + rows)


# A particle run of 400 disks started from a table (its T column sets the disks' temperature).
def md_from_table(table):
    return MD_RESUMABLE + ["--set", "initial.type=table", "--set", f"initial.from={table}",
                           "--set", "md.checkpoint_interval=1000"]


class InputFingerprints(FolderState):
    """Caches, reused sweep points and checkpoints know the case and the files they were made
    from (scene/input_fingerprint.hpp): changed inputs run again, or a resume is refused."""

    ATLAS = ["haff", "--budget", "3", "--jobs", "1", "--quiet", "--no-report"]

    def atlas(self, d, *extra):
        return subprocess.run([GRANVV, "atlas"] + self.ATLAS + list(extra) + ["--out", str(d)],
                              capture_output=True, text=True, timeout=TIMEOUT)

    def made_now(self, stderr):
        line = [l for l in stderr.splitlines() if l.startswith("atlas: wrote")][0]
        return int(line.split(", ")[-1].split()[0])

    def test_an_atlas_runs_again_when_its_table_changed(self):
        table, d = self.tmp / "profile.csv", self.tmp / "atlas"
        write_table(table, 1.0)
        args = ["--set", "initial.type=table", "--set", f"initial.from={table}"]
        r = self.atlas(d, *args)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGreater(self.made_now(r.stderr), 0)
        r = self.atlas(d, *args)  # the same inputs: every run from the cache
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(self.made_now(r.stderr), 0, r.stderr)
        write_table(table, 2.0)
        r = self.atlas(d, *args)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGreater(self.made_now(r.stderr), 0, r.stderr)

    def test_an_edited_atlas_cache_entry_runs_again(self):
        d = self.tmp / "atlas"
        r = self.atlas(d)
        self.assertEqual(r.returncode, 0, r.stderr)
        entries = sorted((d / "runs").glob("*.json"))
        self.assertTrue(entries)
        edits = [lambda e: e.update(times=[]), lambda e: e.update(thermal="x"),
                 lambda e: e["fields"].update(bins=3) if e["fields"] else e.update(times=[7.0]),
                 lambda e: e.update(inputs={"case": {}, "files": []}),
                 lambda e: e.update(format=[1]), lambda e: e.pop("inputs")]
        for entry, edit in zip(entries, edits):
            e = json.loads(entry.read_text())
            edit(e)
            entry.write_text(json.dumps(e))
        r = self.atlas(d)
        self.assertEqual(r.returncode, 0, r.stderr)  # no crash
        self.assertEqual(r.stderr.count("is not used"), min(len(entries), len(edits)), r.stderr)
        self.assertEqual(self.made_now(r.stderr), min(len(entries), len(edits)), r.stderr)
        self.assertTrue(json.loads((d / "atlas.json").read_text()))

    def test_a_sweep_runs_a_point_again_when_its_table_changed(self):
        table, d = self.tmp / "profile.csv", self.tmp / "sweep"
        write_table(table, 1.0)
        args = [GRANVV, "sweep"] + QUICK + ["--set", "initial.type=table", "--set",
                                            f"initial.from={table}", "--set", "hydro.cells=32,48",
                                            "--out", str(d)]
        r = subprocess.run(args, capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(r.returncode, 0, r.stderr)
        r = subprocess.run(args, capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual([q["reused"] for q in json.loads((d / "sweep.json").read_text())["points"]],
                         [True, True])
        write_table(table, 2.0)
        r = subprocess.run(args, capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stderr.count("its inputs changed since (the file"), 2, r.stderr)
        sw = json.loads((d / "sweep.json").read_text())
        self.assertEqual([q["reused"] for q in sw["points"]], [False, False])
        self.assertEqual(sw["status"], "ok")

    def stopped_particle_run(self, args, d):
        p = start(args + ["--out", str(d)])
        self.assertTrue(wait_for(lambda: frames_started(d)))
        time.sleep(0.5)
        p.send_signal(signal.SIGINT)
        _, err = p.communicate(timeout=TIMEOUT)
        self.assertEqual(p.returncode, 128 + signal.SIGINT, err)
        self.assertTrue((d / ".granvv-checkpoint" / "member_0.h5").exists())

    def resume(self, d):
        return subprocess.run([GRANVV, "resume", str(d), "--quiet", "--no-report"],
                              capture_output=True, text=True, timeout=TIMEOUT)

    def test_a_resume_after_its_table_changed_is_refused(self):
        table, d = self.tmp / "profile.csv", self.tmp / "out"
        write_table(table, 1.0)
        self.stopped_particle_run(md_from_table(table), d)
        write_table(table, 2.0)
        r = self.resume(d)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assert_one_error_line(r.stderr)
        self.assertIn(f"the file {table} changed", r.stderr)
        write_table(table, 1.0)  # the same bytes again: the checkpoint continues
        r = self.resume(d)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertTrue(self.assert_consistent(d, "ok")["md"]["checkpoints"]["resumed"])

    def test_a_resume_of_an_edited_checkpoint_case_is_refused(self):
        d = self.tmp / "out"
        self.stopped_particle_run(MD_RESUMABLE + ["--set", "md.checkpoint_interval=1000"], d)
        case = d / ".granvv-checkpoint" / "case.toml"
        text = case.read_text()
        self.assertIn("restitution = 0.9", text)
        # r and q edited together (one gas, r = 1 - 2q), so that the case itself loads.
        self.assertIn("q = 0.05", text)
        case.write_text(text.replace("restitution = 0.9", "restitution = 0.5", 1)
                        .replace("q = 0.05", "q = 0.25", 1))
        r = self.resume(d)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assert_one_error_line(r.stderr)
        self.assertIn("then, 0.5 now", r.stderr)
        # A member file of another checkpoint (other inputs) is not continued either.
        case.write_text(text)
        inputs = d / ".granvv-checkpoint" / "inputs.json"
        inputs.write_text(inputs.read_text() + " ")
        r = self.resume(d)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assert_one_error_line(r.stderr)
        self.assertIn("not written for the inputs", r.stderr)


# Inelastic collapse in the event-driven engine: restitution 0.1 without the collapse rule in a
# gas at area fraction 0.3 (10^4 disks, md_haff's box). With segments of 20 time units the
# segment's own budget alone (md.max_collision_rate N dt = 2e8 collisions) took many minutes.
COLLAPSE = ["md_haff", "--set", "md.engine=event_driven", "--set", "physics.q=0.45",
            "--set", "md.restitution=0.1", "--set", "md.collapse_speed=0",
            "--set", "md.area_fraction=0.3", "--set", "md.sample_interval=20",
            "--quiet", "--no-report"]


class EventDrivenSegments(FolderState):
    """Inside a segment of the event-driven engine the run looks at signals and progress, and a
    collapse (events piling up while the clock stalls) ends the run (md_bridge/event_driven_engine)."""

    def test_inelastic_collapse_ends_the_run_with_its_reason(self):
        d = self.tmp / "out"
        begin = time.monotonic()
        r = run(COLLAPSE + ["--out", str(d)])
        self.assertEqual(r.returncode, 1, r.stderr)
        s = summary(d)
        self.assertEqual(s["status"], "failed")
        self.assertIn("event-rate runaway", s["error"])
        self.assertIn("inelastic collapse", s["error"])
        # 10^5 collisions make the rule's window: about 2 s (measured on an idle core), where
        # the run went on for minutes before.
        self.assertLess(time.monotonic() - begin, 60)

    def test_sigint_inside_a_long_segment_stops_the_run(self):
        d = self.tmp / "out"
        # One segment of 50000 time units of a nearly elastic gas at area fraction 0.3: about
        # 4e7 collisions (25 s at the 1.6e6 collisions/s of an idle core) between two samples.
        p = start(["md_haff", "--set", "md.engine=event_driven", "--set", "md.ensemble=1",
                   "--set", "md.restitution=0.99", "--set", "md.area_fraction=0.3",
                   "--set", "md.t_end=50000", "--set", "md.sample_interval=50000",
                   "--set", "md.output_times=[0.0,50000.0]", "--set", "compare.enabled=false",
                   "--quiet", "--no-report", "--out", str(d)])
        time.sleep(4.0)  # the hydro runs and the disks are set up within about 2 s
        self.assertIsNone(p.poll())
        p.send_signal(signal.SIGINT)
        stopped = time.monotonic()
        _, err = p.communicate(timeout=TIMEOUT)
        self.assertEqual(p.returncode, 128 + signal.SIGINT, err)
        self.assertLess(time.monotonic() - stopped, 10.0)  # within one check of 65536 events
        self.assertEqual(summary(d / "interrupted-run")["status"], "interrupted")

    def test_a_kill_inside_a_long_segment_resumes_with_the_same_digits(self):
        # One segment of 12000 time units (about 8e6 collisions of 10^4 disks, several seconds)
        # between the samples at t = 0 and 12000, checkpointed every 0.5 s of wall time: the
        # checkpoints fall inside the segment. The engine saves its whole state (every disk's
        # flight, cell, prediction and calendar entry, and the segment's sums so far), so the
        # killed and resumed run must give the uninterrupted run's numbers bit for bit.
        args = ["md_haff", "--set", "md.engine=event_driven", "--set", "md.ensemble=1",
                "--set", "md.restitution=0.99", "--set", "md.area_fraction=0.3",
                "--set", "md.t_end=12000", "--set", "md.sample_interval=12000",
                "--set", "md.snapshot_interval=12000", "--set", "md.output_times=[0.0,12000.0]",
                "--set", "md.checkpoint_interval=0.5", "--set", "compare.enabled=false",
                "--quiet", "--no-report"]
        whole = self.tmp / "whole"
        r = run(args + ["--out", str(whole)])
        self.assertEqual(r.returncode, 0, r.stderr)
        d = self.tmp / "killed"
        p = start(args + ["--out", str(d)])
        member = d / ".granvv-checkpoint" / "member_0.h5"

        def inside_the_segment():
            try:
                with h5py.File(member, "r") as f:
                    numbers = dict(zip([n.decode() if isinstance(n, bytes) else n
                                        for n in f["engine/names"][()]], f["engine/values"][()]))
                    return f.attrs["t"] == 0.0 and numbers.get("segment_time", 0.0) > 0.0
            except (OSError, KeyError):
                return False
        self.assertTrue(wait_for(inside_the_segment, 120), "no checkpoint inside the segment")
        p.kill()
        p.communicate(timeout=TIMEOUT)
        self.assertFalse((d / "summary.json").exists())
        r = subprocess.run([GRANVV, "resume", str(d), "--quiet", "--no-report"],
                           capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(r.returncode, 0, r.stderr)
        s = self.assert_consistent(d, "ok")
        c = s["md"]["checkpoints"]
        self.assertTrue(c["resumed"])
        self.assertGreater(c["resumed_t"], 0.0)  # continued from inside the segment
        self.assertLess(c["resumed_t"], 12000.0)
        w = summary(whole)["md"]
        self.assertEqual(s["md"]["steps"], w["steps"])
        for key in ("haff_t0_measured", "events", "collisions"):
            if key in w:
                self.assertEqual(s["md"][key], w[key], key)

        def datasets(path, group):
            out = {}
            with h5py.File(path, "r") as f:
                f[group].visititems(lambda name, o: out.__setitem__(name, o[()])
                                    if isinstance(o, h5py.Dataset) else None)
            return out
        a, b = datasets(whole / "results.h5", "md"), datasets(d / "results.h5", "md")
        self.assertEqual(sorted(a), sorted(b))
        compared = 0
        for name in a:
            if a[name].dtype.kind != "f" or "wall" in name:
                continue
            self.assertTrue(np.array_equal(a[name], b[name], equal_nan=True), name)
            compared += 1
        self.assertGreater(compared, 10)
        with h5py.File(whole / "particles.h5", "r") as f, h5py.File(d / "particles.h5", "r") as g:
            for q in ("position", "velocity"):
                x, y = f[f"particles/all/{q}/value"][()], g[f"particles/all/{q}/value"][()]
                self.assertEqual(x.shape, y.shape)
                self.assertTrue(np.array_equal(x, y), q)  # the disks at t = 12000, every digit


class MpiCommands(FolderState):
    """`granvv atlas` and `granvv sweep` under mpirun: rank 0 alone locks and writes, every rank
    ends with its exit code (app/mpi_ranks.hpp)."""

    MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", "2"]

    def test_an_atlas_under_mpirun_writes_its_atlas(self):
        d = self.tmp / "atlas"
        r = subprocess.run(self.MPIRUN + [GRANVV, "atlas"] + InputFingerprints.ATLAS +
                           ["--out", str(d)], capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("another granvv process", r.stderr)
        self.assertEqual(r.stderr.count("atlas: wrote"), 1, r.stderr)
        self.assertIn("ladder", json.loads((d / "atlas.json").read_text()))

    def sweep_of_two_points(self, case, swept):
        """A two-point sweep under mpirun: exit 0, sweep.json and both points ok; its stderr."""
        d = self.tmp / "sweep"
        r = subprocess.run(self.MPIRUN + [GRANVV, "sweep"] + case +
                           ["--set", swept, "--out", str(d)],
                           capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(r.returncode, 0, r.stderr)
        sw = json.loads((d / "sweep.json").read_text())
        self.assertEqual(sw["status"], "ok")
        self.assertEqual([q["status"] for q in sw["points"]], ["ok", "ok"])
        return r.stderr

    def test_a_sweep_under_mpirun_completes(self):
        err = self.sweep_of_two_points(QUICK, "hydro.cells=32,48")
        self.assertEqual(err.count("sweep: wrote"), 1, err)

    def test_a_particle_sweep_under_mpirun_completes(self):
        self.sweep_of_two_points(MD_QUICK, "md.seed=1,2")


# A scene's input files and formulas as a new user writes them: each refused with one line and
# exit 2 before anything is written, or run with the totals the fields hold.
TINY = ["--set", "hydro.cells=64", "--set", "convergence.cells=[]", "--set", "hydro.t_end=0.01",
        "--set", "hydro.output_times=[0.01]", "--quiet", "--no-report"]


def initial(kind, path, *more):
    out = ["--set", f'initial.type="{kind}"', "--set", f'initial.from="{path}"']
    for m in more:
        out += ["--set", m]
    return out


def write_csv(path, columns, rows, prefix=b""):
    text = ",".join(columns) + "\n" + "".join(",".join(repr(float(v)) for v in r) + "\n"
                                              for r in rows)
    Path(path).write_bytes(prefix + text.encode())


class InputFiles(FolderState):
    def refused(self, args, *needles):
        d = self.tmp / "refused"
        r = run(args + ["--out", str(d)])
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assert_one_error_line(r.stderr)
        self.assertLess(len(r.stderr), 600, r.stderr)
        for needle in needles:
            self.assertIn(needle, r.stderr)
        self.assertFalse(d.exists(), "a refused run made its output folder")
        return r.stderr

    def snapshot(self):
        """A hydro run's results.h5 with a snapshot at t = 0.25."""
        d = self.tmp / "source"
        self.good_run(d)
        return d / "results.h5"

    def test_snapshot_without_or_with_short_density(self):
        source = self.snapshot()
        missing, short = self.tmp / "missing_n.h5", self.tmp / "short_n.h5"
        shutil.copy(source, missing)
        shutil.copy(source, short)
        with h5py.File(missing, "a") as f:
            del f["hydro/fields/n"]
        with h5py.File(short, "a") as f:
            n = f["hydro/fields/n"][()]
            del f["hydro/fields/n"]
            f["hydro/fields/n"] = n[:, :10]
        for path in (missing, short):
            self.refused(["single_mode"] + initial("snapshot", path, "initial.time=0.25") + TINY,
                         "initial.from", "column n has")

    def test_table_declaring_2_to_the_40_rows(self):
        path = self.tmp / "huge.h5"
        with h5py.File(path, "w") as f:
            f.create_dataset("x", shape=(2**40,), chunks=(1024,), dtype="f8")
            for c in ("n", "v_x", "T"):
                f[c] = np.ones(8)
        self.assertLess(path.stat().st_size, 20000)
        for extra in (["--dry-run"], TINY):
            self.refused(["haff"] + initial("table", path) + extra, "initial.from", "declares")

    def test_table_of_strings(self):
        path = self.tmp / "strings.h5"
        with h5py.File(path, "w") as f:
            f["x"] = np.array([b"a", b"b", b"c", b"d"])
            for c in ("n", "v_x", "T"):
                f[c] = np.ones(4)
        self.refused(["haff"] + initial("table", path) + ["--dry-run"], "does not hold numbers")

    def test_csv_with_byte_order_mark_runs(self):
        path = self.tmp / "bom.csv"
        x = np.arange(16) / 16 - 0.5
        write_csv(path, ["x", "n", "v_x", "T"],
                  [(a, 1 + 0.1 * np.cos(2 * np.pi * a), 0, 1) for a in x], prefix=b"\xef\xbb\xbf")
        d = self.tmp / "bom"
        r = run(["haff"] + initial("table", path) + TINY + ["--out", str(d)])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(summary(d)["status"], "ok")
        path.write_bytes(b"\xff\xfe" + "x,n,v_x,T\n".encode("utf-16-le"))
        self.refused(["haff"] + initial("table", path) + ["--dry-run"], "UTF-16")

    def test_snapshot_held_open_for_writing(self):
        path = self.tmp / "writing.h5"
        shutil.copy(self.snapshot(), path)
        env = dict(os.environ)
        env.pop("HDF5_USE_FILE_LOCKING", None)
        holder = subprocess.Popen(
            [sys.executable, "-c", "import h5py, sys, time\n"
             "f = h5py.File(sys.argv[1], 'a'); print('open', flush=True); time.sleep(60)", str(path)],
            stdout=subprocess.PIPE, text=True, env=env)
        try:
            self.assertEqual(holder.stdout.readline().strip(), "open")
            self.refused(["single_mode"] + initial("snapshot", path, "initial.time=0.25") + TINY,
                         "open for writing in another process")
        finally:
            holder.kill()
            holder.wait()

    def test_formula_longer_than_the_parser_takes(self):
        formula = "1" + "+0*x" * 6000  # 24001 characters
        err = self.refused(["haff", "--set", 'initial.type="expression"', "--set",
                            f'initial.density="{formula}"', "--dry-run"], "initial.density",
                           "characters long")
        self.assertEqual(err.count("characters long"), 1, err)

    def test_nan_between_the_check_points_is_refused_before_the_run(self):
        # NaN on a set between the 8193 check points (and the sampler's own grid), in a
        # particle scene that checkpoints: refused with the key, and nothing to resume.
        v = "0.1*sin(2*pi*x) + ((abs(x) < 0.25 && abs(sin(16384*pi*(x+0.5))) > 0.9) ? 0/0 : 0)"
        err = self.refused(MD_QUICK + ["--set", 'initial.type="expression"', "--set",
                                       f'initial.velocity="{v}"', "--set",
                                       "md.checkpoint_interval=0.3"], "initial.velocity",
                           "velocity is", "between the points it was checked at")
        self.assertNotIn("resume", err)

    def test_nan_velocity_at_one_hydro_node_is_named(self):
        # A node of the 500-cell mesh (x = 0.001) that no check point is near.
        v = "(abs(x - 0.001) < 1e-6) ? 0/0 : 0.01*sin(2*pi*x)"
        self.refused(["single_mode", "--set", "convergence.cells=[]", "--set",
                      'initial.type="expression"', "--set", f'initial.velocity="{v}"',
                      "--quiet", "--no-report"], "initial.velocity", "velocity is", "x = ")

    def assert_totals(self, d):
        """The hydro's initial cells hold the integrals of the fields to 1e-12."""
        t = summary(d)["hydro"]["initial_totals"]
        g = t["given"]
        self.assertLessEqual(t["relative_difference"], 1e-12, t)
        self.assertAlmostEqual(t["mass"], g["mass"], delta=1e-12 * g["mass"])
        self.assertAlmostEqual(t["energy"], g["energy"], delta=1e-12 * g["energy"])
        return t

    def test_table_mean_density_is_that_of_the_interpolant(self):
        # Four irregular rows whose trapezoid mean is 1: the monotone cubic holds another mass.
        path = self.tmp / "irregular.csv"
        x, n = np.array([-0.5, -0.2, 0.0, 0.45]), np.array([0.5, 1.0, 4.0, 0.5])
        xx, nn = np.append(x, x[0] + 1), np.append(n, n[0])
        n = n / np.sum(0.5 * np.diff(xx) * (nn[1:] + nn[:-1]))
        write_csv(path, ["x", "n", "v_x", "T"], [(a, b, 0, 1) for a, b in zip(x, n)])
        err = self.refused(["haff"] + initial("table", path) + ["--dry-run"], "mean density",
                           "divide n by")
        divisor = float(err.split("divide n by ")[1].split()[0])
        write_csv(path, ["x", "n", "v_x", "T"], [(a, b / divisor, 0, 1) for a, b in zip(x, n)])
        d = self.tmp / "irregular"
        r = run(["haff"] + initial("table", path) + TINY + ["--out", str(d)])
        self.assertEqual(r.returncode, 0, r.stderr)
        t = self.assert_totals(d)
        self.assertAlmostEqual(t["mass"], 1.0, delta=1e-3)

    def test_snapshot_of_a_steep_state_conserves_or_is_refused(self):
        # single_mode's own outputs up to t = 3.225 continue onto 500 uniform cells with the
        # snapshot's mass (the cells integrate the interpolant exactly); its last state, whose
        # cells are too uneven to interpolate with mean density 1, is refused.
        d = self.tmp / "steep"
        r = run(["single_mode", "--set", "convergence.cells=[]", "--quiet", "--no-report",
                 "--out", str(d)])
        self.assertEqual(r.returncode, 0, r.stderr)
        source = d / "results.h5"
        with h5py.File(source, "r") as f:
            last = float(f["hydro/fields/t"][-1])
        more = ["--set", "convergence.cells=[]", "--set", "hydro.t_end=0.01", "--set",
                "hydro.output_times=[0.01]", "--quiet", "--no-report"]
        self.refused(["single_mode"] + initial("snapshot", source, "initial.time=%r" % last) +
                     more, "initial.from", "mean density", "choose an earlier initial.time")
        for t in (1.0, 3.2, 3.225):
            c = self.tmp / "continued"
            r = run(["single_mode"] + initial("snapshot", source, "initial.time=%r" % t) + more +
                    ["--out", str(c)])
            self.assertEqual(r.returncode, 0, r.stderr)
            totals = self.assert_totals(c)
            self.assertAlmostEqual(totals["mass"], 1.0, delta=1e-3)
            shutil.rmtree(c)

    def test_transverse_velocity_of_a_table_or_formula(self):
        path = self.tmp / "vy.csv"
        x = np.arange(16) / 16 - 0.5
        write_csv(path, ["x", "n", "v_x", "v_y", "T"],
                  [(a, 1, 0, 0.01 * np.sin(2 * np.pi * a), 1) for a in x])
        self.refused(["haff"] + initial("table", path) + ["--dry-run"], "v_y column",
                     "hydro.transverse_velocity = true")
        formula = ["--set", 'initial.type="expression"', "--set",
                   'initial.transverse_velocity="0.01*sin(2*pi*x)"']
        self.refused(["haff"] + formula + ["--dry-run"], "initial.transverse_velocity",
                     "hydro.transverse_velocity = true")
        # Both kinds are taken by the hydro when it carries v_y, and its momentum is theirs.
        for args in (initial("table", path), formula):
            d = self.tmp / "vy_run"
            r = run(["haff"] + args + ["--set", "hydro.transverse_velocity=true"] + TINY +
                    ["--out", str(d)])
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assert_totals(d)
            shutil.rmtree(d)
        # Two transverse velocities: refused, naming both keys.
        self.refused(["haff"] + formula + ["--set", "initial.transverse_amplitude=0.02", "--set",
                                           "hydro.transverse_velocity=true", "--dry-run"],
                     "initial.transverse_amplitude", "initial.transverse_velocity")


class StatusesThatCouldOverstate(FolderState):
    def test_atlas_with_no_budget_does_not_claim_convergence(self):
        d = self.tmp / "atlas"
        r = subprocess.run([GRANVV, "atlas", "haff", "--budget", "1e-9", "--quiet", "--out",
                            str(d)], capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(d / "atlas.json") as f:
            reference = json.load(f)["reference"]
        self.assertEqual(reference["convergence"], {})
        self.assertIsNone(reference["converged_to_tolerance"])
        self.assertIn("not measured", reference["converged_reason"])

    def test_elastic_gas_has_no_haff_deviation(self):
        d = self.tmp / "elastic"
        r = run(MD_QUICK + ["--set", "md.restitution=1", "--out", str(d)])
        self.assertEqual(r.returncode, 0, r.stderr)
        md = summary(d)["md"]
        for key in ("haff_t0_deviation", "haff_t0_deviation_paper", "haff_t0_deviation_dilute",
                    "haff_t0_theory", "haff_t0_within_tolerance"):
            self.assertIsNone(md[key], key)


if __name__ == "__main__":
    GRANVV = str(Path(sys.argv.pop(1)).resolve())
    unittest.main(verbosity=2)
