"""The benchmark harness end to end at a tiny duration, as a user runs it from a shell whose
python3 is not the system one: every side (ours, PyBullet, MuJoCo) produces its figures and the
table is written. No timing is asserted: figures are for the benchmark, not for tests."""
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

from tianracer_sim.script_module import load_script

HERE = os.path.dirname(os.path.abspath(__file__))
BENCH = os.path.join(os.path.dirname(HERE), "bench")
HARNESS = os.path.join(BENCH, "run_benchmarks")
COMMITTED = os.path.join(BENCH, "results.md")
sys.path.insert(0, BENCH)
import lap  # noqa: E402

# The harness's last lines, one per peer (issue 41): `vs MuJoCo: physics 1.05x, lidar 2.30x, 8 cars 1.10x`.
VS = r"^vs (PyBullet|MuJoCo): ((physics|lidar|8 cars) \d+\.\d\dx)(, (physics|lidar|8 cars) \d+\.\d\dx)*$"


def table_rows(text):
    """{scenario title: {column: cell}} of the results file's table."""
    header, rows = None, {}
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if not line.startswith("|"):
            continue
        if cells[0] == "scenario":
            header = cells
        elif header and not set(cells[0]) <= set("-: "):
            rows[cells[0]] = dict(zip(header, cells))
    return rows


