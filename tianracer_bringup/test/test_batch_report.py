"""The pieces of a batch run that need no ROS running: launch file and driver command of a run,
metrics from messages, and the CSV, report and pictures."""
import os
import shutil
import sys
import tempfile
import unittest

from tianracer_bringup import metrics, report
from tianracer_bringup.run import driver_cmd, sim_launch_xml
from tianracer_sim.script_module import load_script

# catkin runs nosetests with -P (no path adjustment): the test folder's helpers by path.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scenario_text import load_text  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


class TestRunFiles(unittest.TestCase):
    def test_params_axis_and_launch_file(self):
        sc, _ = load_text("""\
            base:
              world: racetrack
              duration: 10
              model_args: {robot_namespace: /tianracer}
            matrix:
              params./cmd_vel_node/max_accel: [0.5, 2]
            """)
        xml = sim_launch_xml(sc.runs[1].config)
        self.assertIn('<param name="/cmd_vel_node/max_accel" value="2" />', xml)
        self.assertIn('<arg name="paused" value="true" />', xml)
        self.assertIn('<arg name="real_time_factor" value="0.0" />', xml)
        self.assertIn('robot_namespace:=/tianracer', xml)
        # the parameter is set after the include, so it overrides control.launch's value
        self.assertGreater(xml.index('max_accel'), xml.index('</include>'))

    def test_driver_args(self):
        sc, _ = load_text("""\
            base:
              world: empty
              duration: 1
              driver: {command: [rosrun, pkg, node], args: {speed: 2, fast: true}}
            """)
        self.assertEqual(driver_cmd(sc.runs[0].config, 1234),
                         ['rosrun', 'pkg', 'node', '_speed:=2', '_fast:=true'])


class TestMetrics(unittest.TestCase):
    def drive_circle(self, m, laps, radius=1.0, v=1.0, dt=0.02, start_t=0.0):
        import math
        t = start_t
        n = int(laps * 2 * math.pi * radius / v / dt)
        for k in range(n + 2):
            a = v * t / radius
            # a circle through the spawn point (0, 0), heading +x there
            m.on_truth(t, radius * math.sin(a), radius - radius * math.cos(a), a, v)
            t += dt
        return t

    def test_laps_distance_speed(self):
        m = metrics.Metrics(success={'laps': 2})
        self.drive_circle(m, 2.0, radius=1.5)
        out = m.finish()
        self.assertEqual(out['laps'], 2)
        for lap in out['lap_times']:
            self.assertAlmostEqual(lap, 3 * 3.14159265, delta=0.03)
        self.assertAlmostEqual(out['distance'], 6 * 3.14159265, delta=0.05)
        self.assertAlmostEqual(out['max_speed'], 1.0)
        self.assertTrue(out['success'])
        self.assertEqual(out['collisions'], None)  # not measured

    def test_laps_missing(self):
        m = metrics.Metrics(success={'laps': 3})
        self.drive_circle(m, 1.5, radius=1.5)
        out = m.finish()
        self.assertEqual(out['laps'], 1)
        self.assertFalse(out['success'])
        self.assertIn('1 of 3 laps', out['reason'])

    def test_odometry_drift_in_the_world_frame(self):
        # odom frame at the spawn pose (1, 2, 90 deg): odom (0.5, 0) is world (1, 2.5)
        import math
        m = metrics.Metrics(spawn=(1.0, 2.0, math.pi / 2))
        m.on_truth(0.0, 1.0, 2.0, math.pi / 2, 0.0)
        m.on_truth(1.0, 1.0, 2.6, math.pi / 2, 0.6)
        m.on_odom(1.0, 0.5, 0.0)
        out = m.finish()
        self.assertAlmostEqual(out['odom_drift'], 0.1)
        self.assertAlmostEqual(out['odom_drift_pct'], 100 * 0.1 / 0.6)

    def test_collisions_grouped_per_contact_episode(self):
        m = metrics.Metrics(success={'no_collision': True}, contacts_measured=True)
        m.on_truth(0.0, 0.0, 0.0, 0.0, 0.0)
        for k in range(10):
            m.on_contact(1.0 + 0.001 * k, 'walls::link', 'base_link')
        m.on_contact(1.005, 'box', 'base_link')
        m.on_contact(3.0, 'walls::link', 'base_link')
        m.on_truth(4.0, 0.0, 0.0, 0.0, 0.0)
        out = m.finish()
        self.assertEqual(out['collisions'], 3)
        self.assertEqual(out['first_collision_with'], 'walls::link')
        self.assertAlmostEqual(out['first_collision_time'], 1.0)
        self.assertFalse(out['success'])
        self.assertIn('collided with walls::link at 1.00 s', out['reason'])

    def test_goal_and_clearance_and_user_metric(self):
        m = metrics.Metrics(success={'goal': {'x': 1.0, 'y': 0.0, 'radius': 0.2}, 'stop': True})
        m.add_user_metric('v', 'max')
        m.on_truth(0.0, 0.0, 0.0, 0.0, 0.0)
        self.assertFalse(m.done_early())
        m.on_truth(1.0, 0.85, 0.0, 0.0, 1.0)
        self.assertTrue(m.done_early())
        m.on_scan([float('inf'), 0.5, 0.3, float('-inf'), 0.05], 0.1, 30.0)
        m.on_user('v', 0.4)
        m.on_user('v', 0.9)
        out = m.finish()
        self.assertAlmostEqual(out['goal_time'], 1.0)
        self.assertAlmostEqual(out['min_clearance'], 0.3)
        self.assertEqual(out['v'], 0.9)
        self.assertTrue(out['success'])

    def test_messages_after_the_duration_are_not_counted(self):
        m = metrics.Metrics(duration=1.0)
        for k in range(100):
            m.on_truth(0.5 + 0.02 * k, 0.02 * k, 0.0, 0.0, 1.0)
        m.on_odom(3.0, 5.0, 0.0)
        out = m.finish()
        self.assertTrue(m.ended)
        self.assertAlmostEqual(out['sim_time'], 1.0)
        self.assertAlmostEqual(out['distance'], 1.0)
        self.assertIsNone(out['odom_drift'])

    def test_get_field(self):
        class P:
            x = 1.5
        class M:
            ranges = [3.0, 4.0]
            pose = P()
        self.assertEqual(metrics.get_field(M(), 'pose.x'), 1.5)
        self.assertEqual(metrics.get_field(M(), 'ranges[1]'), 4.0)


