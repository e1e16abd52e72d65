"""Scenario files of `batch`: strict validation with file and line, and the matrix expansion."""
import glob
import os
import sys
import unittest

from tianracer_bringup import scenario

# catkin runs nosetests with -P (no path adjustment): the test folder's helpers by path.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scenario_text import load_text  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SHIPPED = os.path.join(HERE, '..', 'scenarios')


def problems(text):
    try:
        _, path = load_text(text)
    except scenario.ScenarioError as e:
        return e.problems
    raise AssertionError('no error for:\n' + text)


class TestScenarioErrors(unittest.TestCase):
    def assertProblem(self, text, line, fragment):
        ps = problems(text)
        hits = [p for p in ps if p.split(':')[1] == str(line) and fragment in p]
        self.assertTrue(hits, 'expected line %d: %r in %s' % (line, fragment, ps))
        self.assertTrue(all(p.split(':')[0].endswith('s.yaml') for p in ps), ps)

    def test_unknown_key(self):
        self.assertProblem("""\
            base:
              world: empty
              duration: 5
              sensor: {lidar: true}
            """, 4, "unknown key 'sensor'")

    def test_unknown_nested_key(self):
        self.assertProblem("""\
            base:
              world: empty
              duration: 5
              spawn:
                x: 1
                z: 2
            """, 6, "unknown key 'z' in spawn")

    def test_unknown_top_level_key(self):
        self.assertProblem("""\
            base: {world: empty, duration: 5}
            matrix: {seed: [1]}
            runs: 3
            """, 3, "unknown top-level key 'runs'")

    def test_bad_type(self):
        self.assertProblem("""\
            base:
              world: empty
              duration: five
            """, 3, 'duration must be a number')
        self.assertProblem("""\
            base:
              world: empty
              duration: 5
              sensors: {lidar: 1}
            """, 4, 'sensors.lidar must be true or false')

    def test_bad_type_in_matrix(self):
        self.assertProblem("""\
            base: {world: empty, duration: 5}
            matrix:
              seed:
                - 1
                - two
            """, 5, 'matrix.seed[1] must be an integer')

    def test_empty_matrix_axis(self):
        self.assertProblem("""\
            base: {world: empty, duration: 5}
            matrix:
              seed: [1, 2]
              spawn.x: []
            """, 4, 'matrix.spawn.x is an empty list')

    def test_unknown_matrix_key(self):
        self.assertProblem("""\
            base: {world: empty, duration: 5}
            matrix:
              spawn.z: [1, 2]
            """, 3, "unknown matrix key 'spawn.z'")

    def test_missing_world(self):
        self.assertProblem("""\
            name: x
            base:
              duration: 5
            """, 2, "base has no 'world'")

    def test_world_file_not_found(self):
        self.assertProblem("""\
            base:
              duration: 5
              world: worlds/nowhere.world
            """, 3, "world file 'worlds/nowhere.world' not found")

    def test_world_not_shipped(self):
        self.assertProblem("""\
            base:
              duration: 5
              world: moon
            """, 3, "world 'moon' is neither a shipped world")

    def test_driver_needs_one_of_launch_or_command(self):
        self.assertProblem("""\
            base:
              world: empty
              duration: 5
              driver: {args: {speed: 1}}
            """, 4, 'driver needs exactly one of')

    def test_negative_reply_period(self):
        self.assertProblem("""\
            base:
              world: empty
              duration: 5
              driver:
                command: rosrun tianracer_bringup pure_pursuit
                reply_period: -0.02
            """, 6, 'driver.reply_period must be >= 0')

    def test_bad_metric(self):
        self.assertProblem("""\
            base:
              world: empty
              duration: 5
              metrics:
                - {name: v, topic: /tianracer/odom, field: twist.twist.linear.x, stat: median}
            """, 5, 'stat must be one of')

    def test_invalid_yaml(self):
        self.assertProblem("""\
            base:
              world: [empty
            """, 3, 'not valid YAML')

    def test_every_problem_reported(self):
        ps = problems("""\
            base:
              duration: x
              colour: red
            matrix:
              seed: []
            """)
        self.assertEqual(len(ps), 4, ps)


class TestExpansion(unittest.TestCase):
    def test_product_in_file_order(self):
        sc, _ = load_text("""\
            base:
              world: racetrack
              duration: 10
              driver: {command: rosrun tianracer_bringup pure_pursuit, args: {speed: 1.0}}
            matrix:
              driver.args.speed: [0.5, 1.0, 1.5]
              seed: [0, 1]
            """)
        self.assertEqual(len(sc.runs), 6)
        self.assertEqual([(r.config['driver']['args']['speed'], r.config['seed']) for r in sc.runs],
                         [(0.5, 0), (0.5, 1), (1.0, 0), (1.0, 1), (1.5, 0), (1.5, 1)])
        self.assertEqual(sc.runs[3].id, 'run_003')
        self.assertEqual(sc.runs[3].label, 'driver.args.speed=1.0, seed=1')
        # defaults
        c = sc.runs[0].config
        self.assertEqual(c['sensors'], {'lidar': False, 'camera': False, 'depth': False})
        self.assertEqual(c['spawn'], {'x': 0.0, 'y': 0.0, 'yaw': 0.0})
        self.assertEqual(c['real_time_factor'], 0.0)
        self.assertEqual(c['driver']['command'], ['rosrun', 'tianracer_bringup', 'pure_pursuit'])
        self.assertEqual(scenario.run_timeout(c), 60.0 + 5 * 10)

    def test_no_matrix_is_one_run(self):
        sc, _ = load_text("base: {world: empty, duration: 3}\n")
        self.assertEqual(len(sc.runs), 1)
        self.assertEqual(sc.runs[0].label, 'base')

    def test_lockstep_parameters(self):
        """At real_time_factor 0 the simulator waits for the driver's ready_topic each
        reply_period and for the controller commands; otherwise, or with reply_period 0, not."""
        sc, _ = load_text("""\
            base:
              world: empty
              duration: 5
              driver: {command: rosrun tianracer_bringup pure_pursuit}
            matrix:
              real_time_factor: [0, 2]
              driver.reply_period: [0.025, 0]
            """)
        got = [scenario.lockstep(r.config) for r in sc.runs]
        self.assertEqual(got[0], {'replies': '/cmd_vel /cmd_vel_node/received', 'reply_period': 0.025,
                                  'ticks': 'commands'})
        self.assertEqual(got[1:], [{}, {}, {}])
        # A driver that answers elsewhere than the cmd_vel node: its topic alone.
        sc, _ = load_text("""\
            base:
              world: empty
              duration: 5
              real_time_factor: 0
              driver: {command: my_driver, ready_topic: /tianracer/left_rear_wheel_velocity_controller/command}
            """)
        self.assertEqual(scenario.lockstep(sc.runs[0].config)['replies'],
                         '/tianracer/left_rear_wheel_velocity_controller/command')
        sc, _ = load_text("base: {world: empty, duration: 3}\n")
        self.assertEqual(scenario.lockstep(sc.runs[0].config), {})

    def test_shipped_scenarios_load(self):
        files = sorted(glob.glob(os.path.join(SHIPPED, '*.yaml')))
        self.assertGreaterEqual(len(files), 3)
        for path in files:
            sc = scenario.load(path)
            self.assertGreater(len(sc.runs), 1, path)


if __name__ == '__main__':
    unittest.main()