def last_lines(out, n):
    return [line for line in out.splitlines() if line.strip()][-n:]


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

    def test_the_targets_are_spec_9s(self):
        # SPEC §9: the full seed set has two goals (RTF 2 on 2 cores and 15x PyBullet); the report
        # gives each its verdict, and a scenario with one goal keeps the one-pair form.
        harness = load_script(HARNESS)
        self.assertEqual(harness.targets("full"), (("rtf", 2.0), ("ratio", 15.0)))
        self.assertEqual(harness.targets("lidar"), (("ratio", 10.0),))
        self.assertEqual(harness.targets("cars8"), (("rtf", 3.0),))

        def side(rtf):
            return dict(rtf=rtf, sim_seconds=10.0, sim_cpu_seconds=10.0 / rtf, cpu_seconds=10.0 / rtf)
        f = harness.figures("full", dict(ours=side(2.1), pybullet=side(0.15)))
        self.assertEqual(harness.target_cell("full", f), "RTF ≥ 2 (met); ratio ≥ 15× (**not met**)")
        f = harness.figures("lidar", dict(ours=side(20.0), pybullet=side(1.9), mujoco=side(10.5)))
        self.assertEqual(harness.target_cell("lidar", f), "ratio ≥ 10× (met); ≥ 2× MuJoCo (**not met**)")
        self.assertEqual(harness.target_cell("cars8", harness.figures("cars8", dict(ours=None))), "RTF ≥ 3")

    def test_the_last_lines_compare_us_with_each_peer(self):
        harness = load_script(HARNESS)

        def side(rtf, cpu):
            return dict(rtf=rtf, sim_seconds=10.0, sim_cpu_seconds=10.0 / cpu, cpu_seconds=10.0 / cpu)
        results = {"cars8": dict(ours=side(2.0, 2.5), pybullet=side(0.5, 0.5), mujoco=side(2.5, 2.5)),
                   "physics": dict(ours=side(21.0, 24.0), pybullet=side(10.5, 10.5), mujoco=side(20.0, 20.0)),
                   "full": dict(ours=side(2.0, 2.0), pybullet=side(0.1, 0.1)),
                   "lidar": dict(ours=side(18.4, 18.0), pybullet=side(2.0, 2.0), mujoco=side(8.0, 8.0))}
        # Wall-time ratios, in SCENARIOS' order whatever order they ran in; scenarios without a
        # label (full) are not in them.
        self.assertEqual(harness.vs_lines(results), ["vs PyBullet: physics 2.00x, lidar 9.20x, 8 cars 4.00x",
                                                     "vs MuJoCo: physics 1.05x, lidar 2.30x, 8 cars 0.80x"])
        for line in harness.vs_lines(results):
            self.assertRegex(line, VS)
        # A peer that ran none of them has no line; a scenario it did not run is left out.
        del results["lidar"]["mujoco"], results["physics"]["mujoco"], results["cars8"]["mujoco"]
        del results["cars8"]["pybullet"]
        self.assertEqual(harness.vs_lines(results), ["vs PyBullet: physics 2.00x, lidar 9.20x"])

    def test_repeats_give_the_median_run_and_the_range(self):
        harness = load_script(HARNESS)

        def ours(rtf, cpu):
            return dict(rtf=rtf, sim_seconds=10.0, sim_cpu_seconds=10.0 / cpu, tag=rtf)
        # Three runs: the median by sim s/wall s is the run as a whole (its CPU figure too, not
        # the median of the CPU figures); the spread is each figure's lowest-highest.
        med = harness.median_run([ours(9.0, 12.0), ours(11.0, 10.0), ours(8.0, 11.0)], "sim_cpu_seconds")
        self.assertEqual(med["tag"], 9.0)
        self.assertEqual(med["spread"]["runs"], 3)
        self.assertEqual(med["spread"]["rtf"], (8.0, 11.0))
        self.assertAlmostEqual(med["spread"]["cpu"][0], 10.0)
        self.assertAlmostEqual(med["spread"]["cpu"][1], 12.0)
        # An even count takes the lower middle run; one run has no spread.
        self.assertEqual(harness.median_run([ours(5.0, 5.0), ours(7.0, 7.0)], "sim_cpu_seconds")["tag"], 5.0)
        one = harness.median_run([ours(5.0, 5.0)], "sim_cpu_seconds")
        self.assertNotIn("spread", one)
        self.assertEqual(harness.cell(5.0, one, "rtf"), "5.00")
        self.assertEqual(harness.cell(9.0, med, "rtf"), "9.00 (8.00–11.00)")
        self.assertEqual(harness.cell(12.0, med, "cpu"), "12.00 (10.00–12.00)")
        self.assertEqual(harness.cell(None, None, "rtf"), "—")

    def test_repeat_runs_each_side_several_times(self):
        out_md = os.path.join(self.tmp, "repeat.md")
        rc, out = self.harness("--duration", "0.3", "--scenarios", "physics", "--repeat", "3", "--no-pybullet",
                               "--first-scan-runs", "0", "--output", out_md)
        self.assertEqual(rc, 0, out)
        self.assertEqual(len(re.findall(r"\[physics\] ours: \d+\.\d\d sim s/wall s", out)), 3, out)
        self.assertIn("(run 3 of 3)", out)
        with open(out_md) as f:
            text = f.read()
        cell = table_rows(text)["physics only"]["ours sim s/wall s"]
        m = re.match(r"^(\d+\.\d\d) \((\d+\.\d\d)–(\d+\.\d\d)\)$", cell)
        self.assertIsNotNone(m, cell)
        lo, med, hi = float(m.group(2)), float(m.group(1)), float(m.group(3))
        self.assertTrue(lo <= med <= hi, cell)
        self.assertIn("ran 3 times, interleaved", text)
        rc, out = self.harness("--repeat", "0", "--no-pybullet", timeout=60)
        self.assertEqual(rc, 2, out)
        self.assertIn("--repeat must be 1 or more (got 0)", out)

    def test_a_lap_is_measured_from_the_track(self):
        # A car on a circle of radius 1.3 m at 1 m/s, sampled at 50 Hz for 10 s: the start (before
        # lap.SETTLE) is left out, so a slow start does not count.
        track = []
        for k in range(501):
            t = k * 0.02
            a = t / 1.3 if t >= lap.SETTLE else 0.0
            track.append((t, 1.3 * math.sin(a), 1.3 * (1 - math.cos(a)), 1.0))
        one = lap.lap(track)
        self.assertAlmostEqual(one["speed"], 1.0, delta=1e-3)
        self.assertAlmostEqual(one["radius"], 1.3, delta=1e-6)
        self.assertFalse(one["flipped"])
        self.assertEqual((one["start"], one["end"]), (lap.SETTLE, 10.0))
        track[200] = track[200][:3] + (-0.9,)  # upside down once
        self.assertTrue(lap.lap(track)["flipped"])
        self.assertIsNone(lap.fit_circle([(0, 0), (1, 1), (2, 2)]))  # a straight line has no radius
        self.assertEqual(lap.parse_poses("-5.1,-3.75,0 1,2,0.5"), [(-5.1, -3.75, 0.0), (1.0, 2.0, 0.5)])
        for bad in ("1,2", "1,2,x", "1,2,nan", ""):
            with self.assertRaises(ValueError):
                lap.parse_poses(bad)

    def test_the_shim_is_not_the_pybullet_interpreter(self):
        p = subprocess.run(["python3", "-c", "import numpy"], env=self.env, capture_output=True)
        self.assertNotEqual(p.returncode, 0, "the shim python3 should not import numpy")

    def test_tiny_run_writes_both_sides_and_compares(self):
        out_md = os.path.join(self.tmp, "results.md")
        rc, out = self.harness("--duration", "0.5", "--scenarios", "physics,lidar", "--first-scan-runs", "1",
                               "--lap-seconds", "2", "--no-install", "--output", out_md, "--compare", COMMITTED)
        self.assertEqual(rc, 0, out)
        self.assertRegex(out, r"interpreters: PyBullet and MuJoCo side \S+bench_venv/bin/python \(Python [\d.]+, "
                              r"pybullet 3\.2\.7, mujoco 4\.0\.0, numpy [\d.]+\); ROS side /usr/bin/python3")
        text = open(out_md).read()
        rows = table_rows(text)
        for title in ("physics only", "physics + lidar (1081 beams, 40 Hz)"):
            self.assertIn(title, rows, text)
            for col in ("ours sim s/wall s", "PyBullet sim s/wall s", "MuJoCo sim s/wall s", "MuJoCo sim s/CPU s"):
                self.assertRegex(rows[title][col], r"^\d+\.\d\d$", "%s has no figure in: %s" % (col, rows[title]))
            self.assertRegex(rows[title]["ratio vs MuJoCo"], r"^\d+\.\d\d×$", rows[title])
        # The targets are SPEC §9's: physics >= 3x PyBullet and >= MuJoCo; lidar >= 10x and >= 2x MuJoCo.
        self.assertRegex(rows["physics only"]["target"], r"^ratio ≥ 3× \(.*\); ≥ 1× MuJoCo \(.*\)$")
        self.assertRegex(rows["physics + lidar (1081 beams, 40 Hz)"]["target"],
                         r"^ratio ≥ 10× \(.*\); ≥ 2× MuJoCo \(.*\)$")
        self.assertRegex(text, r"physics \+ lidar \(1081 beams, 40 Hz\), MuJoCo: lidar (1[89]|2[01]) calls")
        # The lap check: every side drove it, and none turned over.
        m = re.search(r"Lap check .*: ours (\d\.\d+) m/s, radius (\d\.\d+) m, upright; PyBullet \d\.\d+ m/s "
                      r"\([+-]\d+\.\d %\), radius \d\.\d+ m \([+-]\d+\.\d %\), upright: .*; MuJoCo \d\.\d+ m/s "
                      r"\([+-]\d+\.\d %\), radius \d\.\d+ m \([+-]\d+\.\d %\), upright: ", text)
        self.assertIsNotNone(m, "no lap check (or a car turned over) in:\n" + text)
        self.assertGreater(float(m.group(1)), 0.5, "our car did not drive the lap:\n" + text)
        # The racetrack scenarios' single car drives a lap clear of the walls: each side's lap is
        # printed (one figure each, not a range of one car).
        m = re.search(r"physics only: the car's lap \(speed and radius from [\d.]+ to [\d.]+ s\): ours "
                      r"(\d\.\d+) m/s, radius \d\.\d+ m, 0 flipped; PyBullet \d\.\d+ m/s, radius \d\.\d+ m, "
                      r"0 flipped; MuJoCo \d\.\d+ m/s, radius \d\.\d+ m, 0 flipped\.", text)
        self.assertIsNotNone(m, "no lap of the physics scenario's car in:\n" + text)
        # Last, one line per peer, in the form.
        vs = last_lines(out, 2)
        self.assertRegex(vs[0], r"^vs PyBullet: physics \d+\.\d\dx, lidar \d+\.\d\dx$", out)
        self.assertRegex(vs[1], r"^vs MuJoCo: physics \d+\.\d\dx, lidar \d+\.\d\dx$", out)
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
                               "--lap-seconds", "0", "--no-install", "--output", out_md, "--compare", COMMITTED,
                               timeout=400)
        self.assertEqual(rc, 0, out)
        with open(out_md) as f:
            text = f.read()
        rows = table_rows(text)
        for title in ("50 free boxes in the car's path, physics only",
                      "physics + lidar + 3D lidar (16 x 1800 rays, 10 Hz)"):
            self.assertIn(title, rows, text)
            for col in ("ours sim s/wall s", "PyBullet sim s/wall s"):
                self.assertRegex(rows[title][col], r"^\d+\.\d\d$", "%s has no figure in: %s" % (col, rows[title]))
            self.assertRegex(rows[title]["ratio"], r"^\d+\.\d\d×$", rows[title])
        m = re.search(r"50 free boxes in the car's path, physics only: free models that moved more than 1 cm by "
                      r"the end of the run: ours (\d+) of 50, PyBullet (\d+) of 50, MuJoCo (\d+) of 50\.", text)
        self.assertIsNotNone(m, "no line of moved boxes in:\n" + text)
        self.assertGreater(int(m.group(1)), 0, "the car moved no box in our simulator:\n" + text)
        self.assertGreater(int(m.group(2)), 0, "the car moved no box in PyBullet:\n" + text)
        self.assertGreater(int(m.group(3)), 0, "the car moved no box in MuJoCo:\n" + text)
        self.assertRegex(rows["50 free boxes in the car's path, physics only"]["MuJoCo sim s/wall s"], r"^\d+\.\d\d$")
        # MuJoCo has no 3D lidar here: no figure rather than a figure of less work.
        self.assertEqual(rows["physics + lidar + 3D lidar (16 x 1800 rays, 10 Hz)"]["MuJoCo sim s/wall s"], "—")
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

    def test_eight_cars_row_and_their_laps(self):
        # Eight cars with their lidars in one simulator, and in each peer: each side gives its
        # figures, every car drove (our client reads every car's ground truth) and none turned
        # over; the last lines compare the 8 cars only.
        out_md = os.path.join(self.tmp, "cars8.md")
        rc, out = self.harness("--duration", "1.0", "--scenarios", "cars8", "--first-scan-runs", "0",
                               "--lap-seconds", "0", "--no-install", "--output", out_md, timeout=400)
        self.assertEqual(rc, 0, out)
        with open(out_md) as f:
            text = f.read()
        row = table_rows(text)["8 cars, physics + lidar each (1081 beams, 40 Hz)"]
        for col in ("ours sim s/wall s", "PyBullet sim s/wall s", "MuJoCo sim s/wall s"):
            self.assertRegex(row[col], r"^\d+\.\d\d$", "%s has no figure in: %s" % (col, row))
        self.assertIn("RTF ≥ 3", row["target"])
        for topic in ["/scan"] + ["/tianracer_%02d/scan" % k for k in range(2, 9)]:
            self.assertRegex(text, r"8 cars, .*, messages received .* %s (\d+\.\d)/s" % re.escape(topic))
        self.assertRegex(text, r"8 cars, .*, PyBullet: lidar 32\d calls")  # 8 x 41 scans in 1 s
        self.assertRegex(text, r"8 cars, .*, MuJoCo: lidar 32\d calls")
        m = re.search(r"the 8 cars' laps \(.*\): ours (\d\.\d+)(?:-\d\.\d+)? m/s, radius [\d.-]+ m, 0 flipped; "
                      r"PyBullet [\d.-]+ m/s, radius [\d.-]+ m, 0 flipped; MuJoCo [\d.-]+ m/s, radius [\d.-]+ m, "
                      r"0 flipped\.", text)
        self.assertIsNotNone(m, "no laps of the 8 cars (or one turned over) in:\n" + text)
        self.assertGreater(float(m.group(1)), 0.3, "one of our cars did not drive:\n" + text)
        vs = last_lines(out, 2)
        self.assertRegex(vs[0], r"^vs PyBullet: 8 cars \d+\.\d\dx$", out)
        self.assertRegex(vs[1], r"^vs MuJoCo: 8 cars \d+\.\d\dx$", out)


if __name__ == "__main__":
    unittest.main()
