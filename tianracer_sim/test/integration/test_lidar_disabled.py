#!/usr/bin/env python3
"""rostest: with DISABLE_GAZEBO_LASER=true (set for xacro by lidar_disabled.test) the robot
description has no ray sensor; the sim runs (clock, joint_states) without advertising /scan,
and neither its output nor /rosout carries an ERROR or FATAL line.

This node starts tianracer_sim_node itself, so that it reads all of the node's output: lines
logged at start-up, before the node's /rosout publisher is connected, never reach /rosout.
"""
import re
import signal
import subprocess
import tempfile
import threading
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Clock, Log
from sensor_msgs.msg import JointState
from tianracer_sim.sim_time import Stream, clock_stamp, lossless, sim_sleep, wait_for

from sim_node_binary import node_binary


class LidarDisabled(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_lidar_disabled')
        cls.lock = threading.Lock()
        cls.bad_logs = []
        cls.clock = Stream('/clock', Clock, stamp=clock_stamp)
        cls.joint_states = Stream('/tianracer/joint_states', JointState)
        lossless(rospy.Subscriber('/rosout_agg', Log, cls.on_log))
        cls.output = tempfile.TemporaryFile()
        cls.proc = subprocess.Popen(
            [node_binary(), '__name:=tianracer_sim', '_world:=walled_room',
             '_real_time_factor:=1.0'],
            stdout=cls.output, stderr=subprocess.STDOUT)
        try:
            wait_for(lambda: cls.proc.poll() is not None or cls.clock.count() > 20,
                     'the sim started by the test')
        except AssertionError:
            pass  # test_2 reports it with the node's output

    @classmethod
    def tearDownClass(cls):
        if cls.proc.poll() is None:
            cls.proc.send_signal(signal.SIGINT)
            try:
                cls.proc.wait(timeout=15)
            except subprocess.TimeoutExpired:
                cls.proc.kill()
                cls.proc.wait()

    @classmethod
    def on_log(cls, msg):
        if msg.level >= Log.ERROR and 'tianracer_sim' in msg.name:
            with cls.lock:
                cls.bad_logs.append('%s: %s' % (msg.name, msg.msg))

    def node_output(self):
        self.output.seek(0)
        return self.output.read().decode(errors='replace')

    def test_1_description_has_no_lidar(self):
        urdf = rospy.get_param('/robot_description')
        self.assertIn('<robot', urdf)
        self.assertNotIn('hokuyo', urdf)
        self.assertNotIn('type="ray"', urdf)
        self.assertIn('type="camera"', urdf)  # the rest of the gazebo extensions are there

    def test_2_runs_without_scan(self):
        self.assertIsNone(self.proc.poll(), 'the sim exited:\n' + self.node_output())
        self.assertGreater(self.clock.count(), 20, 'no /clock:\n' + self.node_output())
        t0 = self.clock.latest_stamp()
        t1 = self.clock.first(lambda s, m: s >= t0 + 1.0 - 1e-6, '1 s of sim time',
                              self.clock.count() - 1)[1]
        self.joint_states.first_stamped(t1)
        js = self.joint_states.between(t0, t1)
        rospy.loginfo('clock %.3f -> %.3f, %d joint_states in between', t0, t1, len(js))
        self.assertGreaterEqual(t1 - t0, 1.0 - 1e-6)  # float sum of clock stamps
        self.assertGreater(len(js), 40)  # 50 Hz
        topics = [t for t, _ in rospy.get_published_topics()]
        self.assertIn('/tianracer/joint_states', topics)
        self.assertIn('/rrbot/camera1/image_raw', topics)
        self.assertNotIn('/scan', topics)
        self.assertFalse([t for t in topics if 'scan' in t], topics)

    def test_3_nothing_logs_an_error(self):
        sim_sleep(0.5)
        self.assertIsNone(self.proc.poll(), 'the sim exited:\n' + self.node_output())
        with self.lock:
            self.assertEqual(self.bad_logs, [])
        # Stop it: its stdout goes to a file, fully buffered until it exits.
        self.proc.send_signal(signal.SIGINT)
        code = self.proc.wait(timeout=20)
        out = self.node_output()
        self.assertEqual(code, 0, 'exit code %d after SIGINT:\n%s' % (code, out))
        self.assertIn('robot \'tianracer\'', out)  # its start-up lines are there
        bad = [line for line in out.splitlines() if re.search(r'\b(ERROR|FATAL)\b', line)]
        self.assertEqual(bad, [], 'the sim logged errors:\n' + out)
        warnings = [line for line in out.splitlines() if 'WARN' in line]
        rospy.loginfo('sim output: %d lines, %d warnings, none about a lidar: %s',
                      len(out.splitlines()), len(warnings),
                      not [w for w in warnings if 'lidar' in w or 'ray' in w])
        self.assertFalse([w for w in warnings if 'hokuyo' in w or 'scan' in w], warnings)

if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'lidar_disabled', LidarDisabled)
