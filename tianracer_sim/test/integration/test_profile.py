#!/usr/bin/env python3
"""rostest: ~profile:=true times each part of the sim node's step.

The ~profile service (std_srvs/Trigger) answers a table: one row per part (Bullet, the
controllers, the contact scan, each publication with its conversion and its serialisation,
each sensor's cast, the frame worker's renders and read-backs) with microseconds per step and
calls per step; the Bullet and controller rows run once per step, the lidar's cast 40 times per
sim second; contacts, read by nobody here, are not tracked. At exit the node prints the table.
The start-up line gives each part of the node's start with its time, and the first step's.
(Without ~profile the node offers no such service: test_step checks.)
"""
import re
import signal
import subprocess
import tempfile
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Image, JointState, LaserScan
from std_srvs.srv import Trigger
from tianracer_sim.sim_time import Stream, clock_stamp, wait_for

from sim_node_binary import node_binary


def rows(table):
    """{row name: (us per step, calls per step, us per call)} of the service's table."""
    out = {}
    for line in table.splitlines():
        cells = [c.strip() for c in line.split('|')]
        if len(cells) == 4 and re.match(r'^[0-9.]+$', cells[1]):
            out[cells[0]] = tuple(float(c) for c in cells[1:])
    return out


class Profile(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_profile')
        cls.clock = Stream('/clock', Clock, stamp=clock_stamp)
        # Subscribed, so that the node publishes and casts them (nothing is made for nobody).
        cls.scan = Stream('/scan', LaserScan)
        cls.joint_states = Stream('/tianracer/joint_states', JointState)
        cls.image = Stream('/rrbot/camera1/image_raw', Image)
        cls.output = tempfile.TemporaryFile()
        cls.proc = subprocess.Popen(
            [node_binary(), '__name:=tianracer_sim', '_world:=walled_room',
             '_real_time_factor:=0', '_profile:=true'],
            stdout=cls.output, stderr=subprocess.STDOUT)

    @classmethod
    def tearDownClass(cls):
        if cls.proc.poll() is None:
            cls.proc.kill()
            cls.proc.wait()

    def node_output(self):
        self.output.seek(0)
        return self.output.read().decode(errors='replace')

    def test_1_the_service_answers_the_table(self):
        try:
            rospy.wait_for_service('/tianracer_sim/profile', timeout=60)
        except rospy.ROSException:
            self.fail('no ~profile service:\n' + self.node_output())
        # Two seconds of sim time with the sensors' topics subscribed.
        self.scan.first_stamped(2.0)
        self.image.first_stamped(2.0)
        self.joint_states.first_stamped(2.0)
        answer = rospy.ServiceProxy('/tianracer_sim/profile', Trigger)()
        self.assertTrue(answer.success)
        table = rows(answer.message)
        rospy.loginfo('~profile:\n%s', answer.message)
        steps = int(re.search(r'^(\d+) steps$', answer.message, re.M).group(1))
        self.assertGreater(steps, 2000)
        for name in ('step (all of it)', 'physics: Bullet stepSimulation', 'physics: controllers',
                     'sensor lidar: update'):
            self.assertIn(name, table, answer.message)
            self.assertAlmostEqual(table[name][1], 1.0, places=3, msg=name)
        # Nobody reads contacts (no contacts topic or /diagnostics subscriber): not tracked.
        self.assertNotIn("contacts: scan of the step's manifolds", table, answer.message)
        for name in ('ros: joint_states', 'ros: joint_states / convert',
                     'ros: joint_states / serialise and send', 'ros: /clock',
                     'sensor lidar: publish / serialise and send',
                     'frame worker: camera render', 'frame worker: renders / glReadPixels'):
            self.assertIn(name, table, answer.message)
        # Parts of a row are indented.
        lines = answer.message.splitlines()
        self.assertIn('  ros: joint_states / convert', [l[:len('  ros: joint_states / convert')] for l in lines])
        self.assertIn('ros: joint_states ', [l[:len('ros: joint_states ')] for l in lines])
        # joint_states at 50 Hz, /clock at 200 Hz, the lidar at 40 Hz of a 1 ms step.
        self.assertAlmostEqual(table['ros: joint_states'][1], 1.0, places=3)  # timed every step
        # (Sent and cast only once this node subscribed: at most 50 and 40 per sim second.)
        self.assertGreater(table['ros: joint_states / serialise and send'][1], 0.0)
        self.assertLessEqual(table['ros: joint_states / serialise and send'][1], 0.0505)
        self.assertAlmostEqual(table['ros: /clock'][1], 0.2, delta=0.01)
        self.assertGreater(table['sensor lidar: sample (cast, measure)'][1], 0.0)
        self.assertLessEqual(table['sensor lidar: sample (cast, measure)'][1], 0.0405)
        self.assertGreater(table['physics: Bullet stepSimulation'][0], 0.0)
        outside = float(re.search(r'^step outside Bullet\s*\|\s*([0-9.]+)', answer.message,
                                  re.M).group(1))
        self.assertGreater(outside, 0.0)
        self.assertLess(outside, table['step (all of it)'][0] + 1e-3 +
                        sum(v[0] for k, v in table.items() if k.startswith('between steps')))

    def test_1b_profile_table_prints_it_plainly(self):
        # The same table as the service's message, as lines, not one escaped YAML string.
        out = subprocess.run(['rosrun', 'tianracer_sim', 'profile_table'], capture_output=True,
                             text=True, timeout=60)
        self.assertEqual(out.returncode, 0, out.stderr)
        table = rows(out.stdout)
        self.assertIn('physics: Bullet stepSimulation', table, out.stdout)
        self.assertRegex(out.stdout, r'(?m)^\d+ steps$')
        # A node that does not profile: the reason, exit 1.
        bad = subprocess.run(['rosrun', 'tianracer_sim', 'profile_table', '/no_such_node'],
                             capture_output=True, text=True, timeout=60)
        self.assertEqual(bad.returncode, 1)
        self.assertIn('no service /no_such_node/profile', bad.stderr)

    def test_2_the_table_is_logged_at_exit(self):
        self.proc.send_signal(signal.SIGINT)
        code = self.proc.wait(timeout=20)
        out = self.node_output()
        self.assertEqual(code, 0, 'exit code %d after SIGINT:\n%s' % (code, out))
        self.assertIn('step profile (~profile):', out)
        self.assertIn('physics: Bullet stepSimulation', out)
        # The start-up line (logged whether profiling or not): each part with its time.
        m = re.search(r"start-up: world file and its meshes ([0-9.]+) ms, simulator .* ([0-9.]+) ms, "
                      r"robot 'tianracer': URDF and meshes ([0-9.]+) ms, robot 'tianracer': physics, "
                      r"controllers, sensors \(GL context\), topics ([0-9.]+) ms, Gazebo interface, "
                      r"lockstep, services ([0-9.]+) ms; ([0-9.]+) ms in all", out)
        self.assertIsNotNone(m, out)
        parts = [float(x) for x in m.groups()]
        self.assertAlmostEqual(sum(parts[:-1]), parts[-1], delta=0.5)
        self.assertRegex(out, r'first step: [0-9.]+ ms')


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'profile', Profile)