class TestReport(unittest.TestCase):
    def test_csv_report_and_pictures_from_results(self):
        sc, _ = load_text("""\
            base: {world: empty, duration: 10}
            matrix:
              seed: [0, 1]
              spawn.x: [0.0, 1.0]
            """)
        results = []
        for i, run in enumerate(sc.runs):
            ok = i != 2
            results.append({
                'id': run.id, 'status': 'ok' if ok else 'failed', 'run_dir': '/tmp/x/' + run.id,
                'reason': 'ran its duration' if ok else 'the driver exited with code 1',
                'wall_time': 5.0, 'run_wall_time': 1.0, 'startup_wall_time': 4.0,
                'leftover_processes': 0, 'host': 'h',
                'log_tails': {} if ok else {'driver': 'Traceback\nboom\n'},
                'metrics': None if not ok else {
                    'sim_time': 10.0, 'distance': 5.0 + i, 'mean_speed': 0.5, 'max_speed': 1.0,
                    'laps': 0, 'lap_times': [], 'best_lap': None, 'collisions': None,
                    'min_clearance': None, 'odom_drift': 0.01 * i, 'success': True,
                    'reason': 'ran its duration', 'path': [[0, 0, 0], [1, 1, 0.5 * i]]}})
        out = tempfile.mkdtemp()
        try:
            rows = report.write_all(out, sc, sc.runs, results, 12.0, 'test')
            self.assertEqual(len(rows), 4)
            with open(os.path.join(out, 'results.csv')) as f:
                lines = f.read().splitlines()
            self.assertEqual(len(lines), 5)
            self.assertTrue(lines[0].startswith('seed,spawn.x,id,label,status,completed'))
            md = open(os.path.join(out, 'report.md')).read()
            self.assertIn('## By seed', md)
            self.assertIn('| 0 | 2 | 2 | 5.50 (5.00 – 6.00)', md)  # seed 0: runs 0 and 1
            self.assertIn('### run_002', md)
            self.assertIn('boom', md)
            self.assertIn('Collisions: not measured', md)
            for png in ('paths_empty.png', 'metrics_vs_seed.png', 'metrics_vs_spawn_x.png'):
                with open(os.path.join(out, png), 'rb') as f:
                    self.assertEqual(f.read(8), b'\x89PNG\r\n\x1a\n')
        finally:
            shutil.rmtree(out)


class TestFollowTheGap(unittest.TestCase):
    """The example driver's choice of direction (tianracer_control/scripts/follow_the_gap)."""

    @classmethod
    def setUpClass(cls):
        cls.ftg = load_script(os.path.join(HERE, '..', '..', 'tianracer_control', 'scripts',
                                           'follow_the_gap'))

    def choose(self, ranges_of_angle):
        import math
        n = 181
        angles = [math.radians(-90 + k) for k in range(n)]
        ranges = [ranges_of_angle(a) for a in angles]
        return self.ftg.choose_direction(ranges, angles[0], math.radians(1), math.radians(180),
                                         3.0, 0.35, 1.0)

    def test_open_space_goes_ahead(self):
        direction, ahead = self.choose(lambda a: float('inf'))
        self.assertAlmostEqual(direction, 0.0, delta=0.02)
        self.assertEqual(ahead, 3.0)

    def test_wall_ahead_with_an_opening_on_the_left(self):
        import math
        # a wall 0.8 m ahead across the right half and the front; open from +30 deg leftwards
        direction, ahead = self.choose(lambda a: float('inf') if a > math.radians(30) else 0.8)
        self.assertGreater(direction, math.radians(30))
        self.assertAlmostEqual(ahead, 0.8)

    def test_no_gap(self):
        direction, _ = self.choose(lambda a: 0.5)
        self.assertIsNone(direction)

    def test_bubble_round_the_nearest_return(self):
        import math
        # open everywhere but a post 0.6 m away, 10 deg right: the gap is to its left
        direction, _ = self.choose(lambda a: 0.6 if abs(a - math.radians(-10)) < math.radians(3)
                                   else float('inf'))
        self.assertGreater(direction, math.radians(-10) + math.atan2(0.35, 0.6))


if __name__ == '__main__':
    unittest.main()
