"""A lap of the racetrack driven through the cmd_vel node in lockstep (real_time_factor 0), twice
(two runs of one batch on a local Ray with 2 CPUs, at the same time): the car's final state, the
wheel odometry and the last steering command agree bit for bit, and so do the paths and lap
times. In lockstep the simulator waits for the cmd_vel node's echo of each command it took
(~received) before it publishes the step's /clock: without it, the node could take a step's
/clock before the driver's /cmd_vel (two connections are not ordered) and the runs part."""
import json
import os
import shutil
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from test_batch_run import batch, batch_processes, rows_of  # noqa: E402

METRICS = ['x', 'y', 'qz', 'qw', 'vx', 'wz', 'odom_x', 'steer']


class TestCmdVelLockstep(unittest.TestCase):
    def test_lap_twice_bit_identical(self):
        tmp = tempfile.mkdtemp(prefix='test_cmd_vel_lockstep_')
        try:
            out = os.path.join(tmp, 'out')
            code, log = batch('lap_twice.yaml', out)
            self.assertEqual(code, 0, log)
            a, b = rows_of(out, log)
            self.assertEqual((a['completed'], b['completed']), ('True', 'True'), (a, b))
            self.assertEqual(a['laps'], '1', a)
            metrics = []
            for run in ('run_000', 'run_001'):
                with open(os.path.join(out, 'runs', run, 'result.json')) as f:
                    metrics.append(json.load(f)['metrics'])
            ma, mb = metrics
            for name in METRICS:
                self.assertIsInstance(ma[name], float, name)
                # JSON keeps a double's every bit (repr round-trips).
                self.assertEqual(ma[name].hex(), mb[name].hex(), '%s: %r != %r' % (name, ma[name], mb[name]))
            self.assertGreater(ma['vx'], 1.0)  # still driving at the end
            self.assertEqual(ma['path'], mb['path'])
            self.assertEqual(ma['lap_times'], mb['lap_times'])
            self.assertEqual(batch_processes(tmp), [])
        finally:
            shutil.rmtree(tmp, ignore_errors=True)


if __name__ == '__main__':
    unittest.main()
