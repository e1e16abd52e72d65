"""A lap of the racetrack driven through the cmd_vel node in lockstep (real_time_factor 0), twice
(two runs of one batch on a local Ray with 2 CPUs, at the same time): the extremes of the car's
ground-truth position and yaw rate and of the steering command agree bit for bit, and so do the
paths (0.1 mm) and lap times. In lockstep the simulator waits for the cmd_vel node's echo of each command it took
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

METRICS = ['x_max', 'x_min', 'y_max', 'y_min', 'wz_max', 'wz_min', 'steer_max', 'steer_min']
END_MARGIN = 0.1  # s: the last ground-truth messages before the end may reach the recorder or not


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
            self.assertGreater(ma['x_max'] - ma['x_min'], 3.0)  # a lap, not a car standing still
            self.assertGreater(ma['steer_max'], 0.1)
            path_a, path_b = [[p for p in m['path'] if p[0] <= 16.0 - END_MARGIN] for m in (ma, mb)]
            self.assertGreater(len(path_a), 700)
            self.assertEqual(path_a, path_b)
            self.assertEqual(ma['lap_times'], mb['lap_times'])
            self.assertEqual(batch_processes(tmp), [])
        finally:
            shutil.rmtree(tmp, ignore_errors=True)


if __name__ == '__main__':
    unittest.main()
