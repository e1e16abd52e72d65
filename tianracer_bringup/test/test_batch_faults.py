"""`batch` when things break under it: a simulator that crashes (SIGSEGV) or hangs (SIGSTOP)
mid-run is reported failed with its log and the batch goes on; on a Ray cluster of 2 worker nodes
(ray.cluster_utils.Cluster, one machine, 1 CPU each), a worker node killed mid-batch loses its
run, which is submitted again: every run gets one result, the retried one marked, the report says
what happened, and the lost attempt's processes are gone."""
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, 'test_batch_data')
sys.path.insert(0, HERE)
from test_batch_run import batch_processes, rows_of  # noqa: E402


def batch_cmd(scenario, out, *extra):
    return ['rosrun', 'tianracer_bringup', 'batch', scenario, '--out', out, '--no-progress'] + list(extra)


def batch_env():
    env = dict(os.environ)
    env['PATH'] = '/usr/bin:' + env.get('PATH', '')
    env.setdefault('RAY_AUTH_MODE', 'disabled')
    return env


class TestBatchFaults(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix='test_batch_faults_')

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def scenario(self, name, text):
        path = os.path.join(self.tmp, name)
        with open(path, 'w') as f:
            f.write(text)
        return path

    def test_simulator_crash_and_hang(self):
        driver = os.path.join(DATA, 'sim_fault_driver.py')
        sc = self.scenario('sim_faults.yaml', '''name: sim_faults
base:
  world: empty
  duration: 5
  timeout: 30
  driver: {command: %s, args: {at: 1.0}, reply_period: 0}
matrix:
  driver.args.fault: [crash, hang]
''' % driver)
        out = os.path.join(self.tmp, 'sim_faults')
        p = subprocess.run(batch_cmd(sc, out, '--cpus', '2'), env=batch_env(), stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, timeout=600)
        log = p.stdout.decode(errors='replace')
        self.assertEqual(p.returncode, 1, log)
        crashed, hung = rows_of(out, log)
        self.assertEqual(crashed['status'], 'failed', crashed)
        self.assertRegex(crashed['reason'], r'^the simulator node \(pid \d+\) died: exit code -11 '
                                            r'\(SIGSEGV\) \(while running\)$')
        self.assertEqual(hung['status'], 'failed', hung)
        self.assertEqual(hung['reason'],
                         'timed out after 30 s wall while waiting for the run to reach 5 s of sim time')
        md = open(os.path.join(out, 'report.md')).read()
        self.assertIn('### run_000 (driver.args.fault=crash)', md)
        self.assertIn('### run_001 (driver.args.fault=hang)', md)
        self.assertIn('sending SIGSEGV to the simulator', md)  # the driver's log tail
        self.assertIn('sending SIGSTOP to the simulator', md)
        self.assertIn('exit code -11', md)  # roslaunch's line in the simulator launch's tail
        self.assertEqual(batch_processes(self.tmp), [])

    def test_dead_node(self):
        from ray.cluster_utils import Cluster
        os.environ.setdefault('RAY_AUTH_MODE', 'disabled')
        # The head takes no runs (killing it would end the cluster); two workers of 1 CPU.
        cluster = Cluster(initialize_head=True, head_node_args={'num_cpus': 0})
        try:
            workers = [cluster.add_node(num_cpus=1) for _ in range(2)]
            cluster.wait_for_nodes()
            sc = self.scenario('dead_node.yaml', '''name: dead_node
base:
  world: empty
  duration: 8
  timeout: 120
  real_time_factor: 0
  params: {/cmd_vel_node/cmd_timeout: 0}
  driver: {command: rosrun tianracer_bringup pure_pursuit, args: {speed: 1.0}}
  success: {no_collision: true}
matrix:
  driver.args.speed: [0.5, 1.0, 1.5]
''')
            out = os.path.join(self.tmp, 'dead_node')
            log_path = os.path.join(self.tmp, 'dead_node.log')
            with open(log_path, 'w') as log_file:
                proc = subprocess.Popen(batch_cmd(sc, out, '--address', cluster.address),
                                        env=batch_env(), stdout=log_file, stderr=subprocess.STDOUT)
            # Mid-batch: both workers are running a run (each has unpaused its simulator, and
            # neither has finished); a worker node is then killed with its run.
            runs = os.path.join(out, 'runs')
            deadline = time.time() + 300
            while True:
                self.assertIsNone(proc.poll(), open(log_path).read())
                self.assertLess(time.time(), deadline, open(log_path).read())
                running = [r for r in (os.listdir(runs) if os.path.isdir(runs) else [])
                           if os.path.exists(os.path.join(runs, r, 'recorder.go'))
                           and not os.path.exists(os.path.join(runs, r, 'metrics.json'))]
                if len(running) == 2:
                    break
                time.sleep(0.1)
            cluster.remove_node(workers[0], allow_graceful=False)
            code = proc.wait(600)
            log = open(log_path).read()
        finally:
            cluster.shutdown()
        print(log)
        self.assertEqual(code, 0, log)
        rows = rows_of(out, log)
        self.assertEqual([r['id'] for r in rows], ['run_000', 'run_001', 'run_002'])
        for r in rows:
            self.assertEqual(r['completed'], 'True', r)
            self.assertAlmostEqual(float(r['sim_time']), 8.0, delta=0.05)
        retried = [r for r in rows if r['attempts'] != '1']
        self.assertEqual(len(retried), 1, rows)
        self.assertEqual(retried[0]['attempts'], '2')
        self.assertIn(retried[0]['id'], running)
        with open(os.path.join(runs, retried[0]['id'], 'result.json')) as f:
            res = json.load(f)
        self.assertEqual(res['attempt'], 2)
        self.assertEqual(res['run_dir'], os.path.join(runs, retried[0]['id'], 'retry_2'))
        lost, = res['lost_attempts']
        self.assertEqual(lost['attempt'], 1)
        self.assertRegex(lost['error'], r'^(NodeDiedError|WorkerCrashedError|LocalRayletDiedError)')
        md = open(os.path.join(out, 'report.md')).read()
        print(md)
        self.assertIn('## Lost and retried runs', md)
        self.assertIn('| %s | 1 |' % retried[0]['id'], md)
        self.assertIn('retried: attempt 2 completed', md)
        self.assertIn('3 runs: 3 completed', md)
        self.assertIn('%s: attempt 1 lost after' % retried[0]['id'], log)
        # The lost attempt's processes (master, simulator, driver) were killed by its guard.
        deadline = time.time() + 10
        while batch_processes(self.tmp) and time.time() < deadline:
            time.sleep(0.2)
        self.assertEqual(batch_processes(self.tmp), [])


if __name__ == '__main__':
    unittest.main()
