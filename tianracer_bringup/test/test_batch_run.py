"""`rosrun tianracer_bringup batch` end to end on a local Ray with 2 CPUs: a 4-run batch twice
(same outcomes, distances within 1 %), and a batch with a failing and a hanging driver."""
import csv
import os
import shutil
import subprocess
import tempfile
import unittest

from tianracer_bringup.run import TOKEN_VAR

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, 'test_batch_data')
DURATION = 5.0  # sim seconds of each run of four_runs.yaml


def batch(scenario, out, *extra):
    env = dict(os.environ)
    env['PATH'] = '/usr/bin:' + env.get('PATH', '')
    cmd = ['rosrun', 'tianracer_bringup', 'batch', os.path.join(DATA, scenario), '--out', out,
           '--cpus', '2', '--no-progress'] + list(extra)
    p = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=600)
    return p.returncode, p.stdout.decode(errors='replace')


def rows_of(out, log=''):
    path = os.path.join(out, 'results.csv')
    if not os.path.exists(path):
        raise AssertionError('the batch wrote no %s; its output ends:\n%s' % (path, log[-3000:]))
    with open(path) as f:
        return list(csv.DictReader(f))


def batch_processes(root):
    """pids of live processes that a batch run under `root` started: they carry a run token,
    and their ROS_HOME is in the run's folder (other batches on the machine, e.g. another
    checkout's tests, have theirs elsewhere)."""
    out = []
    needle = TOKEN_VAR.encode() + b'='
    home = b'ROS_HOME=' + os.path.realpath(root).encode()
    for entry in os.listdir('/proc'):
        if not entry.isdigit():
            continue
        try:
            with open('/proc/%s/environ' % entry, 'rb') as f:
                env = f.read().split(b'\0')
            if any(v.startswith(needle) for v in env) and any(v.startswith(home) for v in env):
                with open('/proc/%s/cmdline' % entry, 'rb') as g:
                    out.append((int(entry), g.read().replace(b'\0', b' ').decode(errors='replace')))
        except OSError:
            pass
    return out


class TestBatch(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix='test_batch_')

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_four_runs_twice(self):
        outs = [os.path.join(self.tmp, 'a'), os.path.join(self.tmp, 'b')]
        results = []
        for out in outs:
            code, log = batch('four_runs.yaml', out)
            self.assertEqual(code, 0, log)
            rows = rows_of(out, log)
            self.assertEqual(len(rows), 4, log)
            for name in ('report.md', 'paths_empty.png', 'metrics_vs_driver_args_speed.png',
                         'metrics_vs_spawn_x.png'):
                self.assertTrue(os.path.getsize(os.path.join(out, name)) > 0, name)
            for r in rows:
                self.assertEqual(r['status'], 'ok', r)
                self.assertEqual(r['completed'], 'True', r)
                self.assertAlmostEqual(float(r['sim_time']), DURATION, delta=0.05)
                # the duration at the commanded speed, less the start
                self.assertGreater(float(r['distance']),
                                   0.7 * DURATION * float(r['driver.args.speed']), r)
                self.assertLess(float(r['distance']), DURATION * float(r['driver.args.speed']), r)
                self.assertEqual(r['leftover_processes'], '0')
            results.append(rows)
        self.assertEqual(batch_processes(self.tmp), [])
        for a, b in zip(*results):
            self.assertEqual(a['label'], b['label'])
            self.assertEqual((a['completed'], a['collisions']), (b['completed'], b['collisions']))
            self.assertAlmostEqual(float(a['distance']), float(b['distance']),
                                   delta=0.01 * float(a['distance']))
        md = open(os.path.join(outs[0], 'report.md')).read()
        self.assertIn('## By driver.args.speed', md)
        self.assertIn('## By spawn.x', md)

    def test_failing_and_hanging_runs(self):
        out = os.path.join(self.tmp, 'failures')
        code, log = batch('failures.yaml', out)
        self.assertEqual(code, 1, log)
        rows = rows_of(out, log)
        self.assertEqual(len(rows), 3, log)
        good, broken, hung = rows
        self.assertEqual(good['status'], 'ok', good)
        self.assertEqual(good['completed'], 'True', good)
        self.assertEqual(broken['status'], 'failed')
        self.assertIn('the driver exited with code 1', broken['reason'])
        self.assertEqual(hung['status'], 'failed')
        self.assertIn('timed out after 30 s wall while waiting for the driver to publish /cmd_vel',
                      hung['reason'])
        md = open(os.path.join(out, 'report.md')).read()
        self.assertIn('### run_001', md)
        self.assertIn('not_declared', md)  # roslaunch's message in the log tail
        self.assertIn('### run_002', md)
        self.assertIn('$ sleep 600', md)  # the hanging driver's log
        self.assertNotIn('### run_000', md)
        self.assertEqual(batch_processes(self.tmp), [])

    def test_collision_with_a_wall(self):
        out = os.path.join(self.tmp, 'wall')
        code, log = batch('wall_ahead.yaml', out)
        self.assertEqual(code, 1, log)  # the run ran, and missed no_collision
        row, = rows_of(out, log)
        self.assertEqual(row['status'], 'ok', row)
        self.assertEqual(row['completed'], 'False', row)
        self.assertEqual(row['first_collision_with'], 'box_front::link', row)
        self.assertIn('collided with box_front::link', row['reason'])
        # Ground truth: the car is stopped by the box; contact is when its speed (finite
        # differences of the 50 Hz ground-truth path) first falls below half the cruise speed.
        import json
        with open(os.path.join(out, 'runs', 'run_000', 'result.json')) as f:
            path = json.load(f)['metrics']['path']
        t_contact = None
        cruising = False
        for (t0, x0, y0), (t1, x1, y1) in zip(path, path[1:]):
            v = ((x1 - x0) ** 2 + (y1 - y0) ** 2) ** 0.5 / (t1 - t0)
            cruising = cruising or v > 0.9
            if cruising and v < 0.5:
                t_contact = t0
                break
        self.assertIsNotNone(t_contact, 'the car never stopped at the box')
        self.assertAlmostEqual(float(row['first_collision_time']), t_contact, delta=0.05)
        self.assertEqual(batch_processes(self.tmp), [])

    def test_scenario_error_starts_nothing(self):
        out = os.path.join(self.tmp, 'invalid')
        bad = os.path.join(self.tmp, 'bad.yaml')
        with open(bad, 'w') as f:
            f.write('base:\n  world: empty\n  duration: 5\n  speed: 3\n')
        env = dict(os.environ, PATH='/usr/bin:' + os.environ.get('PATH', ''))
        p = subprocess.run(['rosrun', 'tianracer_bringup', 'batch', bad, '--out', out], env=env,
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60)
        self.assertEqual(p.returncode, 2)
        self.assertIn("bad.yaml:4: unknown key 'speed' in base", p.stdout.decode())
        self.assertFalse(os.path.exists(out))

    def test_dry_run(self):
        env = dict(os.environ, PATH='/usr/bin:' + os.environ.get('PATH', ''))
        p = subprocess.run(['rosrun', 'tianracer_bringup', 'batch', os.path.join(DATA, 'four_runs.yaml'),
                            '--dry-run', '--limit', '3', '--duration', '2'], env=env,
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60)
        text = p.stdout.decode()
        self.assertEqual(p.returncode, 0, text)
        self.assertIn('four_runs: 3 run(s) of 4', text)
        self.assertIn('run_002  driver.args.speed=1.0, spawn.x=0.0', text)
        self.assertIn('2 s', text)


if __name__ == '__main__':
    unittest.main()
