"""The examples run (tiny budgets): the spaces printout, the learner, the benchmark."""
import os
import subprocess
import sys
import tempfile
import unittest


# catkin runs nosetests with -P (no path adjustment): the test folder's helpers by path.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import support

EXAMPLES = os.path.join(support.REPO, 'examples')


def run(script, *args, timeout=600):
    return subprocess.run([sys.executable, os.path.join(EXAMPLES, script)] + list(args),
                          capture_output=True, text=True, timeout=timeout)


class Examples(unittest.TestCase):
    def test_gym_random(self):
        r = run('gym_random.py', '--steps', '50')
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn('observation space', r.stdout)
        self.assertIn('action space', r.stdout)
        self.assertIn('per env step', r.stdout)

    def test_the_learner_writes_its_pictures(self):
        with tempfile.TemporaryDirectory() as out:
            r = run('gym_cem.py', '--iterations', '2', '--population', '4', '--episode-time', '1.0',
                    '--out', out)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertTrue(os.path.getsize(os.path.join(out, 'learning_curve.png')) > 1000)
            self.assertTrue(os.path.getsize(os.path.join(out, 'learning_lap.png')) > 1000)

    def test_the_benchmark_prints_its_table(self):
        r = run('gym_bench.py', '--steps', '20', '--quick')
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn('env-steps/s', r.stdout)
        # Last, the one figure issue 41 asks for, in its form.
        self.assertRegex(r.stdout.strip().splitlines()[-1], r'^1 env \+ lidar: [1-9]\d* env-steps/s$')


if __name__ == '__main__':
    unittest.main()
