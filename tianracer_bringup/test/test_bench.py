"""The benchmark harness end to end at a tiny duration, as a user runs it from a shell whose
python3 is not the system one: both sides produce their figures and the table is written.
No timing is asserted: figures are for the benchmark, not for tests."""
import os
import shutil
import subprocess
import tempfile
import unittest

from tianracer_sim.script_module import load_script

HERE = os.path.dirname(os.path.abspath(__file__))
BENCH = os.path.join(os.path.dirname(HERE), "bench")
HARNESS = os.path.join(BENCH, "run_benchmarks")
COMMITTED = os.path.join(BENCH, "results.md")


class BenchHarnessTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="test_bench_")
        # A python3 first on PATH that sees neither ROS nor numpy nor pybullet (the system
        # interpreter without site-packages), as a pyenv or conda python3 would.
        shim = os.path.join(cls.tmp, "bin")
        os.makedirs(shim)
        with open(os.path.join(shim, "python3"), "w") as f:
            f.write('#!/bin/sh\nexec /usr/bin/python3 -S -E "$@"\n')
        os.chmod(os.path.join(shim, "python3"), 0o755)
        cls.env = dict(os.environ, PATH=shim + ":" + os.environ["PATH"], ROS_HOSTNAME="localhost")
        cls.env.pop("ROS_IP", None)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def harness(self, *args, timeout=240):
        # Run as a user does: the script's '#!/usr/bin/env python3' picks the shim.
        p = subprocess.run([HARNESS] + list(args), env=self.env, capture_output=True, text=True,
                           timeout=timeout)
        return p.returncode, p.stdout + p.stderr

    def test_the_header_names_each_scenarios_own_world_and_model(self):
        harness = load_script(HARNESS)
        self.assertEqual(harness.own_content(["physics", "lidar", "full"]), "")
        text = harness.own_content(["physics", "lane_track", "boxes", "lidar3d"])
        self.assertEqual(text, " unless named (lane_track: world lane_track; "
                               "boxes: world bench/worlds/free_boxes.world; "
                               "lidar3d: model bench/models/tianracer_lidar3d.xacro)")

    def test_the_shim_is_not_the_pybullet_interpreter(self):
        p = subprocess.run(["python3", "-c", "import numpy"], env=self.env, capture_output=True)
        self.assertNotEqual(p.returncode, 0, "the shim python3 should not import numpy")

    def test_tiny_run_writes_both_sides_and_compares(self):
        out_md = os.path.join(self.tmp, "results.md")
        rc, out = self.harness("--duration", "0.5", "--scenarios", "physics,lidar", "--first-scan-runs", "1",
                               "--no-install", "--output", out_md, "--compare", COMMITTED)
        self.assertEqual(rc, 0, out)
        self.assertRegex(out, r"interpreters: PyBullet side \S+bench_venv/bin/python \(Python [\d.]+, "
                              r"pybullet 3\.2\.7, numpy [\d.]+\); ROS side /usr/bin/python3")
        text = open(out_md).read()
        rows = {}
        for line in text.splitlines():
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if line.startswith("|") and len(cells) == 10:
                rows[cells[0]] = cells
        for title in ("physics only", "physics + lidar (1081 beams, 40 Hz)"):
            self.assertIn(title, rows, text)
            ours, pybullet = rows[title][1], rows[title][2]
            self.assertRegex(ours, r"^\d+\.\d\d$", "ours has no figure in: %s" % rows[title])
            self.assertRegex(pybullet, r"^\d+\.\d\d$", "PyBullet has no figure in: %s" % rows[title])
        self.assertRegex(text, r"Machine: \d+ cores, CPU model: .+,")
        self.assertRegex(text, r"Speed index of this machine \(PyBullet physics only.*\): \d+\.\d\d sim s/wall s")
        self.assertRegex(text, r"Launch to first /scan .* median \d+\.\d\d s")
        # --compare: one line per figure against the committed table
        self.assertIn("Change against %s" % COMMITTED, out)
        self.assertRegex(out, r"physics only: ours sim s/wall s +\d+\.\d\d -> \d+\.\d\d +[+-]\d+\.\d %")

    def test_profile_writes_the_per_step_table_between_the_markers(self):
        doc = os.path.join(self.tmp, "performance.md")
        with open(doc, "w") as f:
            f.write("# Performance\n\nbefore\n\n<!-- step profile: begin (tianracer_bringup/bench/"
                    "run_benchmarks --profile FILE) -->\nold table\n<!-- step profile: end -->\n\nafter\n")
        untouched = os.path.join(self.tmp, "not_written.md")
        rc, out = self.harness("--duration", "0.5", "--scenarios", "physics,lidar", "--profile", doc,
                               "--output", untouched)
        self.assertEqual(rc, 0, out)
        self.assertFalse(os.path.exists(untouched), "a profiled run leaves the results file alone")
        text = open(doc).read()
        self.assertTrue(text.startswith("# Performance\n\nbefore\n"), text)
        self.assertTrue(text.rstrip().endswith("after"), text)
        self.assertNotIn("old table", text)
        rows = {}
        for line in text.splitlines():
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if line.startswith("|") and len(cells) == 3:
                rows[cells[0]] = cells[1:]
        self.assertIn("physics: Bullet stepSimulation", rows, text)
        for cell in rows["physics: Bullet stepSimulation"]:
            self.assertRegex(cell, r"^\d+\.\d\d \(1\)$")  # once per step, in both scenarios
        self.assertEqual(rows["sensor lidar: sample (cast, measure)"][0], "", text)  # no lidar in "physics"
        self.assertRegex(rows["sensor lidar: sample (cast, measure)"][1], r"^\d+\.\d\d \(0\.0[34]\d*\)$")
        self.assertRegex(rows["step outside Bullet"][0], r"^\*\*\d+\.\d\d\*\*$")
        self.assertRegex(rows["node CPU (all threads, /proc) per step"][0], r"^\d+\.\d$")

    def test_compare_two_files_without_running(self):
        rc, out = self.harness("--compare", COMMITTED, COMMITTED, timeout=60)
        self.assertEqual(rc, 0, out)
        self.assertRegex(out, r"full seed sensor set: ours sim s/wall s +\d+\.\d\d -> \d+\.\d\d +\+0\.0 %")

    def test_missing_environment_names_the_command(self):
        venv = os.path.join(self.tmp, "no_such_venv")
        rc, out = self.harness("--duration", "0.5", "--scenarios", "physics", "--no-install", "--venv", venv,
                               "--output", os.path.join(self.tmp, "never.md"), timeout=60)
        self.assertEqual(rc, 2, out)
        self.assertIn("run_benchmarks --install-only --venv %s" % venv, out)
        self.assertFalse(os.path.exists(os.path.join(self.tmp, "never.md")))
        self.assertNotIn("|", out)  # no table, not even a half one

    def test_boxes_and_3d_lidar_rows(self):
        # The 50 free boxes (a world scenario) and the 16 x 1800 3D lidar (a model scenario): both
        # sides give figures, and the car has moved boxes on both sides by the end (a scenario
        # whose car never reaches them would measure nothing). --compare against the committed
        # table, which has neither row, still works.
        out_md = os.path.join(self.tmp, "new_rows.md")
        rc, out = self.harness("--duration", "1.5", "--scenarios", "boxes,lidar3d", "--first-scan-runs", "0",
                               "--no-install", "--output", out_md, "--compare", COMMITTED, timeout=400)
        self.assertEqual(rc, 0, out)
        with open(out_md) as f:
            text = f.read()
        header, rows = None, {}
        for line in text.splitlines():
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if not line.startswith("|"):
                continue
            if cells[0] == "scenario":
                header = cells
            elif header and not set(cells[0]) <= set("-: "):
                rows[cells[0]] = dict(zip(header, cells))
        for title in ("50 free boxes in the car's path, physics only",
                      "physics + lidar + 3D lidar (16 x 1800 rays, 10 Hz)"):
            self.assertIn(title, rows, text)
            for col in ("ours sim s/wall s", "PyBullet sim s/wall s"):
                self.assertRegex(rows[title][col], r"^\d+\.\d\d$", "%s has no figure in: %s" % (col, rows[title]))
            self.assertRegex(rows[title]["ratio"], r"^\d+\.\d\d×$", rows[title])
        import re
        m = re.search(r"50 free boxes in the car's path, physics only: free models that moved more than 1 cm by "
                      r"the end of the run: ours (\d+) of 50, PyBullet (\d+) of 50\.", text)
        self.assertIsNotNone(m, "no line of moved boxes in:\n" + text)
        self.assertGreater(int(m.group(1)), 0, "the car moved no box in our simulator:\n" + text)
        self.assertGreater(int(m.group(2)), 0, "the car moved no box in PyBullet:\n" + text)
        # Ours published the 3D lidar's clouds (the rate the client counts is not asserted) and
        # PyBullet cast it at 10 Hz.
        m = re.search(r"physics \+ lidar \+ 3D lidar [^\n]*, messages received [^\n]*/velodyne_points (\d+\.\d)/s", text)
        self.assertIsNotNone(m, "ours published no /velodyne_points:\n" + text)
        self.assertGreater(float(m.group(1)), 0.0, text)
        self.assertRegex(text, r"physics \+ lidar \+ 3D lidar .*, PyBullet: lidar \d+ calls .*, lidar3d 1[56] calls")
        self.assertIn("Change against %s" % COMMITTED, out)
        # The committed table has these rows too: the new run is compared with them.
        self.assertRegex(out, r"50 free boxes in the car's path, physics only: ours sim s/wall s +"
                              r"\d+\.\d\d -> \d+\.\d\d")


if __name__ == "__main__":
    unittest.main()
